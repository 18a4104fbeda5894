#pragma once
// C_fg for any two frames of a system, compounded along the frame tree through their nearest
// common ancestor and cached. A run of principal rotations about one axis is one rotation by the
// sum of the angles: C_{b3,b1} of a planar chain is C3(q2 + q3), not C3(q3) C3(q2) multiplied
// out, so a dot product of vectors resolved in the two frames brings one cosine of the relative
// angle and no sin^2 + cos^2 that nobody collapses.
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
  // one factor of C_{f,ancestor}: a principal rotation by a summed angle, or any other rotation
  struct Factor {
    int axis = 0;  // 1..3 for a principal rotation, 0 for a general one
    GiNaC::ex angle;
    GiNaC::matrix dcm;
  };
  std::vector<Factor> factors_to_ancestor(FrameId f, FrameId ancestor) const;
  GiNaC::matrix compute(FrameId b, FrameId a);

  const MechanicalSystem& system_;
  Subexpressions& z_;
  std::map<std::pair<std::size_t, std::size_t>, GiNaC::matrix> cache_;
};

}  // namespace eomgen
