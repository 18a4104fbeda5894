#pragma once
// Syntax tree of a model file, before names are resolved and loops expanded.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eomgen/base/source_location.hpp"
#include "eomgen/mechanics/dimension.hpp"

namespace eomgen::syntax {

struct Expr;
using ExprPtr = std::shared_ptr<const Expr>;

/// The words that begin or structure statements (docs/model-language.md, "Keywords"): a name
/// that is one of them would read as the statement it names.
inline bool is_keyword(const std::string& word) {
  static const char* const keywords[] = {
      "model",  "description", "const",   "parameter", "coordinate", "input",      "frame",
      "point",  "particle",    "body",    "gravity",   "force",      "moment",     "spring",
      "damper", "torsion",     "potential", "generalized_force", "constraint", "roll", "wheel",
      "shape", "independent", "output", "for",     "in",        "end"};
  for (const char* k : keywords)
    if (word == k) return true;
  return false;
}

/// An identifier, possibly with `{expression}` pieces filled in per loop iteration: q{i-1}.
struct Name {
  struct Piece {
    std::string literal;  // used when index is null
    ExprPtr index;
  };
  std::vector<Piece> pieces;
  SourceLocation location;
  bool is_plain() const { return pieces.size() == 1 && !pieces[0].index; }
  std::string plain() const { return pieces.empty() ? std::string() : pieces[0].literal; }
};

struct Expr {
  /// sum and product are flat, one node for `a + b - c + ...`: a sum of any length is then a
  /// loop, not a recursion as deep as it is long.
  /// text: a string in double quotes, which only an argument's value can be (a mesh's file)
  enum class Kind { number, name, negate, sum, product, power, call, list, in_frame, basis, text };
  /// The operator before an operand of a sum (+, or - when inverse) or a product (*, or /).
  struct Operation {
    bool inverse = false;
    SourceLocation location;
  };
  Kind kind;
  SourceLocation location;    // sum and product: their first operator
  std::string number_text;    // number; text: the string's contents
  Name name;                  // name, call (function), in_frame and basis (frame)
  int basis_index = 0;        // basis: 1, 2 or 3
  std::vector<ExprPtr> args;  // operands, call arguments, list elements; in_frame: the list
  std::vector<Operation> operations;  // sum, product: the operator before args[1], args[2], ...
};

/// How deeply expressions may nest: parentheses, calls, brackets, prefix signs and powers
/// (a^b^c) each add a level. Deeper input is refused where it crosses the limit, before any
/// recursion over the tree could exhaust the stack.
inline constexpr int max_expression_depth = 100;
/// How deeply `for` loops may nest.
inline constexpr int max_loop_depth = 32;
/// How large loops may make a model: iterations plus the tokens of every statement they repeat.
/// A chain of 1,000 links is about 100,000; nested loops of 100,000 iterations each would
/// otherwise run for hours or exhaust memory.
inline constexpr std::size_t max_expanded_tokens = 2000000;
/// How many frames and points a definition may wait for: one defined from one later in the
/// file is built first, recursively (a chain of 20,000 written backwards overflowed the stack).
inline constexpr std::size_t max_definitions_ahead = 256;
/// The largest model text accepted, in bytes. Hand-written models are a few KB; loops make
/// large ones.
inline constexpr std::size_t max_model_bytes = 4u << 20;

/// Where an expression starts. An operator node sits at its operator, which is right for
/// "cannot add ..." but not for a message about the whole expression ("expected a vector").
const SourceLocation& start_of(const Expr& e);

struct Argument {
  std::string key;
  ExprPtr value;
  SourceLocation location;
};

/// A unit in brackets after a parameter, coordinate or input: [kg m^2], [N s/m], [-].
struct Unit {
  std::string text;         // as written, without the brackets and outer spaces
  SourceLocation location;  // of the '['
  Dimension dimension;
};

struct Statement {
  enum class Kind { model, description, constant, parameter, coordinate, input, frame, point, particle,
                    body, gravity, force, moment, spring, damper, torsion, potential, generalized_force,
                    constraint, roll, wheel, shape, independent, output, loop };
  Kind kind;
  SourceLocation location;  // of the keyword
  Name name;                // the declared name (most statements)
  std::vector<Name> names;  // coordinate, input and independent-speed lists
  std::vector<std::optional<Unit>> units;  // coordinate and input: one per name
  std::optional<Unit> unit;  // parameter
  ExprPtr value;            // `= EXPR`; constraint left side; loop first value
  ExprPtr value2;           // constraint right side; loop last value
  std::string text;         // model description
  std::vector<Argument> arguments;  // NAME(key = value, ...); shape: KIND(key = value, ...)
  Name shape_kind;          // shape: sphere, box, cylinder, disk, rod or mesh, as written
  Name frame;               // output ... in FRAME, constraint ... in FRAME
  bool has_frame = false;
  std::vector<Statement> body;  // loop body
  std::size_t token_count = 0;  // tokens the statement spans (a loop: its header): its share of the
                                // work once loops repeat it
};

/// Parses the text of a model file. \throws SourceError.
std::vector<Statement> parse_statements(const std::string& text, const std::string& file);

/// Parses one expression (used for `{...}` pieces of names). \throws SourceError.
ExprPtr parse_expression_text(const std::string& text, const SourceLocation& start);

}  // namespace eomgen::syntax
