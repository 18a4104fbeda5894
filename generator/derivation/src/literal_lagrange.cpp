#include "eomgen/derivation/literal_lagrange.hpp"

#include "eomgen/mechanics/kinematics.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

ex dot3(const matrix& a, const matrix& b) { return a(0, 0) * b(0, 0) + a(1, 0) * b(1, 0) + a(2, 0) * b(2, 0); }

const GiNaC::symbol& sym(const ex& e) { return GiNaC::ex_to<GiNaC::symbol>(e); }

matrix partial(const matrix& m, const ex& variable) {
  matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = m(i, j).diff(sym(variable));
  return out;
}

// The potential energy V of the conservative loads, and the generalized forces Q of the others
// by virtual work: Q_k = f . dv/dqd_k
void load_terms(const MechanicalSystem& s, ex& V, GiNaC::exvector& Q) {
  const Variables& vars = s.variables();
  const auto& coords = vars.coordinates();
  const FrameId inertial = s.inertial_frame();
  auto rate_partials = [&](const matrix& v, const matrix& f) {
    for (std::size_t k = 0; k < coords.size(); ++k) Q[k] += dot3(f, partial(v, coords[k].qd));
  };
  for (const Load& load : s.loads())
    visit_load(
        load,
        [&](const PointForce& f) {
          rate_partials(resolve(s, velocity(s, f.point), inertial), resolve(s, f.force, inertial));
        },
        [&](const BodyMoment& m) {
          rate_partials(resolve(s, angular_velocity(s, m.frame, inertial), inertial), resolve(s, m.moment, inertial));
        },
        [&](const LinearDamper& d) {
          const matrix r = resolve(s, position(s, d.a, d.b), inertial);
          const matrix rel = resolve(s, velocity(s, d.a), inertial).sub(resolve(s, velocity(s, d.b), inertial));
          const ex rate = dot3(r, rel) / GiNaC::sqrt(dot3(r, r));  // dL/dt along the line
          const ex L = GiNaC::sqrt(dot3(r, r));
          for (std::size_t k = 0; k < coords.size(); ++k) Q[k] += -d.damping * rate * L.diff(sym(coords[k].q));
        },
        [&](const CoordinateDamper& d) {
          const ex rate = vars.time_derivative(d.coordinate_expression);
          for (std::size_t k = 0; k < coords.size(); ++k) Q[k] += -d.damping * rate * rate.diff(sym(coords[k].qd));
        },
        [&](const GeneralizedForce& g) { Q[g.coordinate] += g.value; },
        [&](const LinearSpring& sp) {
          const matrix r = resolve(s, position(s, sp.a, sp.b), inertial);
          V += sp.stiffness * GiNaC::pow(GiNaC::sqrt(dot3(r, r)) - sp.rest_length, 2) / 2;
        },
        [&](const TorsionalSpring& sp) { V += sp.stiffness * GiNaC::pow(sp.angle - sp.rest_angle, 2) / 2; },
        [&](const Potential& p) { V += p.value; });
}

}  // namespace

LiteralLagrangeEquations derive_equations_literally(const MechanicalSystem& s) {
  const Variables& vars = s.variables();
  const auto& coords = vars.coordinates();
  const std::size_t n = coords.size();
  const FrameId inertial = s.inertial_frame();

  auto v_inertial = [&](PointId p) { return resolve(s, velocity(s, p), inertial); };
  auto r_inertial = [&](PointId p) { return resolve(s, position(s, p, s.origin()), inertial); };
  const matrix g = resolve(s, s.gravity(), inertial);

  // T and V written out
  ex T = 0, V = 0;
  auto translational = [&](const ex& mass, PointId c) {
    const matrix v = v_inertial(c);
    T += mass * dot3(v, v) / 2;
    V += -mass * dot3(g, r_inertial(c));
  };
  for (const Particle& p : s.particles()) translational(p.mass, p.point);
  for (const RigidBody& b : s.rigid_bodies()) {
    translational(b.mass, b.mass_centre);
    const matrix w = resolve(s, angular_velocity(s, b.frame, inertial), b.frame);
    T += dot3(w, b.inertia.mul(w)) / 2;
  }
  GiNaC::exvector Q(n, ex(0));
  load_terms(s, V, Q);

  LiteralLagrangeEquations out;
  out.kinetic_energy = T;
  out.potential_energy = V;
  out.mass_matrix = matrix(n, n);
  out.forcing = matrix(n, 1);
  const ex L = T - V;
  for (std::size_t k = 0; k < n; ++k) {
    const ex momentum = L.diff(sym(coords[k].qd));
    const ex momentum_rate = vars.time_derivative(momentum);
    for (std::size_t j = 0; j < n; ++j) out.mass_matrix(k, j) = momentum_rate.diff(sym(coords[j].qdd));
    // everything except M qdd moved to the right-hand side
    out.forcing(k, 0) = -vars.without_accelerations(momentum_rate) + L.diff(sym(coords[k].q)) + Q[k];
  }
  return out;
}

}  // namespace eomgen
