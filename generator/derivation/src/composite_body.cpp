#include "eomgen/derivation/composite_body.hpp"

#include "link_tree.hpp"
#include "operation_estimate.hpp"
#include "spatial_tree.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

// column c of a 6 x k matrix
matrix column(const matrix& m, unsigned c) {
  matrix out(6, 1);
  for (unsigned r = 0; r < 6; ++r) out(r, 0) = m(r, c);
  return out;
}

class CompositeBody {
 public:
  CompositeBody(const MechanicalSystem& s, LinkTree tree, Subexpressions& z)
      : vars_(s.variables()), tree_(s, std::move(tree), z), z_(z) {}

  RecursiveMassMatrixAndForcing run() {
    const auto n = static_cast<unsigned>(vars_.coordinate_count());
    out_.mass_matrix = matrix(n, n);
    out_.forcing = matrix(n, 1);
    tau_ = tree_.load_forces();
    composite_inertias();
    bias_forces();
    return std::move(out_);
  }

 private:
  // Ic_i = I_i + sum over the children c of Phi_c^T Ic_c Phi_c, as ten numbers each. The force Ic_i S_i that a unit
  // rate of joint i needs, carried inward to every ancestor j, gives M_J(j)J(i) = S_j^T F.
  void composite_inertias() {
    std::vector<RigidInertia> composite;
    for (std::size_t i = 0; i < tree_.size(); ++i) composite.push_back(tree_.rigid_inertia(i));
    for (std::size_t i = tree_.size(); i-- > 0;) {
      const Link& link = tree_.link(i);
      RigidInertia& own = composite[i];
      own = {z_.bind(own.m), z_.bind(own.h), tree_.bind_symmetric(own.J)};
      const matrix Ic = own.spatial();
      if (link.parent) composite[*link.parent] = composite[*link.parent].add(tree_.rigid_inertia_to_parent(i, own));
      const matrix& S = tree_.joint(i).S;
      if (S.cols() == 0) continue;
      matrix F = z_.bind(Ic.mul(S));
      const matrix diagonal = tree_.congruence(S, Ic);
      for (unsigned a = 0; a < S.cols(); ++a)
        for (unsigned b = 0; b < S.cols(); ++b) out_.mass_matrix(link.joint[a], link.joint[b]) = diagonal(a, b);
      for (std::size_t j = i; tree_.link(j).parent;) {
        for (unsigned c = 0; c < F.cols(); ++c) {
          const matrix moved = z_.bind(tree_.force_to_parent(j, column(F, c)));
          for (unsigned r = 0; r < 6; ++r) F(r, c) = moved(r, 0);
        }
        j = *tree_.link(j).parent;
        const matrix& S_j = tree_.joint(j).S;
        for (unsigned a = 0; a < S_j.cols(); ++a)
          for (unsigned b = 0; b < S.cols(); ++b) {
            ex entry = 0;
            for (unsigned r = 0; r < 6; ++r) entry += S_j(r, a) * F(r, b);
            entry = z_.bind(entry);
            const std::size_t row = tree_.link(j).joint[a], col = link.joint[b];
            out_.mass_matrix(row, col) = out_.mass_matrix(col, row) = entry;
          }
      }
    }
  }

  // Newton-Euler at qdd = 0: outward, the accelerations a_i = Phi_i a_p + zeta_i from the ground's
  // -g; inward, the forces f_i = I_i a_i + (w x J w; 0) plus those of the children; then
  // F_J(i) = Q_J(i) - S_i^T f_i.
  void bias_forces() {
    std::vector<matrix> acceleration(tree_.size()), force(tree_.size());
    const matrix ground = tree_.ground_acceleration();
    for (std::size_t i = 0; i < tree_.size(); ++i) {
      const Link& link = tree_.link(i);
      acceleration[i] = z_.bind(
          tree_.motion_to_link(i, link.parent ? acceleration[*link.parent] : ground).add(tree_.joint(i).zeta));
      force[i] = tree_.spatial_inertia(i).mul(acceleration[i]).add(tree_.velocity_product_force(i));
    }
    for (std::size_t i = tree_.size(); i-- > 0;) {
      const Link& link = tree_.link(i);
      const matrix f = z_.bind(force[i]);
      const matrix& S = tree_.joint(i).S;
      for (unsigned a = 0; a < S.cols(); ++a) {
        ex projected = 0;
        for (unsigned r = 0; r < 6; ++r) projected += S(r, a) * f(r, 0);
        out_.forcing(link.joint[a], 0) = z_.bind(tau_[link.joint[a]] - projected);
      }
      if (link.parent) force[*link.parent] = force[*link.parent].add(tree_.force_to_parent(i, f));
    }
  }

  const Variables& vars_;
  RecursiveMassMatrixAndForcing out_;
  SpatialTree tree_;
  Subexpressions& z_;
  GiNaC::exvector tau_;
};

}  // namespace

std::variant<RecursiveMassMatrixAndForcing, std::string> derive_composite_body_terms(const MechanicalSystem& system,
                                                                                     Subexpressions& subexpressions) {
  std::variant<LinkTree, std::string> tree = link_tree_of_bodies(system);
  if (auto* reason = std::get_if<std::string>(&tree)) return *reason;
  return CompositeBody(system, std::move(std::get<LinkTree>(tree)), subexpressions).run();
}

std::variant<CompositeBodyEquations, std::string> derive_composite_body_equations(const MechanicalSystem& system) {
  CompositeBodyEquations out;
  std::variant<RecursiveMassMatrixAndForcing, std::string> terms = derive_composite_body_terms(system, out.subexpressions);
  if (auto* reason = std::get_if<std::string>(&terms)) return *reason;
  out.mass_matrix = std::move(std::get<RecursiveMassMatrixAndForcing>(terms).mass_matrix);
  out.forcing = std::move(std::get<RecursiveMassMatrixAndForcing>(terms).forcing);
  out.estimated_operations = estimated_operations(out.mass_matrix, out.forcing, out.subexpressions, system.variables());
  return out;
}

}  // namespace eomgen
