#pragma once
// The numbers linearize needs at a point (M, F, Xi, Xi_t, b, phi and the derivatives K, D, B_u,
// S_q, S_qd, C_q) compiled once into an ExpressionTape, so that every further point (a sweep's
// hundreds) costs arithmetic only. Private to the derivation layer.
#include <Eigen/Dense>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "eomgen/derivation/linearization.hpp"
#include "eomgen/symbolic/expression_tape.hpp"
#include "eomrt/linearization.hpp"

namespace eomgen {

/// See SymbolicLinearization::program. The registers of each matrix are row-major.
struct LinearizationProgram {
  std::vector<GiNaC::ex> inputs;  ///< t, q, qd, u, parameters (numeric_substitution's), qdd, lambda
  ExpressionTape tape;
  struct Matrix {
    Eigen::Index rows = 0, cols = 0;
    std::vector<std::uint32_t> registers;
    std::string name;
  };
  Matrix M, F, Xi, Xi_t, b, phi, K, D, B_u, S_q, S_qd, C_q;

  explicit LinearizationProgram(std::vector<GiNaC::ex> in) : inputs(std::move(in)), tape(inputs) {}
};

/// The program of `lin` (derived from `eom`, of `model`).
std::shared_ptr<const LinearizationProgram> compile_program(const Model& model, const ModelEquations& eom,
                                                            const SymbolicLinearization& lin);

/// One operating point run on SymbolicLinearization::program.
class PointEvaluation {
 public:
  /// \throws Error for a name numeric_substitution does not accept
  PointEvaluation(const Model& model, const LinearizationProgram& program, const NamedValues& point);

  /// the accelerations and multipliers the derivatives are taken at; evaluates again
  void set_accelerations(const Eigen::VectorXd& qdd, const Eigen::VectorXd& lambda);

  /// \throws Error as evaluate_matrix does, for an entry that is not finite
  Eigen::MatrixXd matrix(const LinearizationProgram::Matrix& m) const;

  /// M, F, Xi, Xi_t, b and phi (what the accelerations and the constraints need; no
  /// energies or outputs)
  NumericEquations equations() const;

  eomrt::LinearizationTerms<double> terms() const;

 private:
  const LinearizationProgram& program_;
  std::vector<double> inputs_, registers_;
};

}  // namespace eomgen
