#include "eomgen/derivation/articulated_body.hpp"

#include <functional>

#include "eomgen/mechanics/kinematics.hpp"
#include "link_tree.hpp"
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

// rows first..first+2 of a 6x1 column
matrix block(const matrix& v, unsigned first) {
  return matrix(3, 1, GiNaC::lst{v(first, 0), v(first + 1, 0), v(first + 2, 0)});
}

// the 3x3 block of a 6x6 matrix at (row, column)
matrix sub_block(const matrix& m, unsigned row, unsigned column) {
  matrix out(3, 3);
  for (unsigned r = 0; r < 3; ++r)
    for (unsigned c = 0; c < 3; ++c) out(r, c) = m(row + r, column + c);
  return out;
}

// (top; bottom) of two 3x1 columns
matrix stacked(const matrix& top, const matrix& bottom) {
  matrix out(6, 1);
  for (unsigned i = 0; i < 3; ++i) {
    out(i, 0) = top(i, 0);
    out(i + 3, 0) = bottom(i, 0);
  }
  return out;
}

// The joint of link i to its parent p: Phi_i = [[E, 0], [-E r^x, E]] maps the parent's spatial
// velocity and acceleration into link i's, S_i its partials with respect to qd_J(i), zeta_i
// the part of its acceleration at qdd = 0 that Phi_i does not carry over from the parent.
struct Joint {
  matrix E;      // C_{f_i f_p}
  matrix r;      // r^{c_i c_p} resolved in f_i: Phi_i = [[1, 0], [-r^x, 1]] diag(E, E)
  matrix S;      // 6 x |J(i)|
  matrix omega;  // omega_i, in f_i
  matrix zeta;   // 6x1
};

// What the inward pass leaves for the outward one: D_i = L diag(d) L^T, W = L^-1 U_i^T,
// Wd = diag(1/d) W and y = L^-1 u_i, so that qdd_J(i) = L^-T (diag(1/d) y - Wd A'_i).
struct Pivoting {
  matrix L, inverse_d, Wd, y;
};

class ArticulatedBody {
 public:
  ArticulatedBody(const MechanicalSystem& s, LinkTree tree)
      : s_(s), vars_(s.variables()), links_(std::move(tree.links)), z_(fd_.subexpressions) {}

  ForwardDynamics run() {
    joints_.resize(links_.size());
    for (std::size_t i = 0; i < links_.size(); ++i) joints_[i] = joint(i);
    tau_ = generalized_load_forces(s_);
    for (ex& Q : tau_) Q = z_.bind(Q);
    inward();
    outward();
    return std::move(fd_);
  }

 private:
  const Link* parent(std::size_t i) const { return links_[i].parent ? &links_[*links_[i].parent] : nullptr; }

  ex rate_at_zero_acceleration(const ex& e) const {
    return vars_.without_accelerations(vars_.time_derivative(e));
  }
  ex rate_partial(const ex& e, std::size_t k) const {
    return e.diff(GiNaC::ex_to<GiNaC::symbol>(ex(vars_.coordinates()[k].qd)));
  }

  // The relative kinematics come from the plain functions: they involve only J(i). Resolved in
  // f_i, where the joint's own terms are usually given, they need no trigonometric identities.
  Joint joint(std::size_t i) {
    const Link& link = links_[i];
    const Link* p = parent(i);
    const FrameId fp = p ? p->frame : s_.inertial_frame();
    const matrix omega_p = p ? joints_[*link.parent].omega : matrix(3, 1);
    const Vector r = position(s_, link.centre, p ? p->centre : s_.origin());
    const Vector r_rate = time_derivative(s_, r, fp);
    const matrix v_rel = resolve(s_, r_rate, link.frame);
    const matrix a_rel = map_entries(resolve(s_, time_derivative(s_, r_rate, fp), link.frame),
                                     [&](const ex& e) { return vars_.without_accelerations(e); });
    const matrix w_rel = resolve(s_, angular_velocity(s_, link.frame, fp), link.frame);
    Joint j;
    j.E = z_.bind(dcm(s_, link.frame, fp));
    const matrix r_i = z_.bind(resolve(s_, r, link.frame));
    j.r = r_i;
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
    const matrix alpha = map_entries(w_rel, [&](const ex& e) { return rate_at_zero_acceleration(e); })
                             .add(cross3(w, w_rel_bound));
    const matrix w_x_r = z_.bind(cross3(w, r_i));
    const matrix a = cross3(w, w_x_r).add(cross3(w, z_.bind(v_rel)).mul_scalar(2)).add(a_rel);
    j.zeta = z_.bind(stacked(alpha, a));
    return j;
  }

  // Phi (alpha; a) = (w; E a + w x r) with w = E alpha
  matrix motion_to_link(const Joint& j, const matrix& A) {
    const matrix w = z_.bind(j.E.mul(block(A, 0)));
    return stacked(w, j.E.mul(block(A, 3)).add(cross3(w, j.r)));
  }

  // Phi^T (n; f) = (E^T (n + r x f); E^T f)
  matrix force_to_parent(const Joint& j, const matrix& F) {
    const matrix f = z_.bind(block(F, 3));
    const matrix Et = j.E.transpose();
    return stacked(Et.mul(block(F, 0).add(cross3(j.r, f))), Et.mul(f));
  }

  // Phi^T Ia Phi as a shift to c_p in f_i, then a rotation into f_p: with Ia = [[A, B], [B^T, C]]
  // and R = r^x, the shift gives [[A - B R + R H^T, H], [H^T, C]], H = B + R C
  matrix inertia_to_parent(const Joint& j, const matrix& Ia) {
    const matrix R = cross_matrix(j.r);
    const matrix A = sub_block(Ia, 0, 0), B = sub_block(Ia, 0, 3), C = sub_block(Ia, 3, 3);
    const matrix H = z_.bind(B.add(R.mul(C)));
    const matrix K = A.sub(B.mul(R)).add(R.mul(H.transpose()));
    const matrix Et = j.E.transpose();
    const matrix top = congruence(j.E, bind_symmetric(K)), bottom = congruence(j.E, C);
    const matrix corner = z_.bind(Et.mul(z_.bind(H.mul(j.E))));
    matrix out(6, 6);
    for (unsigned r = 0; r < 3; ++r)
      for (unsigned c = 0; c < 3; ++c) {
        out(r, c) = top(r, c);
        out(r + 3, c + 3) = bottom(r, c);
        out(r, c + 3) = corner(r, c);
        out(c + 3, r) = corner(r, c);
      }
    return out;
  }

  // M_i = diag(J_i, m_i 1) and b_i = (omega x J omega; 0)
  void start_link(std::size_t i) {
    const Link& link = links_[i];
    matrix M(6, 6);
    for (unsigned r = 0; r < 3; ++r) {
      for (unsigned c = 0; c < 3; ++c) M(r, c) = link.inertia(r, c);
      M(r + 3, r + 3) = link.mass;
    }
    IA_[i] = M;
    const matrix& w = joints_[i].omega;
    pA_[i] = stacked(cross3(w, z_.bind(link.inertia.mul(w))), matrix(3, 1));
  }

  // X^T A X for a symmetric A, each entry of the upper triangle computed once
  matrix congruence(const matrix& X, const matrix& A) {
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

  // the upper triangle of a symmetric matrix, bound once and mirrored
  matrix bind_symmetric(const matrix& A) {
    matrix out(A.rows(), A.cols());
    for (unsigned r = 0; r < A.rows(); ++r)
      for (unsigned c = r; c < A.cols(); ++c) out(r, c) = out(c, r) = z_.bind(A(r, c));
    return out;
  }

  // D = L diag(d) L^T, written out; each pivot d_a is recorded for the regularity check
  Pivoting factor(const matrix& D) {
    const unsigned k = D.rows();
    Pivoting f{matrix(k, k), matrix(k, 1), {}, {}};
    matrix t(k, k);  // t_ab = L_ab d_b
    for (unsigned a = 0; a < k; ++a) {
      for (unsigned b = 0; b < a; ++b) {
        ex sum = D(a, b);
        for (unsigned m = 0; m < b; ++m) sum -= t(a, m) * f.L(b, m);
        t(a, b) = z_.bind(sum);
        f.L(a, b) = z_.bind(t(a, b) * f.inverse_d(b, 0));
      }
      ex d = D(a, a);
      for (unsigned m = 0; m < a; ++m) d -= t(a, m) * f.L(a, m);
      d = z_.bind(d);
      fd_.pivots.push_back(d);
      f.inverse_d(a, 0) = z_.bind(1 / d);
    }
    return f;
  }

  // L^-1 B by forward substitution (L unit lower triangular)
  matrix forward_substitution(const matrix& L, const matrix& B) {
    matrix X(B.rows(), B.cols());
    for (unsigned a = 0; a < B.rows(); ++a)
      for (unsigned c = 0; c < B.cols(); ++c) {
        ex sum = B(a, c);
        for (unsigned m = 0; m < a; ++m) sum -= L(a, m) * X(m, c);
        X(a, c) = z_.bind(sum);
      }
    return X;
  }

  // IA_p += Phi^T Ia Phi, pA_p += Phi^T pa with Ia = IA - U D^-1 U^T, pa = pA + Ia zeta + U D^-1 u
  void inward() {
    IA_.resize(links_.size());
    pA_.resize(links_.size());
    pivoting_.resize(links_.size());
    for (std::size_t i = 0; i < links_.size(); ++i) start_link(i);
    for (std::size_t i = links_.size(); i-- > 0;) {
      const Joint& j = joints_[i];
      const matrix IA = bind_symmetric(IA_[i]);
      const matrix pA = z_.bind(pA_[i]);
      matrix Ia = IA, pa = pA;
      if (j.S.cols() > 0) {
        const matrix U = z_.bind(IA.mul(j.S));
        const matrix D = bind_symmetric(j.S.transpose().mul(U));
        matrix u(j.S.cols(), 1);
        for (unsigned a = 0; a < u.rows(); ++a) u(a, 0) = tau_[links_[i].joint[a]];
        u = z_.bind(u.sub(j.S.transpose().mul(pA)));
        Pivoting& f = pivoting_[i];
        f = factor(D);
        const matrix W = forward_substitution(f.L, U.transpose());
        f.Wd = matrix(W.rows(), W.cols());
        for (unsigned a = 0; a < W.rows(); ++a)
          for (unsigned c = 0; c < W.cols(); ++c) f.Wd(a, c) = z_.bind(f.inverse_d(a, 0) * W(a, c));
        f.y = forward_substitution(f.L, u);
        Ia = bind_symmetric(IA.sub(W.transpose().mul(f.Wd)));
        pa = pA.add(f.Wd.transpose().mul(f.y));
      }
      if (!links_[i].parent) continue;
      pa = z_.bind(pa.add(Ia.mul(j.zeta)));
      const std::size_t p = *links_[i].parent;
      IA_[p] = IA_[p].add(inertia_to_parent(j, Ia));
      pA_[p] = pA_[p].add(force_to_parent(j, pa));
    }
  }

  // A'_i = Phi_i A_p + zeta_i, qdd_J(i) = D^-1 (u - U^T A'_i), A_i = A'_i + S_i qdd_J(i)
  void outward() {
    const std::size_t n = vars_.coordinate_count();
    fd_.accelerations = matrix(static_cast<unsigned>(n), 1);
    std::vector<bool> has_children(links_.size(), false);
    for (const Link& link : links_)
      if (link.parent) has_children[*link.parent] = true;
    // the ground's acceleration -g stands for gravity acting on every link
    const matrix ground = stacked(matrix(3, 1), resolve(s_, s_.gravity(), s_.inertial_frame()).mul_scalar(-1));
    std::vector<matrix> A(links_.size());
    for (std::size_t i = 0; i < links_.size(); ++i) {
      const Joint& j = joints_[i];
      const std::size_t k = j.S.cols();
      if (k == 0 && !has_children[i]) continue;
      const matrix A_prime = z_.bind(motion_to_link(j, links_[i].parent ? A[*links_[i].parent] : ground).add(j.zeta));
      matrix qdd(k, 1);
      if (k > 0) {
        const Pivoting& f = pivoting_[i];
        const matrix Wd_A = f.Wd.mul(A_prime);
        for (unsigned a = k; a-- > 0;) {
          ex sum = f.inverse_d(a, 0) * f.y(a, 0) - Wd_A(a, 0);
          for (unsigned m = a + 1; m < k; ++m) sum -= f.L(m, a) * qdd(m, 0);
          qdd(a, 0) = z_.bind(sum);
          fd_.accelerations(links_[i].joint[a], 0) = qdd(a, 0);
        }
      }
      if (has_children[i]) A[i] = z_.bind(A_prime.add(j.S.mul(qdd)));
    }
  }

  const MechanicalSystem& s_;
  const Variables& vars_;
  std::vector<Link> links_;
  ForwardDynamics fd_;
  Subexpressions& z_;
  std::vector<Joint> joints_;
  GiNaC::exvector tau_;
  std::vector<matrix> IA_, pA_;
  std::vector<Pivoting> pivoting_;
};

}  // namespace

std::variant<ForwardDynamics, std::string> derive_forward_dynamics(const MechanicalSystem& system) {
  std::variant<LinkTree, std::string> tree = link_tree(system);
  if (auto* reason = std::get_if<std::string>(&tree)) return *reason;
  return ArticulatedBody(system, std::move(std::get<LinkTree>(tree))).run();
}

}  // namespace eomgen
