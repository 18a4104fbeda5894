#include "load_forces.hpp"

#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

class LoadForces {
 public:
  explicit LoadForces(const MechanicalSystem& s) : s_(s), vars_(s.variables()), Q_(vars_.coordinate_count(), 0) {}

  GiNaC::exvector run() {
    for (const Load& load : s_.loads())
      visit_load(
          load, [&](const PointForce& f) { point_force(f); }, [&](const BodyMoment& m) { moment(m); },
          [&](const LinearDamper& d) { damper(d); }, [&](const CoordinateDamper& d) { damper(d); },
          [&](const GeneralizedForce& g) { Q_[g.coordinate] += g.value; },
          [&](const LinearSpring& sp) { spring(sp); }, [&](const TorsionalSpring& sp) { spring(sp); },
          [&](const Potential& p) { potential(p); });
    return Q_;
  }

 private:
  // the model's own symbols: ex_to of a temporary ex(symbol) would name the heap copy that the
  // temporary owns, freed at the end of the return statement
  const GiNaC::symbol& rate(std::size_t k) const { return vars_.coordinates()[k].qd; }
  const GiNaC::symbol& coordinate(std::size_t k) const { return vars_.coordinates()[k].q; }
  Vector rate_partial(const Vector& v, std::size_t k) const {
    return v.map_components([&](const ex& e) { return derivative(e, rate(k)); });
  }

  void point_force(const PointForce& f) {
    const Vector v = velocity(s_, f.point);
    for (std::size_t k = 0; k < Q_.size(); ++k) Q_[k] += dot(s_, f.force, rate_partial(v, k));
  }

  void moment(const BodyMoment& m) {
    const Vector w = angular_velocity(s_, m.frame, s_.inertial_frame());
    for (std::size_t k = 0; k < Q_.size(); ++k) Q_[k] += dot(s_, m.moment, rate_partial(w, k));
  }

  // a force along r = r^{ab} of size `along` |r| on a (and its opposite on b)
  void along_line(PointId a, PointId b, const Vector& r, const ex& along) {
    const Vector v = velocity(s_, a) - velocity(s_, b);
    for (std::size_t k = 0; k < Q_.size(); ++k) Q_[k] += along * dot(s_, r, rate_partial(v, k));
  }

  void damper(const LinearDamper& d) {
    const Vector r = position(s_, d.a, d.b);
    const Vector v = velocity(s_, d.a) - velocity(s_, d.b);
    along_line(d.a, d.b, r, -d.damping * dot(s_, r, v) / dot(s_, r, r));
  }

  void damper(const CoordinateDamper& d) {
    const ex rate_of = vars_.time_derivative(d.coordinate_expression);
    for (std::size_t k = 0; k < Q_.size(); ++k)
      Q_[k] += -d.damping * rate_of * derivative(d.coordinate_expression, coordinate(k));
  }

  void spring(const LinearSpring& sp) {
    // V = k/2 (L - L0)^2: tension -k (L - L0) / L along r^{ab}
    const Vector r = position(s_, sp.a, sp.b);
    const ex length = GiNaC::sqrt(dot(s_, r, r));
    along_line(sp.a, sp.b, r, -sp.stiffness * (length - sp.rest_length) / length);
  }

  void spring(const TorsionalSpring& sp) {
    for (std::size_t k = 0; k < Q_.size(); ++k)
      Q_[k] += -sp.stiffness * (sp.angle - sp.rest_angle) * derivative(sp.angle, coordinate(k));
  }

  void potential(const Potential& p) {
    for (std::size_t k = 0; k < Q_.size(); ++k) Q_[k] += -derivative(p.value, coordinate(k));
  }

  const MechanicalSystem& s_;
  const Variables& vars_;
  GiNaC::exvector Q_;
};

}  // namespace

GiNaC::exvector generalized_load_forces(const MechanicalSystem& system) { return LoadForces(system).run(); }

}  // namespace eomgen
