#pragma once
// Kinematics on the frame and point trees, as plain (fully written out) expressions: DCMs by
// compounding, angular velocities by adding along the tree, the transport theorem. Good for
// inspecting a model and for small systems; derive_equations uses its own recursive, shared
// formulation that scales to long chains.
#include <ginac/ginac.h>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen {

/// The nearest common ancestor of frames a and b in the frame tree.
FrameId common_ancestor(const MechanicalSystem& system, FrameId a, FrameId b);

/// C_ba, so that v_b = C_ba v_a; compounded along the frame tree through the nearest common
/// ancestor: C_ba = C_b,anc C_anc,a. A run of principal rotations about one axis is one rotation
/// by the sum of the angles (C_{b3,b1} of a planar chain is C3(q2 + q3), not C3(q3) C3(q2)), and
/// two about one axis that meet at the common ancestor one by the difference: products of
/// rotations about one axis never bring sin^2 + cos^2 that no simplification would collapse,
/// and the DCMs of long chains stay small.
GiNaC::matrix dcm(const MechanicalSystem& system, FrameId b, FrameId a);

/// omega^ba, the angular velocity of b relative to a: the sum of the relative angular
/// velocities along the tree path (each term kept in its own frame).
Vector angular_velocity(const MechanicalSystem& system, FrameId b, FrameId a);

/// Components of v resolved in frame f (3x1).
GiNaC::matrix resolve(const MechanicalSystem& system, const Vector& v, FrameId f);

GiNaC::ex dot(const MechanicalSystem& system, const Vector& u, const Vector& v);
/// u x v; each term of u keeps its frame.
Vector cross(const MechanicalSystem& system, const Vector& u, const Vector& v);

/// Time derivative seen in frame a (transport theorem): v^{.a} = sum_f (dv_f/dt + omega^fa x v_f).
Vector time_derivative(const MechanicalSystem& system, const Vector& v, FrameId a);

/// Partial derivative seen in frame a with respect to a coordinate or a rate. For a rate the
/// frames do not change; for a coordinate q_k the basis of f turns with
/// d omega^fa / d qd_k (the partial angular velocity).
Vector partial_derivative(const MechanicalSystem& system, const Vector& v,
                          const GiNaC::symbol& variable, FrameId a);

/// r^{pq}, the position of p relative to q.
Vector position(const MechanicalSystem& system, PointId p, PointId q);

/// v^{po/a}: velocity of p relative to the point o (which must be fixed in frame a) with
/// respect to frame a. By default o is the inertial origin and a the inertial frame.
Vector velocity(const MechanicalSystem& system, PointId p, FrameId a, PointId o);
Vector velocity(const MechanicalSystem& system, PointId p);

/// a^{po/a/a}, the acceleration of p relative to o with respect to frame a.
Vector acceleration(const MechanicalSystem& system, PointId p, FrameId a, PointId o);
Vector acceleration(const MechanicalSystem& system, PointId p);

}  // namespace eomgen
