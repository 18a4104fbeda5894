#include "eomgen/derivation/articulated_body.hpp"

#include <optional>

#include "link_tree.hpp"
#include "spatial_tree.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

// What the inward pass leaves for the outward one: D_i = L diag(d) L^T, W = L^-1 U_i^T,
// Wd = diag(1/d) W and y = L^-1 u_i, so that qdd_J(i) = L^-T (diag(1/d) y - Wd A'_i).
struct Pivoting {
  matrix L, inverse_d, Wd, y;
};

// Column c of S as +-e_k (a joint about or along an axis of its link's frame, through its
// origin, either way): k and the sign; none for any other column.
struct UnitAxis {
  unsigned k;
  int sign;
};
std::optional<UnitAxis> unit_axis(const matrix& S, unsigned c) {
  std::optional<UnitAxis> axis;
  for (unsigned r = 0; r < S.rows(); ++r) {
    if (S(r, c).is_zero()) continue;
    if (axis || !(S(r, c).is_equal(1) || S(r, c).is_equal(-1))) return std::nullopt;
    axis = UnitAxis{r, S(r, c).is_equal(1) ? 1 : -1};
  }
  return axis;
}

class ArticulatedBody {
 public:
  ArticulatedBody(const MechanicalSystem& s, LinkTree tree)
      : vars_(s.variables()), tree_(s, std::move(tree), fd_.subexpressions), z_(fd_.subexpressions) {}

  ForwardDynamics run() {
    tau_ = tree_.load_forces();
    inward();
    outward();
    return std::move(fd_);
  }

 private:
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
    const std::size_t count = tree_.size();
    IA_.resize(count);
    pA_.resize(count);
    pivoting_.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      IA_[i] = tree_.spatial_inertia(i);
      pA_[i] = tree_.velocity_product_force(i);
    }
    for (std::size_t i = count; i-- > 0;) {
      const SpatialJoint& j = tree_.joint(i);
      const Link& link = tree_.link(i);
      const matrix IA = tree_.bind_symmetric(IA_[i]);
      const matrix pA = z_.bind(pA_[i]);
      matrix Ia = IA, pa = pA;
      if (j.S.cols() > 0) {
        const matrix U = z_.bind(IA.mul(j.S));
        const matrix D = tree_.bind_symmetric(j.S.transpose().mul(U));
        matrix u(j.S.cols(), 1);
        for (unsigned a = 0; a < u.rows(); ++a) u(a, 0) = tau_[link.joint[a]];
        u = z_.bind(u.sub(j.S.transpose().mul(pA)));
        Pivoting& f = pivoting_[i];
        f = factor(D);
        const matrix W = forward_substitution(f.L, U.transpose());
        f.Wd = matrix(W.rows(), W.cols());
        for (unsigned a = 0; a < W.rows(); ++a)
          for (unsigned c = 0; c < W.cols(); ++c) f.Wd(a, c) = z_.bind(f.inverse_d(a, 0) * W(a, c));
        // Wd S = diag(1/d) L^-1 U^T S = diag(1/d) L^-1 D = L^T exactly: at a column +-e_k of S,
        // column k of Wd is +- a column of L^T (1 on the diagonal), not (1/d) d
        for (unsigned b = 0; b < j.S.cols(); ++b)
          if (const std::optional<UnitAxis> e = unit_axis(j.S, b))
            for (unsigned a = 0; a < W.rows(); ++a)
              f.Wd(a, e->k) = e->sign * (a == b ? ex(1) : a < b ? f.L(b, a) : ex(0));
        f.y = forward_substitution(f.L, u);
        Ia = IA.sub(W.transpose().mul(f.Wd));
        pa = pA.add(f.Wd.transpose().mul(f.y));
        // Ia S = U - U D^-1 D = 0 and S^T pa = S^T pA + u = tau, exactly; where S's columns are
        // +-e_k, those are rows and columns of Ia and entries of pa, which the subexpressions
        // (D and 1/D bound apart) would compute as x - x (1/d) d and lose
        for (unsigned a = 0; a < j.S.cols(); ++a) {
          const std::optional<UnitAxis> e = unit_axis(j.S, a);
          if (!e) continue;
          for (unsigned m = 0; m < 6; ++m) Ia(e->k, m) = Ia(m, e->k) = 0;
          pa(e->k, 0) = e->sign * tau_[link.joint[a]];
        }
        Ia = tree_.bind_symmetric(Ia);
      }
      if (!link.parent) continue;
      pa = z_.bind(pa.add(Ia.mul(j.zeta)));
      const std::size_t p = *link.parent;
      IA_[p] = IA_[p].add(tree_.inertia_to_parent(i, Ia));
      pA_[p] = pA_[p].add(tree_.force_to_parent(i, pa));
    }
  }

  // A'_i = Phi_i A_p + zeta_i, qdd_J(i) = D^-1 (u - U^T A'_i), A_i = A'_i + S_i qdd_J(i)
  void outward() {
    const std::size_t n = vars_.coordinate_count();
    fd_.accelerations = matrix(static_cast<unsigned>(n), 1);
    const matrix ground = tree_.ground_acceleration();
    std::vector<matrix> A(tree_.size());
    for (std::size_t i = 0; i < tree_.size(); ++i) {
      const SpatialJoint& j = tree_.joint(i);
      const Link& link = tree_.link(i);
      const std::size_t k = j.S.cols();
      if (k == 0 && !tree_.has_children(i)) continue;
      const matrix A_prime = z_.bind(tree_.motion_to_link(i, link.parent ? A[*link.parent] : ground).add(j.zeta));
      matrix qdd(k, 1);
      if (k > 0) {
        const Pivoting& f = pivoting_[i];
        const matrix Wd_A = f.Wd.mul(A_prime);
        for (unsigned a = k; a-- > 0;) {
          ex sum = f.inverse_d(a, 0) * f.y(a, 0) - Wd_A(a, 0);
          for (unsigned m = a + 1; m < k; ++m) sum -= f.L(m, a) * qdd(m, 0);
          qdd(a, 0) = z_.bind(sum);
          fd_.accelerations(link.joint[a], 0) = qdd(a, 0);
        }
      }
      if (tree_.has_children(i)) A[i] = z_.bind(A_prime.add(j.S.mul(qdd)));
    }
  }

  const Variables& vars_;
  ForwardDynamics fd_;
  SpatialTree tree_;
  Subexpressions& z_;
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
