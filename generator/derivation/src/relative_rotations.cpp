#include "relative_rotations.hpp"

#include "eomgen/mechanics/kinematics.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix identity3() { return GiNaC::ex_to<matrix>(GiNaC::unit_matrix(3)); }

matrix product(const std::vector<matrix>& factors) {
  matrix out = identity3();
  for (const matrix& m : factors) out = out.mul(m);
  return out;
}

}  // namespace

// C_{f,ancestor} = C_{f,p} C_{p,pp} ... as factors in that order, consecutive principal rotations
// about one axis merged into one
std::vector<RelativeRotations::Factor> RelativeRotations::factors_to_ancestor(FrameId f, FrameId ancestor) const {
  std::vector<Factor> factors;
  for (; f != ancestor; f = *system_.frame(f).parent) {
    const Rotation& rotation = system_.frame(f).rotation;
    switch (rotation.kind()) {
      case Rotation::Kind::identity:
        continue;
      case Rotation::Kind::principal: {
        const int axis = rotation.axes()[0];
        const ex angle = rotation.parameters().op(0);
        if (!factors.empty() && factors.back().axis == axis)
          factors.back().angle += angle;
        else
          factors.push_back(Factor{axis, angle, {}});
        continue;
      }
      case Rotation::Kind::euler:
      case Rotation::Kind::axis_angle:
      case Rotation::Kind::quaternion:
      case Rotation::Kind::rodrigues:
      case Rotation::Kind::modified_rodrigues:
      case Rotation::Kind::matrix:
        factors.push_back(Factor{0, 0, rotation.dcm()});
        continue;
    }
  }
  return factors;
}

matrix RelativeRotations::compute(FrameId b, FrameId a) {
  const FrameId ancestor = common_ancestor(system_, a, b);
  std::vector<Factor> down = factors_to_ancestor(b, ancestor);  // C_{b,anc}
  std::vector<Factor> up = factors_to_ancestor(a, ancestor);    // C_{a,anc}
  // C_ba = C_{b,anc} C_{a,anc}^T; two principal rotations about one axis meet at the ancestor
  // as one rotation by the difference of their angles
  if (!down.empty() && !up.empty() && down.back().axis != 0 && down.back().axis == up.back().axis) {
    down.back().angle -= up.back().angle;
    up.pop_back();
  }
  std::vector<matrix> factors;
  for (const Factor& f : down) factors.push_back(f.axis == 0 ? f.dcm : principal_rotation(f.axis, f.angle));
  for (auto it = up.rbegin(); it != up.rend(); ++it)
    factors.push_back((it->axis == 0 ? it->dcm : principal_rotation(it->axis, it->angle)).transpose());
  return z_.bind(product(factors));
}

const matrix& RelativeRotations::dcm(FrameId b, FrameId a) {
  const auto key = std::make_pair(b.index, a.index);
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;
  auto reverse = cache_.find(std::make_pair(a.index, b.index));
  matrix value = reverse != cache_.end() ? reverse->second.transpose() : compute(b, a);
  return cache_.emplace(key, std::move(value)).first->second;
}

matrix RelativeRotations::resolve(const Vector& v, FrameId f) {
  matrix out(3, 1);
  for (const auto& [frame, c] : v.terms()) out = out.add(frame == f ? c : dcm(f, frame).mul(c));
  return out;
}

}  // namespace eomgen
