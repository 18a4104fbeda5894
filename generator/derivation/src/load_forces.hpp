#pragma once
// The generalized forces of a system's loads, from the plain kinematics of kinematics.hpp.
// Written-out partial velocities grow with the depth of a point in a chain, so this suits the
// few loads of a model, not long chains of them.
#include <ginac/ginac.h>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen {

/// Q_k of every load but gravity (point forces, moments, springs, dampers, generalized forces,
/// potentials): the load dotted with the partial velocities, n entries.
GiNaC::exvector generalized_load_forces(const MechanicalSystem& system);

}  // namespace eomgen
