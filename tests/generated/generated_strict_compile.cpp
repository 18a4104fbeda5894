// Instantiates every function of every generated header for double and float. This file is
// compiled with -Wall -Wextra -Werror -pedantic (see tests/CMakeLists.txt) and includes
// nothing but the generated headers, Eigen and the standard library.
#include "generated_strict_compile.hpp"

#include "bead_on_hoop.hpp"
#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "four_bar.hpp"
#include "heavy_top.hpp"
#include "knife_edge.hpp"
#include "planar_3rrr.hpp"
#include "two_wheeled_robot.hpp"
#include "planar_chain.hpp"
#include "quaternion_rigid_body.hpp"
#include "rolling_coin.hpp"
#include "simple_pendulum.hpp"
#include "spacecraft_panel.hpp"
#include "spherical_pendulum.hpp"
#include "spring_mass_damper.hpp"
#include "universal_chain.hpp"

namespace {

// every function at one state; true when every result is finite
template <class Model, class Scalar>
bool evaluates_finitely() {
  typename Model::template Parameters<Scalar> p;
  const typename Model::template Vector<Scalar> q = Model::template Vector<Scalar>::Constant(Scalar(0.3));
  const typename Model::template Vector<Scalar> qd = Model::template Vector<Scalar>::Constant(Scalar(-0.2));
  const typename Model::template Inputs<Scalar> u = Model::template Inputs<Scalar>::Constant(Scalar(0.1));
  const Scalar t(0.5);
  typename Model::template MassMatrix<Scalar> M;
  typename Model::template Vector<Scalar> F;
  typename Model::template ConstraintJacobian<Scalar> Xi;
  typename Model::template ConstraintVector<Scalar> Xi_t, b;
  typename Model::template HolonomicVector<Scalar> phi;
  typename Model::template OutputVector<Scalar> y;
  Model::mass_matrix(t, q, p, M);
  Model::forcing(t, q, qd, u, p, F);
  Model::mass_matrix_and_forcing(t, q, qd, u, p, M, F);
  Model::constraint_jacobian(t, q, p, Xi);
  Model::constraint_rate_term(t, q, p, Xi_t);
  Model::constraint_acceleration_term(t, q, qd, p, b);
  Model::holonomic_residuals(t, q, p, phi);
  Model::outputs(t, q, qd, u, p, y);
  const Scalar energy = Model::kinetic_energy(t, q, qd, p) + Model::potential_energy(t, q, p);
  // and every overload taking the Constants
  const typename Model::template Constants<Scalar> c(p);
  typename Model::template MassMatrix<Scalar> Mc;
  typename Model::template Vector<Scalar> Fc;
  Model::mass_matrix(t, q, c, Mc);
  Model::forcing(t, q, qd, u, c, Fc);
  Model::mass_matrix_and_forcing(t, q, qd, u, c, Mc, Fc);
  Model::constraint_jacobian(t, q, c, Xi);
  Model::constraint_rate_term(t, q, c, Xi_t);
  Model::constraint_acceleration_term(t, q, qd, c, b);
  Model::holonomic_residuals(t, q, c, phi);
  Model::outputs(t, q, qd, u, c, y);
  const Scalar energy_c = Model::kinetic_energy(t, q, qd, c) + Model::potential_energy(t, q, c);
  // the generated forward dynamics solves M qdd = F to the scalar's rounding
  if constexpr (Model::has_forward_dynamics) {
    typename Model::template Vector<Scalar> qdd;
    if (!Model::forward_dynamics(t, q, qd, u, p, qdd)) return false;
    typename Model::template Vector<Scalar> qdd_c;
    if (!Model::forward_dynamics(t, q, qd, u, c, qdd_c) || !(qdd_c == qdd)) return false;
    const Scalar scale = Scalar(1) + F.norm() + M.norm() * qdd.norm();
    if ((M * qdd - F).norm() > Scalar(1000) * Eigen::NumTraits<Scalar>::epsilon() * scale) return false;
  }
  return M.allFinite() && F.allFinite() && Xi.allFinite() && Xi_t.allFinite() && b.allFinite() &&
         phi.allFinite() && y.allFinite() && energy == energy && (M - M.transpose()).norm() == Scalar(0) &&
         Mc == M && Fc == F && energy_c == energy;
}

template <class... Models>
std::vector<std::string> failing(const char* const* names) {
  std::vector<std::string> out;
  std::size_t i = 0;
  for (bool ok : {(evaluates_finitely<Models, double>() && evaluates_finitely<Models, float>())...}) {
    if (!ok) out.push_back(names[i]);
    ++i;
  }
  return out;
}

}  // namespace

std::vector<std::string> generated_models_failing_in_double_or_float() {
  static const char* const names[] = {"bead_on_hoop", "cart_pole", "cartesian_pendulum", "double_pendulum",
                                      "four_bar", "heavy_top", "knife_edge", "planar_3rrr", "planar_chain",
                                      "quaternion_rigid_body", "rolling_coin", "simple_pendulum",
                                      "spacecraft_panel", "spherical_pendulum", "spring_mass_damper",
                                      "two_wheeled_robot", "universal_chain"};
  using namespace eomgen_models;
  return failing<bead_on_hoop::Model, cart_pole::Model, cartesian_pendulum::Model, double_pendulum::Model,
                 four_bar::Model, heavy_top::Model, knife_edge::Model, planar_3rrr::Model, planar_chain::Model,
                 quaternion_rigid_body::Model, rolling_coin::Model, simple_pendulum::Model, spacecraft_panel::Model,
                 spherical_pendulum::Model, spring_mass_damper::Model, two_wheeled_robot::Model,
                 universal_chain::Model>(names);
}
