#pragma once
// Direction cosine matrices C_ba of every parameterization in docs/conventions.md, and the
// angular velocity omega_b^ba each one implies.
#include <ginac/ginac.h>

#include <array>
#include <string>

namespace eomgen {

class Variables;

/// Principal rotation C1, C2 or C3 (axis 1, 2 or 3) of an angle; note the sign of the sines:
/// C3(x) = [[c, s, 0], [-s, c, 0], [0, 0, 1]].
GiNaC::matrix principal_rotation(int axis, const GiNaC::ex& angle);

/// Cross operator u^x with u^x v = u x v.
GiNaC::matrix cross_matrix(const GiNaC::matrix& u);
/// Inverse of the cross operator, taken from the skew-symmetric part of W.
GiNaC::matrix uncross(const GiNaC::matrix& W);
/// Column 1_i of the identity (axis 1, 2 or 3).
GiNaC::matrix unit_column(int axis);

/// An Euler sequence "i-j-k": C_ba = Ck(t3) Cj(t2) Ci(t1), the rotation about i applied first.
struct EulerSequence {
  std::array<int, 3> axes;
  /// Parses "3-1-3", "313" or "3_1_3". \throws ModelError for any of the 15 invalid sequences.
  static EulerSequence parse(const std::string& text);
  std::string name() const;  // "3-1-3"
};

/// The rotation of a child frame b relative to its parent a, in one of the parameterizations
/// of docs/conventions.md. Holds the parameters so the angular velocity can use the rate relation
/// of that parameterization (each one is Poisson's equation worked out, and tested as such).
class Rotation {
 public:
  enum class Kind { identity, principal, euler, axis_angle, quaternion, rodrigues,
                    modified_rodrigues, matrix };

  static Rotation identity();
  static Rotation principal(int axis, const GiNaC::ex& angle);
  static Rotation euler(const EulerSequence& sequence, const GiNaC::ex& t1, const GiNaC::ex& t2,
                        const GiNaC::ex& t3);
  /// axis a (3x1, unit length), angle phi.
  static Rotation axis_angle(const GiNaC::matrix& axis, const GiNaC::ex& angle);
  /// Quaternion, scalar last: q = [eps; eta], unit norm.
  static Rotation quaternion(const GiNaC::matrix& epsilon, const GiNaC::ex& eta);
  /// Rodrigues (Gibbs) parameters p = eps / eta.
  static Rotation rodrigues(const GiNaC::matrix& p);
  /// Modified Rodrigues parameters s = eps / (1 + eta).
  static Rotation modified_rodrigues(const GiNaC::matrix& s);
  /// An explicit 3x3 matrix C_ba; its angular velocity comes from Poisson's equation.
  static Rotation explicit_matrix(const GiNaC::matrix& dcm);

  Kind kind() const { return kind_; }
  /// C_ba, which maps components in the parent a to components in the child b: v_b = C_ba v_a.
  const GiNaC::matrix& dcm() const { return dcm_; }
  /// The parameters as given (angles, axis and angle, eps and eta, p or s), for printing.
  const GiNaC::lst& parameters() const { return parameters_; }
  /// Euler sequence, for kind() == euler; axis for kind() == principal in axes[0].
  const std::array<int, 3>& axes() const { return axes_; }

  /// omega_b^ba, resolved in the child frame b; linear in the rates.
  GiNaC::matrix angular_velocity(const Variables& variables) const;

 private:
  Rotation(Kind kind, GiNaC::matrix dcm, GiNaC::lst parameters, std::array<int, 3> axes = {});

  Kind kind_;
  GiNaC::matrix dcm_;
  GiNaC::lst parameters_;
  std::array<int, 3> axes_;
};

/// omega_b^ba from Poisson's equation: (omega_b^ba)^x = -(dC_ba/dt) C_ba^T.
GiNaC::matrix angular_velocity_from_poisson(const GiNaC::matrix& dcm, const Variables& variables);

// Closed-form DCMs (free functions, also used by Rotation).
GiNaC::matrix euler_rotation(const EulerSequence& sequence, const GiNaC::ex& t1,
                             const GiNaC::ex& t2, const GiNaC::ex& t3);
GiNaC::matrix axis_angle_rotation(const GiNaC::matrix& axis, const GiNaC::ex& angle);
GiNaC::matrix quaternion_rotation(const GiNaC::matrix& epsilon, const GiNaC::ex& eta);
GiNaC::matrix rodrigues_rotation(const GiNaC::matrix& p);
GiNaC::matrix modified_rodrigues_rotation(const GiNaC::matrix& s);

}  // namespace eomgen
