#include "spatial_tree.hpp"

#include <functional>

#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/mechanics/rotation.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"
#include "load_forces.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix map_entries(const matrix& m, const std::function<ex(const ex&)>& f) {
  matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = f(m(i, j));
  return out;
}

matrix cross3(const matrix& u, const matrix& v) { return cross_matrix(u).mul(v); }

// the 3x3 block of a 6x6 matrix at (row, column)
matrix sub_block(const matrix& m, unsigned row, unsigned column) {
  matrix out(3, 3);
  for (unsigned r = 0; r < 3; ++r)
    for (unsigned c = 0; c < 3; ++c) out(r, c) = m(row + r, column + c);
  return out;
}

// [[A, B], [B^T, C]]
matrix symmetric_blocks(const matrix& A, const matrix& B, const matrix& C) {
  matrix out(6, 6);
  for (unsigned r = 0; r < 3; ++r)
    for (unsigned c = 0; c < 3; ++c) {
      out(r, c) = A(r, c);
      out(r + 3, c + 3) = C(r, c);
      out(r, c + 3) = B(r, c);
      out(c + 3, r) = B(r, c);
    }
  return out;
}

}  // namespace

matrix spatial_block(const matrix& v, unsigned first) {
  return matrix(3, 1, GiNaC::lst{v(first, 0), v(first + 1, 0), v(first + 2, 0)});
}

matrix stacked(const matrix& top, const matrix& bottom) {
  matrix out(6, 1);
  for (unsigned i = 0; i < 3; ++i) {
    out(i, 0) = top(i, 0);
    out(i + 3, 0) = bottom(i, 0);
  }
  return out;
}

SpatialTree::SpatialTree(const MechanicalSystem& system, LinkTree tree, Subexpressions& z)
    : s_(system), vars_(system.variables()), links_(std::move(tree.links)), z_(z), has_children_(links_.size(), false) {
  for (const Link& link : links_)
    if (link.parent) has_children_[*link.parent] = true;
  joints_.reserve(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    joints_.push_back(make_joint(i));
    centre_offsets_.push_back(resolve(s_, position(s_, links_[i].centre, links_[i].origin), links_[i].frame));
  }
}

// The relative kinematics come from the plain functions: they involve only J(i). Resolved in
// f_i, where the joint's own terms are usually given, they need no trigonometric identities.
SpatialJoint SpatialTree::make_joint(std::size_t i) const {
  const Link& link = links_[i];
  const Link* p = link.parent ? &links_[*link.parent] : nullptr;
  const FrameId fp = p ? p->frame : s_.inertial_frame();
  const matrix omega_p = p ? joints_[*link.parent].omega : matrix(3, 1);
  const Vector r = position(s_, link.origin, p ? p->origin : s_.origin());
  const Vector r_rate = time_derivative(s_, r, fp);
  const matrix v_rel = resolve(s_, r_rate, link.frame);
  const matrix a_rel = map_entries(resolve(s_, time_derivative(s_, r_rate, fp), link.frame),
                                   [&](const ex& e) { return vars_.without_accelerations(e); });
  const matrix w_rel = resolve(s_, angular_velocity(s_, link.frame, fp), link.frame);
  const auto rate_partial = [&](const ex& e, std::size_t k) {
    return derivative(e, GiNaC::ex_to<GiNaC::symbol>(ex(vars_.coordinates()[k].qd)));
  };
  SpatialJoint j;
  j.E = z_.bind(dcm(s_, link.frame, fp));
  const matrix r_child = resolve(s_, r, link.frame), r_parent = resolve(s_, r, fp);
  const auto moves = [&](const matrix& v) {
    for (unsigned k = 0; k < 3; ++k)
      if (vars_.contains(v(k, 0), SymbolKind::coordinate)) return true;
    return false;
  };
  j.turn = turn_of(link, fp);
  j.r = z_.bind(r_child);
  if (moves(r_child) && !moves(r_parent)) {
    j.r_parent = z_.bind(r_parent);
    j.shift_in_parent = true;
  }
  j.S = matrix(6, static_cast<unsigned>(link.joint.size()));
  for (unsigned c = 0; c < link.joint.size(); ++c)
    for (unsigned row = 0; row < 3; ++row) {
      j.S(row, c) = z_.bind(rate_partial(w_rel(row, 0), link.joint[c]));
      j.S(row + 3, c) = z_.bind(rate_partial(v_rel(row, 0), link.joint[c]));
    }
  // omega_i = E omega_p + omega_rel
  const matrix w = z_.bind(j.E.mul(omega_p));
  const matrix w_rel_bound = z_.bind(w_rel);
  j.omega = z_.bind(w.add(w_rel_bound));
  // alpha: d(omega_rel)/dt + w x omega_rel; a: w x (w x r) + 2 w x v_rel + a_rel, w = E omega_p
  const matrix alpha =
      map_entries(w_rel, [&](const ex& e) { return vars_.without_accelerations(vars_.time_derivative(e)); })
          .add(cross3(w, w_rel_bound));
  // w x (w x r) = E (omega_p x (omega_p x r_p)): by the constants r_p where the shift is made
  // in the parent
  const matrix centripetal =
      j.shift_in_parent ? j.E.mul(z_.bind(cross3(omega_p, z_.bind(cross3(omega_p, j.r_parent)))))
                        : cross3(w, z_.bind(cross3(w, j.r)));
  const matrix a = centripetal.add(cross3(w, z_.bind(v_rel)).mul_scalar(2)).add(a_rel);
  j.zeta = z_.bind(stacked(alpha, a));
  return j;
}

GiNaC::exvector SpatialTree::load_forces() const {
  GiNaC::exvector tau = generalized_load_forces(s_);
  for (ex& Q : tau) Q = z_.bind(Q);
  return tau;
}

matrix SpatialTree::ground_acceleration() const {
  return stacked(matrix(3, 1), resolve(s_, s_.gravity(), s_.inertial_frame()).mul_scalar(-1));
}

// J_o = J - m c^x c^x, the inertia about the origin
matrix SpatialTree::origin_inertia(std::size_t i) const {
  const Link& link = links_[i];
  const matrix C = cross_matrix(centre_offsets_[i]);
  return link.inertia.sub(C.mul(C).mul_scalar(link.mass));
}

matrix SpatialTree::spatial_inertia(std::size_t i) const {
  const Link& link = links_[i];
  const matrix J = origin_inertia(i), mC = cross_matrix(centre_offsets_[i]).mul_scalar(link.mass);
  matrix M(6, 6);
  for (unsigned r = 0; r < 3; ++r) {
    for (unsigned c = 0; c < 3; ++c) {
      M(r, c) = J(r, c).expand();
      M(r, c + 3) = mC(r, c);
      M(r + 3, c) = -mC(r, c);
    }
    M(r + 3, r + 3) = link.mass;
  }
  return M;
}

matrix SpatialTree::velocity_product_force(std::size_t i) const {
  const matrix& w = joints_[i].omega;
  const matrix& c = centre_offsets_[i];
  const matrix n = cross3(w, z_.bind(origin_inertia(i).mul(w)));
  const matrix f = c.is_zero_matrix() ? matrix(3, 1) : cross3(w, z_.bind(cross3(w, c))).mul_scalar(links_[i].mass);
  return stacked(n, f);
}

// Phi (alpha; a) = (w; E a + w x r) with w = E alpha; with r_p = E^T r, E a + w x r = E (a + alpha x r_p)
matrix SpatialTree::motion_to_link(std::size_t i, const matrix& A) const {
  const SpatialJoint& j = joints_[i];
  const matrix alpha = spatial_block(A, 0);
  const matrix w = z_.bind(j.E.mul(alpha));
  if (j.shift_in_parent) return stacked(w, j.E.mul(z_.bind(spatial_block(A, 3).add(cross3(alpha, j.r_parent)))));
  return stacked(w, j.E.mul(spatial_block(A, 3)).add(cross3(w, j.r)));
}

// Phi^T (n; f) = (E^T (n + r x f); E^T f) = (E^T n + r_p x E^T f; E^T f)
matrix SpatialTree::force_to_parent(std::size_t i, const matrix& F) const {
  const SpatialJoint& j = joints_[i];
  const matrix f = z_.bind(spatial_block(F, 3));
  const matrix Et = j.E.transpose();
  if (j.shift_in_parent) {
    const matrix f_p = z_.bind(Et.mul(f));
    return stacked(Et.mul(spatial_block(F, 0)).add(cross3(j.r_parent, f_p)), f_p);
  }
  return stacked(Et.mul(spatial_block(F, 0).add(cross3(j.r, f))), Et.mul(f));
}

// E = C_k(q) F: F = E at q = 0, a signed permutation, and C_k(q) F equal to E term by term
std::optional<SpatialJoint::Turn> SpatialTree::turn_of(const Link& link, FrameId fp) const {
  if (link.joint.size() != 1) return std::nullopt;
  const ex q = vars_.coordinates()[link.joint[0]].q;
  const matrix E = dcm(s_, link.frame, fp);
  matrix F(3, 3);
  for (unsigned r = 0; r < 3; ++r)
    for (unsigned c = 0; c < 3; ++c) {
      F(r, c) = E(r, c).subs(q == 0).eval();
      if (!(F(r, c).is_zero() || F(r, c).is_equal(1) || F(r, c).is_equal(-1))) return std::nullopt;
    }
  for (int axis = 1; axis <= 3; ++axis) {
    const matrix turned = principal_rotation(axis, q).mul(F);
    bool equal = true;
    for (unsigned r = 0; r < 3 && equal; ++r)
      for (unsigned c = 0; c < 3 && equal; ++c) equal = (E(r, c) - turned(r, c)).expand().is_zero();
    if (!equal) continue;
    const ex c = z_.bind(GiNaC::cos(q)), s = z_.bind(GiNaC::sin(q));
    return SpatialJoint::Turn{axis, F, c, s, z_.bind(s * s), z_.bind(s * c)};
  }
  return std::nullopt;
}

// C_k^T A C_k with the entries of the plane (a, b) of the turn written in sin^2 q and sin q cos q
// (shared by the joint): with d = p - u and w the sum of the off-diagonal pair r, q,
// x = d s^2 + w s c and y = d s c - w s^2 give p - x, u + x, y + r and y + q; a block isotropic
// about the axis (d = 0, w = 0) stays as it is. The row and column of k turn by the single
// angle. Then F^T ( ) F, which only moves entries and signs.
matrix SpatialTree::turned(std::size_t i, const matrix& A, bool symmetric) const {
  const SpatialJoint& j = joints_[i];
  if (!j.turn) {
    if (symmetric) return congruence(j.E, A);
    return z_.bind(j.E.transpose().mul(z_.bind(A.mul(j.E))));
  }
  const SpatialJoint::Turn& t = *j.turn;
  const unsigned k = static_cast<unsigned>(t.axis - 1), a = (k + 1) % 3, b = (k + 2) % 3;
  const ex p = A(a, a), u = A(b, b), r = A(a, b), q = A(b, a);
  const ex d = z_.bind(p - u), w = z_.bind(r + q);
  const ex x = z_.bind(d * t.ss + w * t.sc), y = z_.bind(d * t.sc - w * t.ss);
  matrix B(3, 3);
  B(a, a) = p - x;
  B(b, b) = u + x;
  B(a, b) = y + r;
  B(b, a) = y + q;
  B(k, k) = A(k, k);
  B(a, k) = t.c * A(a, k) - t.s * A(b, k);
  B(b, k) = t.s * A(a, k) + t.c * A(b, k);
  B(k, a) = symmetric ? B(a, k) : t.c * A(k, a) - t.s * A(k, b);
  B(k, b) = symmetric ? B(b, k) : t.s * A(k, a) + t.c * A(k, b);
  B = symmetric ? bind_symmetric(B) : z_.bind(B);
  return t.F.transpose().mul(B).mul(t.F);
}

// [[A, B], [B^T, C]] shifted by R = r^x: [[A - B R + R H^T, H], [H^T, C]], H = B + R C
matrix SpatialTree::shifted(const matrix& A, const matrix& B, const matrix& C, const matrix& r) const {
  const matrix R = cross_matrix(r);
  const matrix H = z_.bind(B.add(R.mul(C)));
  return symmetric_blocks(bind_symmetric(A.sub(B.mul(R)).add(R.mul(H.transpose()))), H, C);
}

// Phi^T I Phi: a shift to o_p in f_i, then a rotation into f_p; or, where r is constant in f_p
// and not in f_i, the rotation first and the shift by r_p after
matrix SpatialTree::inertia_to_parent(std::size_t i, const matrix& I) const {
  const SpatialJoint& j = joints_[i];
  const matrix A = sub_block(I, 0, 0), B = sub_block(I, 0, 3), C = sub_block(I, 3, 3);
  // one statement each: the order of the bindings is the order of the subexpressions, which
  // the order of a call's arguments would leave to the compiler
  if (j.shift_in_parent) {
    const matrix A_p = turned(i, A, true);
    const matrix B_p = turned(i, B, false);
    const matrix C_p = turned(i, C, true);
    return shifted(A_p, B_p, C_p, j.r_parent);
  }
  const matrix moved = shifted(A, B, C, j.r);
  const matrix top = turned(i, sub_block(moved, 0, 0), true);
  const matrix bottom = turned(i, C, true);
  const matrix corner = turned(i, sub_block(moved, 0, 3), false);
  return symmetric_blocks(top, corner, bottom);
}

matrix RigidInertia::spatial() const {
  const matrix H = cross_matrix(h);
  matrix C(3, 3);
  for (unsigned k = 0; k < 3; ++k) C(k, k) = m;
  return symmetric_blocks(J, H, C);
}

RigidInertia RigidInertia::add(const RigidInertia& other) const {
  return {m + other.m, h.add(other.h), J.add(other.J)};
}

RigidInertia SpatialTree::rigid_inertia(std::size_t i) const {
  const Link& link = links_[i];
  return {link.mass, centre_offsets_[i].mul_scalar(link.mass), origin_inertia(i)};
}

// shifted by r: h' = h + m r, J' = J - h^x r^x - r^x h'^x (the shift of the 6x6 with B = h^x,
// C = m 1); turned: h' = E^T h, J' = E^T J E
RigidInertia SpatialTree::rigid_inertia_to_parent(std::size_t i, const RigidInertia& I) const {
  const SpatialJoint& j = joints_[i];
  const auto shift = [&](const RigidInertia& in, const matrix& r) {
    const matrix h = z_.bind(in.h.add(r.mul_scalar(in.m)));
    const matrix R = cross_matrix(r);
    const matrix J = bind_symmetric(in.J.sub(cross_matrix(in.h).mul(R)).sub(R.mul(cross_matrix(h))));
    return RigidInertia{in.m, h, J};
  };
  const auto turn = [&](const RigidInertia& in) {
    const matrix h = z_.bind(j.E.transpose().mul(in.h));
    const matrix J = turned(i, in.J, true);
    return RigidInertia{in.m, h, J};
  };
  if (j.shift_in_parent) return shift(turn(I), j.r_parent);
  return turn(shift(I, j.r));
}

matrix SpatialTree::congruence(const matrix& X, const matrix& A) const {
  const matrix AX = z_.bind(A.mul(X));
  matrix out(X.cols(), X.cols());
  for (unsigned r = 0; r < X.cols(); ++r)
    for (unsigned c = r; c < X.cols(); ++c) {
      ex sum = 0;
      for (unsigned m = 0; m < X.rows(); ++m) sum += X(m, r) * AX(m, c);
      out(r, c) = out(c, r) = z_.bind(sum);
    }
  return out;
}

matrix SpatialTree::bind_symmetric(const matrix& A) const {
  matrix out(A.rows(), A.cols());
  for (unsigned r = 0; r < A.rows(); ++r)
    for (unsigned c = r; c < A.cols(); ++c) out(r, c) = out(c, r) = z_.bind(A(r, c));
  return out;
}

}  // namespace eomgen
