#pragma once
// C_fg for any two frames of a system, as kinematics.hpp's dcm() compounds it (runs of principal
// rotations about one axis merged into one), bound in the intermediates and cached: a dot product
// of vectors resolved in two frames of a planar chain brings one cosine of the relative angle.
#include <ginac/ginac.h>

#include <map>
#include <utility>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

class RelativeRotations {
 public:
  RelativeRotations(const MechanicalSystem& system, Subexpressions& intermediates)
      : system_(system), z_(intermediates) {}

  /// C_ba (so that v_b = C_ba v_a), its entries bound in the intermediates.
  const GiNaC::matrix& dcm(FrameId b, FrameId a);

  /// The components of v resolved in frame f.
  GiNaC::matrix resolve(const Vector& v, FrameId f);

 private:
  GiNaC::matrix compute(FrameId b, FrameId a);

  const MechanicalSystem& system_;
  Subexpressions& z_;
  std::map<std::pair<std::size_t, std::size_t>, GiNaC::matrix> cache_;
};

}  // namespace eomgen
