#include "eomgen/derivation/equations_of_motion.hpp"

#include <vector>

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::matrix;

matrix zero3() { return matrix(3, 1); }

bool is_zero(const matrix& m) {
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      if (!m(i, j).is_zero()) return false;
  return true;
}

ex dot3(const matrix& a, const matrix& b) {
  exvector terms;
  for (unsigned i = 0; i < 3; ++i)
    if (!a(i, 0).is_zero() && !b(i, 0).is_zero()) terms.push_back(a(i, 0) * b(i, 0));
  return GiNaC::add(terms);
}

matrix cross3(const matrix& u, const matrix& v) { return cross_matrix(u).mul(v); }

matrix map_entries(const matrix& m, const std::function<ex(const ex&)>& f) {
  matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = f(m(i, j));
  return out;
}

// Kinematics of one frame relative to the inertial frame, recursively from its parent.
struct FrameState {
  matrix C_0f;            // C_{0f}: resolves f-components in the inertial frame
  std::vector<matrix> W;  // partial angular velocities d omega_f / d qd_k, in f
  matrix omega;           // omega^{f0}_f
  matrix alpha0;          // d omega^{f0} / dt seen in 0, at qdd = 0, resolved in f
};

// Kinematics of one point relative to the inertial origin, resolved in the inertial frame.
struct PointState {
  matrix r;               // r^{P w}
  std::vector<matrix> V;  // partial velocities d v_P / d qd_k
  matrix v;               // v^{P w / 0}
  matrix a0;              // acceleration at qdd = 0
};

class Derivation {
 public:
  explicit Derivation(const MechanicalSystem& s)
      : s_(s), vars_(s.variables()), n_(vars_.coordinate_count()), z_(eom_.subexpressions) {}

  EquationsOfMotion run() {
    frame_kinematics();
    point_kinematics();
    m_terms_.assign(n_ * n_, exvector());
    f_terms_.assign(n_, exvector());
    inertia_terms();
    gravity_terms();
    load_terms();
    assemble();
    constraints();
    return std::move(eom_);
  }

 private:
  ex rate_partial(const ex& e, std::size_t k) const {
    return e.diff(GiNaC::ex_to<GiNaC::symbol>(ex(vars_.coordinates()[k].qd)));
  }
  ex coordinate_partial(const ex& e, std::size_t k) const {
    return e.diff(GiNaC::ex_to<GiNaC::symbol>(ex(vars_.coordinates()[k].q)));
  }
  // time derivative at qdd = 0 of a plain (model-symbol) expression
  ex rate_at_zero_acceleration(const ex& e) const {
    return vars_.without_accelerations(vars_.time_derivative(e));
  }

  void frame_kinematics() {
    frames_.resize(s_.frames().size());
    FrameState& root = frames_[0];
    root.C_0f = GiNaC::ex_to<matrix>(GiNaC::unit_matrix(3));
    root.W.assign(n_, zero3());
    root.omega = zero3();
    root.alpha0 = zero3();
    for (std::size_t f = 1; f < s_.frames().size(); ++f) {
      const Frame& frame = s_.frames()[f];
      const FrameState& p = frames_[frame.parent->index];
      FrameState& st = frames_[f];
      const matrix& C_fp = frame.rotation.dcm();
      const matrix& w_rel = frame.relative_angular_velocity;
      st.C_0f = z_.bind(p.C_0f.mul(C_fp.transpose()));
      st.W.resize(n_);
      for (std::size_t k = 0; k < n_; ++k)
        st.W[k] = z_.bind(C_fp.mul(p.W[k]).add(map_entries(w_rel, [&](const ex& e) { return rate_partial(e, k); })));
      // omega^{f0} = omega^{p0} + omega^{fp}
      const matrix w_parent = z_.bind(C_fp.mul(p.omega));
      st.omega = z_.bind(w_parent.add(w_rel));
      // alpha^{f0} = C_fp alpha^{p0} + d(omega_rel)/dt + omega^{p0} x omega^{fp}
      const matrix w_rel_dot = map_entries(w_rel, [&](const ex& e) { return rate_at_zero_acceleration(e); });
      st.alpha0 = z_.bind(C_fp.mul(p.alpha0).add(w_rel_dot).add(cross3(w_parent, w_rel)));
    }
  }

  void point_kinematics() {
    points_.resize(s_.points().size());
    PointState& origin = points_[0];
    origin.r = zero3();
    origin.V.assign(n_, zero3());
    origin.v = zero3();
    origin.a0 = zero3();
    for (std::size_t i = 1; i < s_.points().size(); ++i) {
      const Point& point = s_.points()[i];
      PointState st = points_[point.parent->index];
      for (const auto& [frame_id, r_f] : point.offset.terms()) {
        const FrameState& f = frames_[frame_id.index];
        const matrix rdot = map_entries(r_f, [&](const ex& e) { return vars_.time_derivative(e); });
        const matrix rddot0 = map_entries(rdot, [&](const ex& e) { return vars_.without_accelerations(vars_.time_derivative(e)); });
        st.r = st.r.add(f.C_0f.mul(r_f));
        for (std::size_t k = 0; k < n_; ++k) {
          // V_k += C_0f (d r_f / d q_k + W_k x r_f)
          const matrix local = map_entries(r_f, [&](const ex& e) { return coordinate_partial(e, k); }).add(cross3(f.W[k], r_f));
          if (!is_zero(local)) st.V[k] = st.V[k].add(f.C_0f.mul(local));
        }
        // v += C_0f (r_f' + omega x r_f)
        st.v = st.v.add(f.C_0f.mul(rdot.add(cross3(f.omega, r_f))));
        // a0 += C_0f (r_f'' + alpha0 x r + 2 omega x r_f' + omega x (omega x r))
        const matrix w_x_r = z_.bind(cross3(f.omega, r_f));
        st.a0 = st.a0.add(f.C_0f.mul(rddot0.add(cross3(f.alpha0, r_f))
                                         .add(cross3(f.omega, rdot).mul_scalar(2))
                                         .add(cross3(f.omega, w_x_r))));
      }
      st.r = z_.bind(st.r);
      for (auto& V : st.V) V = z_.bind(V);
      st.v = z_.bind(st.v);
      st.a0 = z_.bind(st.a0);
      points_[i] = std::move(st);
    }
  }

  // resolves a physical vector in the inertial frame through the bound DCMs
  matrix in_inertial(const Vector& v) {
    matrix out = zero3();
    for (const auto& [frame_id, c] : v.terms()) out = out.add(frames_[frame_id.index].C_0f.mul(c));
    return z_.bind(out);
  }

  void add_m(std::size_t j, std::size_t k, const ex& term) {
    if (!term.is_zero()) m_terms_[j * n_ + k].push_back(term);
  }
  void add_f(std::size_t k, const ex& term) {
    if (!term.is_zero()) f_terms_[k].push_back(term);
  }

  void translational_inertia(const ex& mass, const PointState& c) {
    for (std::size_t j = 0; j < n_; ++j) {
      if (is_zero(c.V[j])) continue;
      for (std::size_t k = j; k < n_; ++k) add_m(j, k, mass * dot3(c.V[j], c.V[k]));
      add_f(j, -mass * dot3(c.V[j], c.a0));
    }
    t_terms_.push_back(mass * dot3(c.v, c.v) / 2);
  }

  void inertia_terms() {
    for (const Particle& p : s_.particles()) translational_inertia(p.mass, points_[p.point.index]);
    for (const RigidBody& b : s_.rigid_bodies()) {
      translational_inertia(b.mass, points_[b.mass_centre.index]);
      const FrameState& f = frames_[b.frame.index];
      const matrix& J = b.inertia;
      // rotational part: W_j . J W_k, and the inertia torque J alpha0 + omega x J omega
      std::vector<matrix> JW(n_);
      for (std::size_t k = 0; k < n_; ++k) JW[k] = z_.bind(J.mul(f.W[k]));
      const matrix Jw = z_.bind(J.mul(f.omega));
      const matrix torque = z_.bind(J.mul(f.alpha0).add(cross3(f.omega, Jw)));
      for (std::size_t j = 0; j < n_; ++j) {
        if (is_zero(f.W[j])) continue;
        for (std::size_t k = j; k < n_; ++k) add_m(j, k, dot3(f.W[j], JW[k]));
        add_f(j, -dot3(f.W[j], torque));
      }
      t_terms_.push_back(dot3(f.omega, Jw) / 2);
    }
  }

  void gravity_terms() {
    if (s_.gravity().is_zero()) return;
    const matrix g = in_inertial(s_.gravity());
    auto add_weight = [&](const ex& mass, const PointState& c) {
      // V = -m g . r, generalized force m g . V_k
      v_terms_.push_back(-mass * dot3(g, c.r));
      for (std::size_t k = 0; k < n_; ++k) add_f(k, mass * dot3(g, c.V[k]));
    };
    for (const Particle& p : s_.particles()) add_weight(p.mass, points_[p.point.index]);
    for (const RigidBody& b : s_.rigid_bodies()) add_weight(b.mass, points_[b.mass_centre.index]);
  }

  // the generalized force of each load (and the potential energy of the conservative ones)
  void load_terms() {
    for (const Load& load : s_.loads())
      visit_load(
          load, [&](const PointForce& f) { force_terms(f); }, [&](const BodyMoment& m) { moment_terms(m); },
          [&](const LinearDamper& d) { damper_terms(d); }, [&](const CoordinateDamper& d) { damper_terms(d); },
          [&](const GeneralizedForce& g) { add_f(g.coordinate, g.value); },
          [&](const LinearSpring& sp) { spring_terms(sp); }, [&](const TorsionalSpring& sp) { spring_terms(sp); },
          [&](const Potential& p) { potential_terms(p); });
  }

  void force_terms(const PointForce& f) {
    const matrix force = in_inertial(f.force);
    const PointState& p = points_[f.point.index];
    for (std::size_t k = 0; k < n_; ++k) add_f(k, dot3(force, p.V[k]));
  }

  void moment_terms(const BodyMoment& m) {
    const FrameState& b = frames_[m.frame.index];
    const matrix moment = z_.bind(b.C_0f.transpose().mul(in_inertial(m.moment)));
    for (std::size_t k = 0; k < n_; ++k) add_f(k, dot3(moment, b.W[k]));
  }

  void damper_terms(const LinearDamper& d) {
    // f_a = -c ((v_a - v_b) . e) e along e = r^{ab} / |r^{ab}|
    const PointState& a = points_[d.a.index];
    const PointState& b = points_[d.b.index];
    const matrix r = z_.bind(a.r.sub(b.r));
    const ex length_sq = z_.bind(dot3(r, r));
    const ex along = z_.bind(-d.damping * dot3(r, a.v.sub(b.v)) / length_sq);
    for (std::size_t k = 0; k < n_; ++k) add_f(k, along * dot3(r, a.V[k].sub(b.V[k])));
  }

  void damper_terms(const CoordinateDamper& d) {
    const ex rate = vars_.time_derivative(d.coordinate_expression);
    for (std::size_t k = 0; k < n_; ++k) add_f(k, -d.damping * rate * coordinate_partial(d.coordinate_expression, k));
  }

  void spring_terms(const LinearSpring& sp) {
    // V = k/2 (L - L0)^2; force on a: -k (L - L0) r^{ab} / L
    const PointState& a = points_[sp.a.index];
    const PointState& b = points_[sp.b.index];
    const matrix r = z_.bind(a.r.sub(b.r));
    const ex length = z_.bind(GiNaC::sqrt(dot3(r, r)));
    const ex stretch = length - sp.rest_length;
    v_terms_.push_back(sp.stiffness * GiNaC::pow(stretch, 2) / 2);
    const ex tension = z_.bind(-sp.stiffness * stretch / length);
    for (std::size_t k = 0; k < n_; ++k) add_f(k, tension * dot3(r, a.V[k].sub(b.V[k])));
  }

  void spring_terms(const TorsionalSpring& sp) {
    const ex twist = sp.angle - sp.rest_angle;
    v_terms_.push_back(sp.stiffness * GiNaC::pow(twist, 2) / 2);
    for (std::size_t k = 0; k < n_; ++k) add_f(k, -sp.stiffness * twist * coordinate_partial(sp.angle, k));
  }

  void potential_terms(const Potential& p) {
    v_terms_.push_back(p.value);
    for (std::size_t k = 0; k < n_; ++k) add_f(k, -coordinate_partial(p.value, k));
  }

  void assemble() {
    eom_.coordinate_count = n_;
    eom_.mass_matrix = matrix(n_, n_);
    eom_.forcing = matrix(n_, 1);
    for (std::size_t j = 0; j < n_; ++j) {
      for (std::size_t k = j; k < n_; ++k) {
        const ex entry = GiNaC::add(m_terms_[j * n_ + k]);
        eom_.mass_matrix(j, k) = entry;
        eom_.mass_matrix(k, j) = entry;
      }
      eom_.forcing(j, 0) = GiNaC::add(f_terms_[j]);
    }
    eom_.kinetic_energy = GiNaC::add(t_terms_);
    eom_.potential_energy = GiNaC::add(v_terms_);
  }

  void constraints() {
    const auto& cs = s_.constraints();
    const std::size_t m = cs.size();
    std::size_t holonomic = 0;
    for (const Constraint& c : cs) holonomic += c.kind == Constraint::Kind::holonomic;
    eom_.constraint_count = m;
    eom_.constraint_jacobian = matrix(m, n_);
    eom_.constraint_rate_term = matrix(m, 1);
    eom_.constraint_acceleration_term = matrix(m, 1);
    eom_.holonomic_residuals = matrix(holonomic, 1);
    std::size_t h = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const Constraint& c = cs[i];
      ex rate_form = 0;  // Xi qd + Xi_t
      if (c.kind == Constraint::Kind::holonomic) {
        // Xi = dphi/dq, Xi_t = dphi/dt
        for (std::size_t k = 0; k < n_; ++k) eom_.constraint_jacobian(i, k) = coordinate_partial(c.expression, k);
        eom_.constraint_rate_term(i, 0) = c.expression.diff(vars_.time());
        eom_.holonomic_residuals(h++, 0) = c.expression;
        rate_form = vars_.time_derivative(c.expression);
      } else {
        for (std::size_t k = 0; k < n_; ++k) eom_.constraint_jacobian(i, k) = rate_partial(c.expression, k);
        eom_.constraint_rate_term(i, 0) = vars_.at_rest(c.expression);
        rate_form = c.expression;
      }
      // d/dt (Xi qd + Xi_t) = Xi qdd + (dXi/dt qd + dXi_t/dt): keep the part without qdd
      eom_.constraint_acceleration_term(i, 0) = rate_at_zero_acceleration(rate_form);
    }
  }

  const MechanicalSystem& s_;
  const Variables& vars_;
  const std::size_t n_;
  EquationsOfMotion eom_;
  Subexpressions& z_;
  std::vector<FrameState> frames_;
  std::vector<PointState> points_;
  std::vector<exvector> m_terms_;
  std::vector<exvector> f_terms_;
  exvector t_terms_;
  exvector v_terms_;
};

}  // namespace

EquationsOfMotion derive_equations(const MechanicalSystem& system) { return Derivation(system).run(); }

}  // namespace eomgen
