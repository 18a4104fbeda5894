#include "relative_rotations.hpp"

#include "eomgen/mechanics/kinematics.hpp"

namespace eomgen {

using GiNaC::matrix;

matrix RelativeRotations::compute(FrameId b, FrameId a) {
  return z_.bind(eomgen::dcm(system_, b, a));
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
