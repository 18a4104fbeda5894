#include "eomgen/derivation/articulated_body.hpp"

#include <optional>

#include "eomgen/derivation/composite_body.hpp"
#include "ldl_factor.hpp"
#include "link_tree.hpp"
#include "operation_estimate.hpp"
#include "spatial_tree.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

// What the inward pass leaves for the outward one: D_i = L diag(d) L^T, W = L^-1 U_i^T,
// Wd = diag(1/d) W and y = L^-1 u_i, so that qdd_J(i) = L^-T (diag(1/d) y - Wd A'_i).
struct Pivoting {
  LdlFactors factors;
  matrix Wd, y;
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
        f.factors = ldl_factor(D, z_, fd_.pivots);
        const matrix& L = f.factors.L;
        const matrix& inverse_d = f.factors.inverse_d;
        const matrix W = forward_substitution(L, U.transpose(), z_);
        f.Wd = matrix(W.rows(), W.cols());
        for (unsigned a = 0; a < W.rows(); ++a)
          for (unsigned c = 0; c < W.cols(); ++c) f.Wd(a, c) = z_.bind(inverse_d(a, 0) * W(a, c));
        // Wd S = diag(1/d) L^-1 U^T S = diag(1/d) L^-1 D = L^T exactly: at a column +-e_k of S,
        // column k of Wd is +- a column of L^T (1 on the diagonal), not (1/d) d
        for (unsigned b = 0; b < j.S.cols(); ++b)
          if (const std::optional<UnitAxis> e = unit_axis(j.S, b))
            for (unsigned a = 0; a < W.rows(); ++a)
              f.Wd(a, e->k) = e->sign * (a == b ? ex(1) : a < b ? L(b, a) : ex(0));
        f.y = forward_substitution(L, u, z_);
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
          ex sum = f.factors.inverse_d(a, 0) * f.y(a, 0) - Wd_A(a, 0);
          for (unsigned m = a + 1; m < k; ++m) sum -= f.factors.L(m, a) * qdd(m, 0);
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

// qdd = M^-1 F, M factored with the coordinates in reverse (for the tree order of a model, the
// leaves first: their elimination fills in only their ancestors' rows, which a chain fills anyway)
ForwardDynamics by_mass_matrix(const RecursiveMassMatrixAndForcing& terms, ForwardDynamics fd) {
  fd.form = ForwardDynamics::Form::mass_matrix;
  const unsigned n = terms.mass_matrix.rows();
  matrix M(n, n), F(n, 1);
  for (unsigned r = 0; r < n; ++r) {
    F(r, 0) = terms.forcing(n - 1 - r, 0);
    for (unsigned c = 0; c < n; ++c) M(r, c) = terms.mass_matrix(n - 1 - r, n - 1 - c);
  }
  const LdlFactors factors = ldl_factor(M, fd.subexpressions, fd.pivots);
  const matrix x = ldl_solve(factors, F, fd.subexpressions);
  fd.accelerations = matrix(n, 1);
  for (unsigned r = 0; r < n; ++r) fd.accelerations(n - 1 - r, 0) = x(r, 0);
  return fd;
}

inline constexpr double recursion_weight = 1.15;

double operations(const ForwardDynamics& fd, const Variables& variables) {
  return estimated_operations(matrix(1, 1), fd.accelerations, fd.subexpressions, variables);
}

}  // namespace

std::variant<ForwardDynamics, std::string> derive_forward_dynamics(const MechanicalSystem& system,
                                                                   std::optional<ForwardDynamics::Form> form) {
  std::variant<LinkTree, std::string> tree = link_tree(system);
  if (auto* reason = std::get_if<std::string>(&tree)) return *reason;
  ForwardDynamics recursion;
  if (form != ForwardDynamics::Form::mass_matrix) {
    recursion = ArticulatedBody(system, std::move(std::get<LinkTree>(tree))).run();
    recursion.estimated_operations = operations(recursion, system.variables());
    if (form) return recursion;
  }
  // a tree for link_tree() is one for the composite-body recursions
  ForwardDynamics factored;
  RecursiveMassMatrixAndForcing terms =
      std::get<RecursiveMassMatrixAndForcing>(derive_composite_body_terms(system, factored.subexpressions));
  factored = by_mass_matrix(terms, std::move(factored));
  factored.estimated_operations = operations(factored, system.variables());
  if (form) return factored;
  factored.estimated_operations_other = recursion.estimated_operations;
  recursion.estimated_operations_other = factored.estimated_operations;
  // An operation of the recursion costs more than one of the factors: its inward and outward
  // passes are one long chain of dependent steps, while M's entries and F are independent
  // of each other. Measured on the shipped arms (docs/performance.md, "The forward dynamics
  // by M"), 0.13 to 0.14 ns against 0.12 to 0.13 per operation: the recursion's count is
  // weighed 1.15. On a tie the recursion, which grows linearly with the links, the factors
  // cubically.
  if (factored.estimated_operations < recursion_weight * recursion.estimated_operations) return factored;
  return recursion;
}

}  // namespace eomgen
