#pragma once
// Expressions compiled once into a flat list of operations on numbered registers, for
// evaluating the same expressions at many points (a stability sweep linearizes at hundreds).
// Walking GiNaC trees costs a type test and a map lookup per node; a tape costs one step per
// operation. The arithmetic is DoubleEvaluator's (order-independent sums and products), so
// both give the same bits.
#include <ginac/ginac.h>

#include <cstdint>
#include <string>
#include <vector>

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {

class ExpressionTape {
 public:
  /// `inputs`: the symbols whose values each evaluation is given, in that order
  explicit ExpressionTape(const std::vector<GiNaC::ex>& inputs);

  /// symbol := value, computed in the order of the calls; value may use the inputs and the
  /// symbols defined before
  /// \throws Error naming `what` for a symbol that is neither, a complex number, or an
  ///   expression with no double evaluation
  void define(const GiNaC::ex& symbol, const GiNaC::ex& value, const std::string& what);

  /// \return the register that will hold e after evaluate() (same conditions as define)
  std::uint32_t compile(const GiNaC::ex& e, const std::string& what);

  /// Runs the tape: registers[0..inputs) are the inputs, the rest are computed.
  void evaluate(const std::vector<double>& inputs, std::vector<double>& registers) const;

  std::size_t input_count() const { return input_count_; }

 private:
  enum class Op : std::uint8_t { constant, sum, product, square_root, power, unary, atan2 };
  struct Step {
    Op op;
    std::uint32_t result, first, count;  // operands are operands_[first, first + count)
    double constant;
    double (*unary)(double);
  };
  std::uint32_t node(const GiNaC::ex& e, const std::string& what);
  std::uint32_t emit(Step step, const std::vector<std::uint32_t>& operands);

  std::size_t input_count_ = 0;
  std::uint32_t registers_ = 0;
  std::vector<Step> steps_;
  std::vector<std::uint32_t> operands_;
  ExpressionMap<std::uint32_t> registered_;  // looked up, never iterated
};

}  // namespace eomgen
