#include "eomgen/mechanics/rotation.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix identity3() { return GiNaC::ex_to<matrix>(GiNaC::unit_matrix(3)); }

matrix column(const ex& a, const ex& b, const ex& c) { return matrix(3, 1, GiNaC::lst{a, b, c}); }

void require_column3(const matrix& m, const char* what) {
  if (m.rows() != 3 || m.cols() != 1)
    throw ModelError(fmt::format("{}: expected a 3x1 column, got {}x{}", what, m.rows(), m.cols()));
}

void require_axis(int axis) {
  if (axis < 1 || axis > 3)
    throw ModelError(fmt::format("principal rotation: expected axis 1, 2 or 3, got {}", axis));
}

ex dot3(const matrix& a, const matrix& b) { return a(0, 0) * b(0, 0) + a(1, 0) * b(1, 0) + a(2, 0) * b(2, 0); }

matrix time_derivative(const matrix& m, const Variables& variables) {
  matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = variables.time_derivative(m(i, j));
  return out;
}

}  // namespace

matrix principal_rotation(int axis, const ex& angle) {
  require_axis(axis);
  const ex c = GiNaC::cos(angle), s = GiNaC::sin(angle);
  switch (axis) {
    case 1: return matrix(3, 3, GiNaC::lst{1, 0, 0, 0, c, s, 0, -s, c});
    case 2: return matrix(3, 3, GiNaC::lst{c, 0, -s, 0, 1, 0, s, 0, c});
    case 3: return matrix(3, 3, GiNaC::lst{c, s, 0, -s, c, 0, 0, 0, 1});
  }
  EOMGEN_UNREACHABLE(fmt::format("principal_rotation: axis {} passed require_axis", axis));
}

matrix cross_matrix(const matrix& u) {
  require_column3(u, "cross operator");
  return matrix(3, 3, GiNaC::lst{0, -u(2, 0), u(1, 0), u(2, 0), 0, -u(0, 0), -u(1, 0), u(0, 0), 0});
}

matrix uncross(const matrix& W) {
  if (W.rows() != 3 || W.cols() != 3)
    throw ModelError(fmt::format("uncross: expected a 3x3 matrix, got {}x{}", W.rows(), W.cols()));
  // skew-symmetric part, so that a W that is skew only on the manifold still gives omega
  return column((W(2, 1) - W(1, 2)) / 2, (W(0, 2) - W(2, 0)) / 2, (W(1, 0) - W(0, 1)) / 2);
}

matrix unit_column(int axis) {
  require_axis(axis);
  matrix e(3, 1);
  e(axis - 1, 0) = 1;
  return e;
}

EulerSequence EulerSequence::parse(const std::string& text) {
  // accepted spellings: "3-1-3", "313", "3_1_3"
  std::string digits;
  if (text.size() == 3) {
    digits = text;
  } else if (text.size() == 5 && text[1] == text[3] && (text[1] == '-' || text[1] == '_')) {
    digits = {text[0], text[2], text[4]};
  }
  const bool valid_digits = digits.size() == 3 && std::all_of(digits.begin(), digits.end(), [](char ch) {
                              return ch >= '1' && ch <= '3';
                            });
  if (!valid_digits || digits[0] == digits[1] || digits[1] == digits[2])
    throw ModelError(fmt::format(
        "Euler sequence '{}': expected three axes from 1, 2, 3 with no two consecutive axes "
        "equal, such as \"3-2-1\" or \"3-1-3\"", text));
  return EulerSequence{{digits[0] - '0', digits[1] - '0', digits[2] - '0'}};
}

std::string EulerSequence::name() const { return fmt::format("{}-{}-{}", axes[0], axes[1], axes[2]); }

matrix euler_rotation(const EulerSequence& sequence, const ex& t1, const ex& t2, const ex& t3) {
  const auto& a = sequence.axes;
  return principal_rotation(a[2], t3).mul(principal_rotation(a[1], t2)).mul(principal_rotation(a[0], t1));
}

matrix axis_angle_rotation(const matrix& axis, const ex& angle) {
  require_column3(axis, "axis/angle rotation");
  // C = cos(phi) 1 + (1 - cos(phi)) a a^T - sin(phi) a^x
  return identity3()
      .mul_scalar(GiNaC::cos(angle))
      .add(axis.mul(axis.transpose()).mul_scalar(1 - GiNaC::cos(angle)))
      .sub(cross_matrix(axis).mul_scalar(GiNaC::sin(angle)));
}

matrix quaternion_rotation(const matrix& eps, const ex& eta) {
  require_column3(eps, "quaternion rotation");
  // C = (eta^2 - eps^T eps) 1 + 2 eps eps^T - 2 eta eps^x
  return identity3()
      .mul_scalar(eta * eta - dot3(eps, eps))
      .add(eps.mul(eps.transpose()).mul_scalar(2))
      .sub(cross_matrix(eps).mul_scalar(2 * eta));
}

matrix rodrigues_rotation(const matrix& p) {
  require_column3(p, "Rodrigues rotation");
  // C = 1 + 2/(1 + p^T p) (p^x p^x - p^x)
  const matrix px = cross_matrix(p);
  return identity3().add(px.mul(px).sub(px).mul_scalar(2 / (1 + dot3(p, p))));
}

matrix modified_rodrigues_rotation(const matrix& s) {
  require_column3(s, "modified Rodrigues rotation");
  // C = 1 + 4/(1 + s^T s)^2 (2 s^x s^x - (1 - s^T s) s^x)
  const matrix sx = cross_matrix(s);
  const ex ss = dot3(s, s);
  return identity3().add(
      sx.mul(sx).mul_scalar(2).sub(sx.mul_scalar(1 - ss)).mul_scalar(4 / GiNaC::pow(1 + ss, 2)));
}

Rotation::Rotation(Kind kind, matrix dcm, GiNaC::lst parameters, std::array<int, 3> axes)
    : kind_(kind), dcm_(std::move(dcm)), parameters_(std::move(parameters)), axes_(axes) {}

Rotation Rotation::identity() { return Rotation(Kind::identity, identity3(), {}); }

Rotation Rotation::principal(int axis, const ex& angle) {
  return Rotation(Kind::principal, principal_rotation(axis, angle), {angle}, {axis, 0, 0});
}

Rotation Rotation::euler(const EulerSequence& sequence, const ex& t1, const ex& t2, const ex& t3) {
  return Rotation(Kind::euler, euler_rotation(sequence, t1, t2, t3), {t1, t2, t3}, sequence.axes);
}

Rotation Rotation::axis_angle(const matrix& axis, const ex& angle) {
  return Rotation(Kind::axis_angle, axis_angle_rotation(axis, angle), {axis, angle});
}

Rotation Rotation::quaternion(const matrix& epsilon, const ex& eta) {
  return Rotation(Kind::quaternion, quaternion_rotation(epsilon, eta), {epsilon, eta});
}

Rotation Rotation::rodrigues(const matrix& p) {
  return Rotation(Kind::rodrigues, rodrigues_rotation(p), {p});
}

Rotation Rotation::modified_rodrigues(const matrix& s) {
  return Rotation(Kind::modified_rodrigues, modified_rodrigues_rotation(s), {s});
}

Rotation Rotation::explicit_matrix(const matrix& dcm) {
  if (dcm.rows() != 3 || dcm.cols() != 3)
    throw ModelError(fmt::format("explicit rotation matrix: expected 3x3, got {}x{}", dcm.rows(), dcm.cols()));
  return Rotation(Kind::matrix, dcm, {dcm});
}

matrix angular_velocity_from_poisson(const matrix& dcm, const Variables& variables) {
  // (omega_b^ba)^x = -(dC_ba/dt) C_ba^T
  return uncross(time_derivative(dcm, variables).mul(dcm.transpose()).mul_scalar(-1));
}

matrix Rotation::angular_velocity(const Variables& v) const {
  auto rate = [&](const ex& e) { return v.time_derivative(e); };
  auto param = [&](unsigned i) { return GiNaC::ex_to<matrix>(parameters_.op(i)); };
  switch (kind_) {
    case Kind::identity:
      return matrix(3, 1);
    case Kind::principal:
      return unit_column(axes_[0]).mul_scalar(rate(parameters_.op(0)));
    case Kind::euler: {
      // omega_b = 1_k dt3 + Ck(t3) 1_j dt2 + Ck(t3) Cj(t2) 1_i dt1
      const matrix Ck = principal_rotation(axes_[2], parameters_.op(2));
      const matrix CkCj = Ck.mul(principal_rotation(axes_[1], parameters_.op(1)));
      return unit_column(axes_[2])
          .mul_scalar(rate(parameters_.op(2)))
          .add(Ck.mul(unit_column(axes_[1])).mul_scalar(rate(parameters_.op(1))))
          .add(CkCj.mul(unit_column(axes_[0])).mul_scalar(rate(parameters_.op(0))));
    }
    case Kind::axis_angle: {
      // omega = a dphi + sin(phi) da - (1 - cos(phi)) a^x da
      const matrix a = param(0);
      const ex phi = parameters_.op(1);
      const matrix da = time_derivative(a, v);
      return a.mul_scalar(rate(phi))
          .add(da.mul_scalar(GiNaC::sin(phi)))
          .sub(cross_matrix(a).mul(da).mul_scalar(1 - GiNaC::cos(phi)));
    }
    case Kind::quaternion: {
      // omega = 2 (eta 1 - eps^x) deps - 2 eps deta
      const matrix eps = param(0);
      const ex eta = parameters_.op(1);
      return identity3()
          .mul_scalar(eta)
          .sub(cross_matrix(eps))
          .mul(time_derivative(eps, v))
          .mul_scalar(2)
          .sub(eps.mul_scalar(2 * rate(eta)));
    }
    case Kind::rodrigues: {
      // omega = 2/(1 + p^T p) (1 - p^x) dp
      const matrix p = param(0);
      return identity3().sub(cross_matrix(p)).mul(time_derivative(p, v)).mul_scalar(2 / (1 + dot3(p, p)));
    }
    case Kind::modified_rodrigues: {
      // omega = 4/(1 + s^T s)^2 ((1 - s^T s) 1 - 2 s^x + 2 s s^T) ds
      const matrix s = param(0);
      const ex ss = dot3(s, s);
      return identity3()
          .mul_scalar(1 - ss)
          .sub(cross_matrix(s).mul_scalar(2))
          .add(s.mul(s.transpose()).mul_scalar(2))
          .mul(time_derivative(s, v))
          .mul_scalar(4 / GiNaC::pow(1 + ss, 2));
    }
    case Kind::matrix:
      return angular_velocity_from_poisson(dcm_, v);
  }
  EOMGEN_UNREACHABLE("Rotation::angular_velocity: a Rotation::Kind outside its enumerators");
}

}  // namespace eomgen
