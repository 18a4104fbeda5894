// Recursive-descent parser: tokens -> statements with expression trees.
#include <fmt/format.h>

#include <map>

#include "eomgen/base/error.hpp"
#include "model_lexer.hpp"
#include "model_syntax.hpp"
#include "model_unit.hpp"

namespace eomgen::syntax {
namespace {

using Kind = Statement::Kind;

const std::map<std::string, Kind> element_keywords = {
    {"particle", Kind::particle}, {"body", Kind::body},     {"force", Kind::force},
    {"moment", Kind::moment},     {"spring", Kind::spring}, {"damper", Kind::damper},
    {"torsion", Kind::torsion},   {"roll", Kind::roll},     {"generalized_force", Kind::generalized_force},
    {"wheel", Kind::wheel}};

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string text) : tokens_(std::move(tokens)), text_(std::move(text)) {}

  std::vector<Statement> statements(bool inside_loop) {
    std::vector<Statement> out;
    for (;;) {
      skip_newlines();
      if (peek().kind == Token::Kind::end) {
        if (inside_loop) error(peek(), "expected 'end' to close the 'for' loop");
        return out;
      }
      if (is_word("end")) {
        if (!inside_loop) error(peek(), "'end' without a 'for' loop");
        next();
        end_of_statement();
        return out;
      }
      out.push_back(statement());
    }
  }

  ExprPtr whole_expression() {
    ExprPtr e = expression();
    skip_newlines();
    if (peek().kind != Token::Kind::end) error(peek(), fmt::format("unexpected {} in expression", describe(peek())));
    return e;
  }

 private:
  const Token& peek(std::size_t ahead = 0) const { return tokens_[std::min(pos_ + ahead, tokens_.size() - 1)]; }
  const Token& next() { return tokens_[pos_ < tokens_.size() - 1 ? pos_++ : pos_]; }
  bool is_symbol(const char* s) const { return peek().kind == Token::Kind::symbol && peek().text == s; }
  bool is_word(const char* s) const { return peek().kind == Token::Kind::identifier && peek().text == s; }
  void skip_newlines() {
    while (peek().kind == Token::Kind::newline) next();
  }
  [[noreturn]] void error(const Token& t, const std::string& message) const { throw SourceError(t.location, message); }

  const Token& expect_symbol(const char* s, const char* context) {
    if (!is_symbol(s)) error(peek(), fmt::format("expected '{}' {}, got {}", s, context, describe(peek())));
    return next();
  }
  void end_of_statement() {
    if (peek().kind != Token::Kind::newline && peek().kind != Token::Kind::end)
      error(peek(), fmt::format("expected end of line after the statement, got {}", describe(peek())));
  }

  Name name(const char* what) {
    if (peek().kind != Token::Kind::identifier)
      error(peek(), fmt::format("expected {} (an identifier), got {}", what, describe(peek())));
    return make_name(next());
  }

  // splits "q{i-1}x" into pieces, parsing each {...} as an expression at its own position
  Name make_name(const Token& t) {
    Name n;
    n.location = t.location;
    std::size_t k = 0;
    std::string literal;
    while (k < t.text.size()) {
      if (t.text[k] != '{') {
        literal += t.text[k++];
        continue;
      }
      if (!literal.empty()) n.pieces.push_back({literal, nullptr});
      literal.clear();
      const std::size_t close = t.text.find('}', k);
      SourceLocation at = t.location;
      at.column += static_cast<int>(k) + 1;
      const std::string inner = t.text.substr(k + 1, close - k - 1);
      if (inner.find('{') != std::string::npos) throw SourceError(at, "nested '{' in a name");
      n.pieces.push_back({"", parse_expression_text(inner, at)});
      k = close + 1;
    }
    if (!literal.empty()) n.pieces.push_back({literal, nullptr});
    return n;
  }

  Statement statement() {
    const Token& keyword = peek();
    if (keyword.kind != Token::Kind::identifier)
      error(keyword, fmt::format("expected a statement keyword, got {}", describe(keyword)));
    const std::string word = keyword.text;
    const std::size_t first_token = pos_;
    next();
    Statement s;
    s.location = keyword.location;
    if (word == "model") {
      s.kind = Kind::model;
      s.name = name("the model name");
      if (peek().kind == Token::Kind::string) s.text = next().text;
    } else if (word == "description") {
      s.kind = Kind::description;
      if (peek().kind != Token::Kind::string) error(peek(), "expected a string in double quotes after 'description'");
      s.text = next().text;
    } else if (word == "const" || word == "parameter" || word == "potential") {
      s.kind = word == "const" ? Kind::constant : word == "parameter" ? Kind::parameter : Kind::potential;
      s.name = name(word == "potential" ? "the potential's name" : "a name");
      expect_symbol("=", fmt::format("after the name in a {} statement", word).c_str());
      s.value = expression();
      if (s.kind == Kind::parameter && is_symbol("[")) s.unit = unit();
    } else if (word == "coordinate" || word == "input" || word == "independent") {
      s.kind = word == "coordinate" ? Kind::coordinate : word == "input" ? Kind::input : Kind::independent;
      const char* what = s.kind == Kind::input ? "an input name" : "a coordinate name";
      for (;;) {
        s.names.push_back(name(what));
        s.units.push_back(s.kind != Kind::independent && is_symbol("[") ? std::optional<Unit>(unit()) : std::nullopt);
        if (!is_symbol(",")) break;
        next();
      }
    } else if (word == "frame" || word == "point") {
      s.kind = word == "frame" ? Kind::frame : Kind::point;
      s.name = name(word == "frame" ? "the frame's name" : "the point's name");
      expect_symbol("=", fmt::format("after the {} name", word).c_str());
      s.value = expression();
    } else if (word == "gravity") {
      s.kind = Kind::gravity;
      expect_symbol("=", "after 'gravity'");
      s.value = expression();
    } else if (word == "constraint") {
      s.kind = Kind::constraint;
      s.name = name("the constraint's name");
      expect_symbol(":", "after the constraint's name");
      s.value = expression();
      expect_symbol("=", "in the constraint (write LEFT = RIGHT)");
      s.value2 = expression();
      if (is_word("in")) {  // the frame of a vector constraint's rows
        next();
        s.frame = name("a frame name after 'in'");
        s.has_frame = true;
      }
    } else if (word == "output") {
      s.kind = Kind::output;
      s.name = name("the output's name");
      expect_symbol("=", "after the output's name");
      s.value = expression();
      if (is_word("in")) {
        next();
        s.frame = name("a frame name after 'in'");
        s.has_frame = true;
      }
    } else if (word == "for") {
      s.kind = Kind::loop;
      s.name = name("the loop variable");
      if (!is_word("in")) error(peek(), fmt::format("expected 'in' after the loop variable, got {}", describe(peek())));
      next();
      s.value = expression();
      expect_symbol("..", "between the first and last value of the loop (for i in 1..n)");
      s.value2 = expression();
      end_of_statement();
      s.token_count = pos_ - first_token;
      if (loop_depth_ == max_loop_depth)
        error(keyword, fmt::format("loops nest deeper than {} levels: expected fewer loops inside one another",
                                   max_loop_depth));
      ++loop_depth_;
      s.body = statements(true);
      --loop_depth_;
      return s;
    } else if (auto it = element_keywords.find(word); it != element_keywords.end()) {
      s.kind = it->second;
      s.name = name(fmt::format("the {}'s name", word).c_str());
      expect_symbol("(", fmt::format("after the {}'s name, then key = value arguments", word).c_str());
      s.arguments = arguments();
    } else if (word == "shape") {
      s.kind = Kind::shape;
      s.name = name("the shape's name");
      expect_symbol("=", "after the shape's name");
      s.shape_kind = name("the shape's kind (sphere, box, cylinder, disk or rod)");
      expect_symbol("(", "after the shape's kind, then key = value arguments");
      s.arguments = arguments();
    } else {
      error(keyword, fmt::format("unknown statement '{}': expected one of model, description, const, parameter, "
                                 "coordinate, input, frame, point, particle, body, gravity, force, moment, "
                                 "spring, damper, torsion, potential, generalized_force, constraint, roll, "
                                 "wheel, shape, independent, output, for", word));
    }
    end_of_statement();
    s.token_count = pos_ - first_token;
    return s;
  }

  // key = value, ... up to and including the ')' (the '(' is read)
  std::vector<Argument> arguments() {
    std::vector<Argument> out;
    while (!is_symbol(")")) {
      const Token& key = peek();
      if (key.kind != Token::Kind::identifier)
        error(key, fmt::format("expected an argument name (key = value), got {}", describe(key)));
      next();
      expect_symbol("=", fmt::format("after the argument name '{}'", key.text).c_str());
      if (peek().kind == Token::Kind::string) {  // a file name: a value of its own, never an operand
        const Token& t = next();
        auto text = std::make_shared<Expr>();
        text->kind = Expr::Kind::text;
        text->location = t.location;
        text->number_text = t.text;
        out.push_back(Argument{key.text, text, key.location});
      } else {
        out.push_back(Argument{key.text, expression(), key.location});
      }
      if (!is_symbol(")")) expect_symbol(",", "or ')' after an argument");
    }
    next();
    return out;
  }

  // [m/s^2]: its dimension, and its text as written for the generated code and reports
  Unit unit() {
    const Token& open = next();
    std::size_t start = open.end_offset;
    std::vector<Token> inside;
    while (!is_symbol("]")) {
      if (peek().kind == Token::Kind::newline || peek().kind == Token::Kind::end)
        error(open, "unterminated unit: expected ']'");
      inside.push_back(next());
    }
    const Token& close = next();
    std::string u = text_.substr(start, close.offset - start);
    while (!u.empty() && u.front() == ' ') u.erase(u.begin());
    while (!u.empty() && u.back() == ' ') u.pop_back();
    return Unit{u, open.location, unit_dimension(inside, open.location)};
  }

  static ExprPtr make(Expr::Kind kind, SourceLocation loc, std::vector<ExprPtr> args = {}) {
    auto e = std::make_shared<Expr>();
    e->kind = kind;
    e->location = std::move(loc);
    e->args = std::move(args);
    return e;
  }

  // One more level of nesting for as long as it lives; refused beyond max_expression_depth.
  class Deeper {
   public:
    Deeper(Parser& parser, const Token& at) : parser_(parser) {
      if (parser_.depth_ == max_expression_depth)
        parser.error(at, fmt::format("expressions nest deeper than {} levels (parentheses, calls, brackets, signs "
                                     "and powers): expected a flatter expression",
                                     max_expression_depth));
      ++parser_.depth_;
    }
    Deeper(const Deeper&) = delete;
    Deeper& operator=(const Deeper&) = delete;
    ~Deeper() { --parser_.depth_; }

   private:
    Parser& parser_;
  };

  ExprPtr expression() {
    const Deeper level(*this, peek());
    return chain(Expr::Kind::sum, "+", "-", &Parser::term);
  }

  ExprPtr term() { return chain(Expr::Kind::product, "*", "/", &Parser::unary); }

  // operand (op operand)*, as one flat node when there is more than one operand
  ExprPtr chain(Expr::Kind kind, const char* op, const char* inverse_op, ExprPtr (Parser::*operand)()) {
    ExprPtr first = (this->*operand)();
    if (!is_symbol(op) && !is_symbol(inverse_op)) return first;
    auto node = std::make_shared<Expr>();
    node->kind = kind;
    node->location = peek().location;
    node->args.push_back(std::move(first));
    while (is_symbol(op) || is_symbol(inverse_op)) {
      const Token& t = next();
      node->operations.push_back(Expr::Operation{t.text == inverse_op, t.location});
      node->args.push_back((this->*operand)());
    }
    return node;
  }

  ExprPtr unary() {
    if (is_symbol("-")) {
      const Token& op = next();
      const Deeper level(*this, op);
      return make(Expr::Kind::negate, op.location, {unary()});
    }
    if (is_symbol("+")) {
      const Deeper level(*this, next());
      return unary();
    }
    return power();
  }

  ExprPtr power() {
    ExprPtr base = postfix();
    if (is_symbol("^")) {
      const Token& op = next();
      const Deeper level(*this, op);
      return make(Expr::Kind::power, op.location, {base, unary()});  // right associative
    }
    return base;
  }

  ExprPtr postfix() {
    ExprPtr e = primary();
    if (is_symbol(".") && e->kind == Expr::Kind::name) {
      const Token& dot = next();
      if (peek().kind != Token::Kind::number || (peek().text != "1" && peek().text != "2" && peek().text != "3"))
        error(peek(), fmt::format("expected 1, 2 or 3 after '.' (a basis vector such as b.1), got {}", describe(peek())));
      auto b = std::make_shared<Expr>();
      b->kind = Expr::Kind::basis;
      b->location = e->location;
      b->name = e->name;
      b->basis_index = next().text[0] - '0';
      (void)dot;
      return b;
    }
    return e;
  }

  ExprPtr primary() {
    const Token& t = peek();
    if (t.kind == Token::Kind::number) {
      next();
      auto e = make(Expr::Kind::number, t.location);
      std::const_pointer_cast<Expr>(e)->number_text = t.text;
      return e;
    }
    if (t.kind == Token::Kind::identifier) {
      next();
      auto e = std::make_shared<Expr>();
      e->location = t.location;
      e->name = make_name(t);
      if (is_symbol("(")) {
        next();
        e->kind = Expr::Kind::call;
        while (!is_symbol(")")) {
          e->args.push_back(expression());
          if (!is_symbol(")")) expect_symbol(",", "or ')' between function arguments");
        }
        next();
      } else {
        e->kind = Expr::Kind::name;
      }
      return e;
    }
    if (is_symbol("(")) {
      next();
      ExprPtr inner = expression();
      expect_symbol(")", "to close '('");
      return inner;
    }
    if (is_symbol("[")) {
      next();
      auto list = std::make_shared<Expr>();
      list->kind = Expr::Kind::list;
      list->location = t.location;
      while (!is_symbol("]")) {
        list->args.push_back(expression());
        if (!is_symbol("]")) expect_symbol(",", "or ']' between list elements");
      }
      next();
      if (is_word("in")) {
        next();
        auto framed = std::make_shared<Expr>();
        framed->kind = Expr::Kind::in_frame;
        framed->location = t.location;
        framed->name = name("a frame name after 'in'");
        framed->args = {list};
        return framed;
      }
      return list;
    }
    error(t, fmt::format("expected an expression (a number, a name, '(' or '['), got {}", describe(t)));
  }

  std::vector<Token> tokens_;
  std::string text_;
  std::size_t pos_ = 0;
  int depth_ = 0;       // expression nesting (Deeper)
  int loop_depth_ = 0;  // `for` loops open around the current statement
};

}  // namespace

const SourceLocation& start_of(const Expr& e) {
  switch (e.kind) {
    case Expr::Kind::sum:
    case Expr::Kind::product:
    case Expr::Kind::power: return start_of(*e.args[0]);
    case Expr::Kind::number:
    case Expr::Kind::name:
    case Expr::Kind::negate:  // a prefix operator starts where it stands
    case Expr::Kind::call:
    case Expr::Kind::list:
    case Expr::Kind::in_frame:
    case Expr::Kind::basis:
    case Expr::Kind::text: return e.location;
  }
  EOMGEN_UNREACHABLE("start_of: an Expr::Kind outside its enumerators");
}

std::vector<Statement> parse_statements(const std::string& text, const std::string& file) {
  Parser p(tokenize(text, file), text);
  return p.statements(false);
}

ExprPtr parse_expression_text(const std::string& text, const SourceLocation& start) {
  if (text.find_first_not_of(" \t") == std::string::npos) throw SourceError(start, "expected an expression inside '{}'");
  Parser p(tokenize(text, start.file, start.line, start.column), text);
  return p.whole_expression();
}

}  // namespace eomgen::syntax
