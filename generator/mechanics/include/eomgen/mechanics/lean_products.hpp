#pragma once
// Products of physical vectors written in the frame where they come out smallest. dot() and
// cross() of kinematics.hpp resolve the second vector in the frames of the first, which is cheap
// and right inside the derivation; a position or an attitude built from a product, though, enters
// every later derivation, the linearization and the generated code, so there it pays to try each
// frame on the tree path between the vectors' frames and keep the simplest result (the contact of
// a rolling coin, written in its lean frame, is -r s.3 instead of a quotient of sines).
#include <ginac/ginac.h>

#include <cstddef>
#include <vector>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen {

/// The number of nodes of e's expression tree: the measure of "smallest" here.
std::size_t expression_size(const GiNaC::ex& e);

/// The frames on the tree paths from each of `frames` up to their nearest common ancestor, the
/// ancestor included, each once, in the order met.
std::vector<FrameId> frames_between(const MechanicalSystem& system, const std::vector<FrameId>& frames);

/// u . v, resolved in the frame between u's and v's frames where it is smallest after
/// simplify_for_display (or as dot() gives it, when that is smaller still).
GiNaC::ex lean_dot(const MechanicalSystem& system, const Vector& u, const Vector& v);

/// |v|, from lean_dot(v, v).
GiNaC::ex lean_norm(const MechanicalSystem& system, const Vector& v);

/// u x v, as one term in the frame between u's and v's frames where its simplified components
/// are smallest (or as cross() gives it, when that is smaller still).
Vector lean_cross(const MechanicalSystem& system, const Vector& u, const Vector& v);

/// v as one term, in the frame between its terms' frames where its simplified components are
/// smallest (or v itself, when that is smaller still).
Vector lean_resolved(const MechanicalSystem& system, const Vector& v);

}  // namespace eomgen
