#pragma once
// Chain models for the derivation benchmark. Both are built through the public API only, and
// every call creates fresh symbols, so two chains never share state.
#include <cstddef>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen::bench {

/// Planar chain of n uniform rods in the 1-2 plane of the inertial frame a, joined by pins,
/// the first pinned at the origin w. Coordinates q1..qn are relative joint angles:
///   frame b_i = C3(q_i) relative to b_{i-1} (b_0 = a),
///   mass centre mc_i at l/2 along b_i^1 from joint j_{i-1} (j_0 = w),
///   joint j_i at l along b_i^1 from j_{i-1},
///   inertia about mc_i in b_i: diag(m l^2/1200, m l^2/12, m l^2/12) (axial value small, > 0),
///   gravity g along a^1 (the chain hangs along a^1 at q = 0).
/// Parameters m = 2 kg, l = 0.5 m, g = 9.81 m/s^2 (defaults).
MechanicalSystem planar_chain(std::size_t n);

/// 3D chain of n uniform boxes joined by universal joints, the first hung from the origin w.
/// Joint i has two coordinates, u_i then v_i (coordinates q_{2i-1}, q_{2i}):
///   frame c_i = C1(u_i) relative to b_{i-1} (b_0 = a), frame b_i = C2(v_i) relative to c_i,
///   mass centre mc_i at l/2 along -b_i^3 from joint j_{i-1} (j_0 = w),
///   joint j_i at l along -b_i^3 from j_{i-1},
///   inertia about mc_i in b_i: diag(m (l^2 + h^2)/12, m (l^2 + h^2)/12, m h^2/6) (a box l x h x h),
///   gravity g along -a^3 (the chain hangs along -a^3 at q = 0).
/// Parameters m = 2 kg, l = 0.5 m, h = 0.05 m, g = 9.81 m/s^2 (defaults).
MechanicalSystem universal_joint_chain(std::size_t n);

}  // namespace eomgen::bench
