#pragma once
// Reference derivation by literal differentiation of the Lagrangian,
//   d/dt (dL/dqd) - dL/dq = Q_nc,
// with T and V written out through the plain kinematics functions. It shares no code with
// derive_equations' recursive formulation, so agreement between the two is a real check.
// Expressions grow exponentially with chain length: for tests and small systems only.
#include <ginac/ginac.h>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen {

struct LiteralLagrangeEquations {
  GiNaC::matrix mass_matrix;  ///< d2T/dqd2
  GiNaC::matrix forcing;      ///< everything but M qdd, on the right-hand side
  GiNaC::ex kinetic_energy;
  GiNaC::ex potential_energy;
};

LiteralLagrangeEquations derive_equations_literally(const MechanicalSystem& system);

}  // namespace eomgen
