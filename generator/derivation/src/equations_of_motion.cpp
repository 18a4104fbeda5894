#include "eomgen/derivation/equations_of_motion.hpp"

#include <limits>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/composite_body.hpp"
#include "eomgen/symbolic/expression_size.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"
#include "link_tree.hpp"
#include "operation_estimate.hpp"
#include "parameter_coefficients.hpp"
#include "relative_rotations.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::matrix;

// constraint terms of more tree nodes than this, all together, are bound to intermediates
constexpr double large_constraint_size = 5000;

// The local resolution multiplies out each entry of M, F, T and V; an entry that would
// multiply out to more nodes than this (before like terms combine) stops it. The shipped models'
// largest is the bicycle's, about 31,000; a chain of 12 rods has 8,000.
constexpr double largest_local_entry = 200000;
// the local form is derived until its entries multiplied out pass this many times the inertial
// form's estimated operations (or 1,000, for a model whose inertial form costs next to nothing)
constexpr double local_form_budget = 8;

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

// Kinematics of one point relative to the inertial origin: resolved in the inertial frame, or
// (KinematicsResolution::local) kept as sums of terms each resolved in the frame it arose in.
struct PointState {
  Vector r;               // r^{P w}
  std::vector<Vector> V;  // partial velocities d v_P / d qd_k
  Vector v;               // v^{P w / 0}
  Vector a0;              // acceleration at qdd = 0
};



// the rates of the coordinates, rates and time: d/dt of the model's kinematics
GiNaC::exmap rates(const Variables& vars) {
  GiNaC::exmap out{{vars.time(), 1}};
  for (const Coordinate& c : vars.coordinates()) {
    out[c.q] = c.qd;
    out[c.qd] = c.qdd;
  }
  return out;
}

GiNaC::exmap accelerations_to_zero(const Variables& vars) {
  GiNaC::exmap out;
  for (const Coordinate& c : vars.coordinates()) out[c.qdd] = 0;
  return out;
}

class Derivation {
 public:
  /// `kane`: M and F by Kane's equations; otherwise only the kinematics, T and V (M and F are
  /// then left zero for the recursions to fill).
  /// `local_budget`: in the local resolution, the most nodes all entries may have multiplied out
  /// before grouping; beyond it the local form is given up (multiplied_out() false).
  Derivation(const MechanicalSystem& s, KinematicsResolution resolution, bool kane = true,
             double local_budget = std::numeric_limits<double>::infinity())
      : s_(s), vars_(s.variables()), n_(vars_.coordinate_count()), partials_(kane ? n_ : 0), resolution_(resolution),
        z_(eom_.subexpressions), rotations_(s, eom_.subexpressions), time_derivative_(rates(vars_)),
        without_accelerations_(accelerations_to_zero(vars_)), local_budget_(local_budget) {}

  EquationsOfMotion run() {
    eom_.resolution = resolution_;
    frame_kinematics();
    if (resolution_ == KinematicsResolution::inertial)
      point_kinematics_inertial();
    else
      point_kinematics_local();
    m_terms_.assign(n_ * n_, exvector());
    f_terms_.assign(n_, exvector());
    inertia_terms();
    gravity_terms();
    load_terms();
    assemble();
    constraints();
    return std::move(eom_);
  }

  /// After run() in the local resolution: false if an entry was too large to multiply out, and
  /// the equations are the local form's sums as they arose.
  bool multiplied_out() const { return !too_large_; }

 private:
  ex rate_partial(const ex& e, std::size_t k) const {
    return derivative(e, GiNaC::ex_to<GiNaC::symbol>(ex(vars_.coordinates()[k].qd)));
  }
  ex coordinate_partial(const ex& e, std::size_t k) const {
    return derivative(e, GiNaC::ex_to<GiNaC::symbol>(ex(vars_.coordinates()[k].q)));
  }
  // time derivative at qdd = 0 of a plain (model-symbol) expression
  ex rate_at_zero_acceleration(const ex& e) const {
    return without_accelerations_(time_derivative(e));
  }
  // d/dt of the kinematics: a small expression as Variables takes it (which names a symbol that
  // has no rate), a large one through the derivation's memo (only the language makes those, and
  // it has checked their symbols)
  ex time_derivative(const ex& e) const {
    return is_small_tree(e, small_tree_limit) ? vars_.time_derivative(e) : time_derivative_(e);
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
      if (resolution_ == KinematicsResolution::inertial) st.C_0f = z_.bind(p.C_0f.mul(C_fp.transpose()));
      st.W.resize(n_);
      for (std::size_t k = 0; k < partials_; ++k)
        st.W[k] = z_.bind(C_fp.mul(p.W[k]).add(map_entries(w_rel, [&](const ex& e) { return rate_partial(e, k); })));
      // omega^{f0} = omega^{p0} + omega^{fp}
      const matrix w_parent = z_.bind(C_fp.mul(p.omega));
      st.omega = z_.bind(w_parent.add(w_rel));
      // alpha^{f0} = C_fp alpha^{p0} + d(omega_rel)/dt + omega^{p0} x omega^{fp}
      if (partials_ == 0) continue;  // accelerations serve Kane's F only
      const matrix w_rel_dot = map_entries(w_rel, [&](const ex& e) { return rate_at_zero_acceleration(e); });
      st.alpha0 = z_.bind(C_fp.mul(p.alpha0).add(w_rel_dot).add(cross3(w_parent, w_rel)));
    }
  }

  void start_points() {
    points_.resize(s_.points().size());
    points_[0].V.assign(n_, Vector());
  }

  // the partial velocity of an offset r_f (in frame f) with respect to qd_k, in f
  matrix offset_partial(const FrameState& f, const matrix& r_f, std::size_t k) const {
    return map_entries(r_f, [&](const ex& e) { return coordinate_partial(e, k); }).add(cross3(f.W[k], r_f));
  }

  // the acceleration at qdd = 0 of an offset r_f (in frame f): r'' + alpha0 x r + 2 omega x r' +
  // omega x (omega x r), with omega x r given (bound or not)
  matrix offset_acceleration(const FrameState& f, const matrix& r_f, const matrix& w_x_r) const {
    const matrix rdot = map_entries(r_f, [&](const ex& e) { return time_derivative(e); });
    const matrix rddot0 = map_entries(rdot, [&](const ex& e) { return rate_at_zero_acceleration(e); });
    return rddot0.add(cross3(f.alpha0, r_f)).add(cross3(f.omega, rdot).mul_scalar(2)).add(cross3(f.omega, w_x_r));
  }

  matrix offset_velocity(const FrameState& f, const matrix& r_f) const {
    return map_entries(r_f, [&](const ex& e) { return time_derivative(e); }).add(cross3(f.omega, r_f));
  }

  void point_kinematics_inertial() {
    start_points();
    const FrameId inertial = s_.inertial_frame();
    for (std::size_t i = 1; i < s_.points().size(); ++i) {
      const Point& point = s_.points()[i];
      const PointState& parent = points_[point.parent->index];
      matrix r = inertial_components(parent.r), v = inertial_components(parent.v),
             a0 = inertial_components(parent.a0);
      std::vector<matrix> V(n_);
      for (std::size_t k = 0; k < partials_; ++k) V[k] = inertial_components(parent.V[k]);
      for (const auto& [frame_id, r_f] : point.offset.terms()) {
        const FrameState& f = frames_[frame_id.index];
        r = r.add(f.C_0f.mul(r_f));
        for (std::size_t k = 0; k < partials_; ++k) {
          const matrix local = offset_partial(f, r_f, k);
          if (!is_zero(local)) V[k] = V[k].add(f.C_0f.mul(local));
        }
        v = v.add(f.C_0f.mul(offset_velocity(f, r_f)));
        if (partials_ > 0) a0 = a0.add(f.C_0f.mul(offset_acceleration(f, r_f, z_.bind(cross3(f.omega, r_f)))));
      }
      PointState& st = points_[i];
      st.r = Vector(inertial, z_.bind(r));
      st.V.resize(n_);
      for (std::size_t k = 0; k < partials_; ++k) st.V[k] = Vector(inertial, z_.bind(V[k]));
      st.v = Vector(inertial, z_.bind(v));
      if (partials_ > 0) st.a0 = Vector(inertial, z_.bind(a0));
    }
  }

  void point_kinematics_local() {
    start_points();
    for (std::size_t i = 1; i < s_.points().size(); ++i) {
      const Point& point = s_.points()[i];
      PointState st = points_[point.parent->index];
      for (const auto& [frame_id, r_f] : point.offset.terms()) {
        const FrameState& f = frames_[frame_id.index];
        st.r += Vector(frame_id, r_f);
        for (std::size_t k = 0; k < partials_; ++k) st.V[k] += Vector(frame_id, offset_partial(f, r_f, k));
        st.v += Vector(frame_id, offset_velocity(f, r_f));
        st.a0 += Vector(frame_id, offset_acceleration(f, r_f, cross3(f.omega, r_f)));
      }
      points_[i] = std::move(st);
    }
  }

  // the components of a vector of the inertial resolution (zero or one term, in the inertial frame)
  static matrix inertial_components(const Vector& v) { return v.is_zero() ? zero3() : v.terms().front().second; }

  // u . v, resolving each term of v in the frame of each term of u
  ex dot(const Vector& u, const Vector& v) {
    exvector terms;
    for (const auto& [frame, c] : u.terms()) terms.push_back(dot3(c, rotations_.resolve(v, frame)));
    return GiNaC::add(terms);
  }

  // a load's vector as the derivation resolves vectors: in the inertial frame, or as given
  Vector physical(const Vector& v) {
    switch (resolution_) {
      case KinematicsResolution::inertial: return Vector(s_.inertial_frame(), in_inertial(v));
      case KinematicsResolution::local: return v;
    }
    EOMGEN_UNREACHABLE("Derivation::physical: a KinematicsResolution outside its enumerators");
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
    for (std::size_t j = 0; j < partials_; ++j) {
      if (c.V[j].is_zero()) continue;
      for (std::size_t k = j; k < partials_; ++k) add_m(j, k, mass * dot(c.V[j], c.V[k]));
      add_f(j, -mass * dot(c.V[j], c.a0));
    }
    t_terms_.push_back(mass * dot(c.v, c.v) / 2);
  }

  // bound in the inertial resolution; the local one multiplies its entries out instead, so that
  // their parameter-only factors meet those of the other bodies
  matrix shared(const matrix& m) { return resolution_ == KinematicsResolution::inertial ? z_.bind(m) : m; }

  void inertia_terms() {
    for (const Particle& p : s_.particles()) translational_inertia(p.mass, points_[p.point.index]);
    for (const RigidBody& b : s_.rigid_bodies()) {
      translational_inertia(b.mass, points_[b.mass_centre.index]);
      const FrameState& f = frames_[b.frame.index];
      const matrix& J = b.inertia;
      // rotational part: W_j . J W_k, and the inertia torque J alpha0 + omega x J omega
      std::vector<matrix> JW(n_);
      for (std::size_t k = 0; k < partials_; ++k) JW[k] = shared(J.mul(f.W[k]));
      const matrix Jw = shared(J.mul(f.omega));
      t_terms_.push_back(dot3(f.omega, Jw) / 2);
      if (partials_ == 0) continue;
      const matrix torque = shared(J.mul(f.alpha0).add(cross3(f.omega, Jw)));
      for (std::size_t j = 0; j < partials_; ++j) {
        if (is_zero(f.W[j])) continue;
        for (std::size_t k = j; k < partials_; ++k) add_m(j, k, dot3(f.W[j], JW[k]));
        add_f(j, -dot3(f.W[j], torque));
      }
    }
  }

  void gravity_terms() {
    if (s_.gravity().is_zero()) return;
    const Vector g = physical(s_.gravity());
    auto add_weight = [&](const ex& mass, const PointState& c) {
      // V = -m g . r, generalized force m g . V_k
      v_terms_.push_back(-mass * dot(g, c.r));
      for (std::size_t k = 0; k < partials_; ++k) add_f(k, mass * dot(g, c.V[k]));
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
    if (partials_ == 0) return;
    const Vector force = physical(f.force);
    const PointState& p = points_[f.point.index];
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, dot(force, p.V[k]));
  }

  void moment_terms(const BodyMoment& m) {
    if (partials_ == 0) return;
    const FrameState& b = frames_[m.frame.index];
    const matrix moment = resolution_ == KinematicsResolution::inertial
                              ? z_.bind(b.C_0f.transpose().mul(in_inertial(m.moment)))
                              : rotations_.resolve(m.moment, m.frame);
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, dot3(moment, b.W[k]));
  }

  // r^{ab}, bound in the inertial resolution (a spring or damper uses it several times)
  Vector separation(const PointState& a, const PointState& b) {
    const Vector r = a.r - b.r;
    switch (resolution_) {
      case KinematicsResolution::inertial: return Vector(s_.inertial_frame(), z_.bind(inertial_components(r)));
      case KinematicsResolution::local: return r;
    }
    EOMGEN_UNREACHABLE("Derivation::separation: a KinematicsResolution outside its enumerators");
  }

  void damper_terms(const LinearDamper& d) {
    if (partials_ == 0) return;
    // f_a = -c ((v_a - v_b) . e) e along e = r^{ab} / |r^{ab}|
    const PointState& a = points_[d.a.index];
    const PointState& b = points_[d.b.index];
    const Vector r = separation(a, b);
    const ex length_sq = z_.bind(dot(r, r));
    const ex along = z_.bind(-d.damping * dot(r, a.v - b.v) / length_sq);
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, along * dot(r, a.V[k] - b.V[k]));
  }

  void damper_terms(const CoordinateDamper& d) {
    const ex rate = vars_.time_derivative(d.coordinate_expression);
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, -d.damping * rate * coordinate_partial(d.coordinate_expression, k));
  }

  void spring_terms(const LinearSpring& sp) {
    // V = k/2 (L - L0)^2; force on a: -k (L - L0) r^{ab} / L
    const PointState& a = points_[sp.a.index];
    const PointState& b = points_[sp.b.index];
    const Vector r = separation(a, b);
    const ex length = z_.bind(GiNaC::sqrt(dot(r, r)));
    const ex stretch = length - sp.rest_length;
    v_terms_.push_back(sp.stiffness * GiNaC::pow(stretch, 2) / 2);
    if (partials_ == 0) return;
    const ex tension = z_.bind(-sp.stiffness * stretch / length);
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, tension * dot(r, a.V[k] - b.V[k]));
  }

  void spring_terms(const TorsionalSpring& sp) {
    const ex twist = sp.angle - sp.rest_angle;
    v_terms_.push_back(sp.stiffness * GiNaC::pow(twist, 2) / 2);
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, -sp.stiffness * twist * coordinate_partial(sp.angle, k));
  }

  void potential_terms(const Potential& p) {
    v_terms_.push_back(p.value);
    for (std::size_t k = 0; k < partials_; ++k) add_f(k, -coordinate_partial(p.value, k));
  }

  // a sum of terms; in the local resolution multiplied out and grouped by the state-dependent
  // monomials, with one parameter-only coefficient each
  ex total(const exvector& terms) {
    const ex sum = GiNaC::add(terms);
    switch (resolution_) {
      case KinematicsResolution::inertial: return sum;
      case KinematicsResolution::local:
        // multiplied out, a sum of products of sums can be exponentially larger than its
        // graph (points defined from other points' positions inside functions): then the
        // local form is not worth its cost, and not made
        if (too_large_) return sum;
        const double nodes = expanded_sizes_.expanded(sum).nodes;
        multiplied_out_nodes_ += nodes;
        if (nodes > largest_local_entry || multiplied_out_nodes_ > local_budget_) {
          too_large_ = true;
          return sum;
        }
        return collect_parameter_coefficients(sum.expand(), vars_);
    }
    EOMGEN_UNREACHABLE("Derivation::total: a KinematicsResolution outside its enumerators");
  }

  void assemble() {
    eom_.coordinate_count = n_;
    eom_.mass_matrix = matrix(n_, n_);
    eom_.forcing = matrix(n_, 1);
    for (std::size_t j = 0; j < n_; ++j) {
      for (std::size_t k = j; k < n_; ++k) {
        const ex entry = total(m_terms_[j * n_ + k]);
        eom_.mass_matrix(j, k) = entry;
        eom_.mass_matrix(k, j) = entry;
      }
      eom_.forcing(j, 0) = total(f_terms_[j]);
    }
    eom_.kinetic_energy = total(t_terms_);
    eom_.potential_energy = total(v_terms_);
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
        eom_.constraint_rate_term(i, 0) = derivative(c.expression, vars_.time());
        eom_.holonomic_residuals(h++, 0) = c.expression;
        rate_form = vars_.time_derivative(c.expression);
      } else {
        for (std::size_t k = 0; k < n_; ++k) eom_.constraint_jacobian(i, k) = rate_partial(c.expression, k);
        eom_.constraint_rate_term(i, 0) = vars_.at_rest(c.expression);
        rate_form = c.expression;
      }
      // d/dt (Xi qd + Xi_t) = Xi qdd + (dXi/dt qd + dXi_t/dt): keep the part without qdd. Through
      // the derivation's memo whatever the size: a wheel's rows share their contact's kinematics,
      // which GiNaC's tree walk took apart again for each row (a seventh of the bicycle's
      // linearize); the result is the same expression.
      eom_.constraint_acceleration_term(i, 0) = without_accelerations_(time_derivative_(rate_form));
    }
    share_large_constraint_terms();
  }

  // The constraints are differentiated in model symbols, outside the shared kinematics: a
  // contact point such as a steered wheel's makes b a tree of some 10,000 nodes per row, with
  // the same pieces repeated by the product rule. Bound to intermediates, printing,
  // linearization (which differentiates them again) and emission see a graph instead. Small
  // constraints stay as derived: the forms one writes by hand.
  void share_large_constraint_terms() {
    std::vector<matrix*> parts{&eom_.constraint_jacobian, &eom_.constraint_rate_term,
                               &eom_.constraint_acceleration_term, &eom_.holonomic_residuals};
    GiNaC::lst all;
    for (const matrix* part : parts)
      for (unsigned i = 0; i < part->rows(); ++i)
        for (unsigned j = 0; j < part->cols(); ++j) all.append((*part)(i, j));
    if (tree_size(all) <= large_constraint_size) return;
    const ex shared = z_.share(all);
    std::size_t k = 0;
    for (matrix* part : parts)
      for (unsigned i = 0; i < part->rows(); ++i)
        for (unsigned j = 0; j < part->cols(); ++j) (*part)(i, j) = shared.op(k++);
  }

  const MechanicalSystem& s_;
  const Variables& vars_;
  const std::size_t n_;
  // partial velocities computed: n_ for Kane's equations, none when the recursions give M and F
  const std::size_t partials_;
  const KinematicsResolution resolution_;
  EquationsOfMotion eom_;
  Subexpressions& z_;
  RelativeRotations rotations_;
  // d/dt and qdd = 0 of the kinematics, each shared node of points defined from one another's
  // positions taken once for the whole derivation (graph_calculus.hpp)
  mutable DirectionalDerivative time_derivative_;
  mutable Substitution without_accelerations_;
  std::vector<FrameState> frames_;
  std::vector<PointState> points_;
  std::vector<exvector> m_terms_;
  std::vector<exvector> f_terms_;
  exvector t_terms_;
  exvector v_terms_;
  ExpressionSizes expanded_sizes_;
  bool too_large_ = false;  // an entry of the local form was too large to multiply out
  const double local_budget_;
  double multiplied_out_nodes_ = 0;  // by the local form so far
};

}  // namespace

namespace {

// the equations in one resolution with their estimate; `multiplied_out` false where the local
// resolution found an entry too large to multiply out
EquationsOfMotion derive(const MechanicalSystem& system, KinematicsResolution resolution, bool& multiplied_out,
                         double local_budget = std::numeric_limits<double>::infinity()) {
  Derivation derivation(system, resolution, /*kane=*/true, local_budget);
  EquationsOfMotion eom = derivation.run();
  multiplied_out = derivation.multiplied_out();
  const double not_tried = std::numeric_limits<double>::quiet_NaN();
  const double estimate = multiplied_out ? estimated_operations(eom.mass_matrix, eom.forcing, eom.subexpressions,
                                                                system.variables())
                                         : not_tried;
  eom.estimated_operations_inertial = resolution == KinematicsResolution::inertial ? estimate : not_tried;
  eom.estimated_operations_local = resolution == KinematicsResolution::local ? estimate : not_tried;
  return eom;
}

}  // namespace

EquationsOfMotion derive_equations(const MechanicalSystem& system, KinematicsResolution resolution) {
  bool multiplied_out = true;
  return derive(system, resolution, multiplied_out);
}

EquationsOfMotion derive_equations(const MechanicalSystem& system) {
  const std::size_t n = system.variables().coordinate_count();
  if (n > local_resolution_limit && std::holds_alternative<LinkTree>(link_tree(system))) {
    // a long tree: its kinematics, T and V here, M and F from the recursions
    EquationsOfMotion eom = Derivation(system, KinematicsResolution::inertial, /*kane=*/false).run();
    std::variant<RecursiveMassMatrixAndForcing, std::string> recursive =
        derive_composite_body_terms(system, eom.subexpressions);
    auto* terms = std::get_if<RecursiveMassMatrixAndForcing>(&recursive);
    EOMGEN_DEMAND(terms != nullptr, "a link tree without recursive M and F");
    eom.mass_matrix = std::move(terms->mass_matrix);
    eom.forcing = std::move(terms->forcing);
    eom.dynamics = DynamicsForm::recursions;
    const double not_tried = std::numeric_limits<double>::quiet_NaN();
    eom.estimated_operations_inertial = eom.estimated_operations_local = not_tried;
    eom.estimated_operations_recursions =
        estimated_operations(eom.mass_matrix, eom.forcing, eom.subexpressions, system.variables());
    return eom;
  }
  bool multiplied_out = true;
  EquationsOfMotion inertial = derive(system, KinematicsResolution::inertial, multiplied_out);
  // the local resolution grows like the fourth power of a chain's depth: tried on small models
  // only, and kept when its code is smaller
  if (system.variables().coordinate_count() > local_resolution_limit) return inertial;
  // and given up once its entries, multiplied out, pass a multiple of the inertial form's
  // estimate: grouping shrinks them, but not by that much (a robot arm's 3D offsets multiply
  // out to eight times the inertial form's operations, and deriving them took most of the time)
  EquationsOfMotion local = derive(system, KinematicsResolution::local, multiplied_out,
                                   local_form_budget * std::max(inertial.estimated_operations_inertial, 1000.0));
  if (!multiplied_out) return inertial;
  local.estimated_operations_inertial = inertial.estimated_operations_inertial;
  inertial.estimated_operations_local = local.estimated_operations_local;
  return local.estimated_operations_local < inertial.estimated_operations_inertial ? std::move(local)
                                                                                    : std::move(inertial);
}

}  // namespace eomgen
