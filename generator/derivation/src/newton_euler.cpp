#include "newton_euler.hpp"

#include "eomgen/mechanics/rotation.hpp"
#include "link_tree.hpp"
#include "spatial_tree.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix column(const matrix& m, unsigned c) {
  matrix out(m.rows(), 1);
  for (unsigned r = 0; r < m.rows(); ++r) out(r, 0) = m(r, c);
  return out;
}

// S^T F for a 6 x k motion subspace and a 6 x c block of forces
matrix projected(const matrix& S, const matrix& F) { return S.transpose().mul(F); }

// a_i = Phi_i a_p + zeta_i + S_i qdd_J(i), from the ground's -g (gravity acting on every link)
std::vector<matrix> accelerations(const SpatialTree& tree, const Variables& vars, Subexpressions& z) {
  std::vector<matrix> a(tree.size());
  const matrix ground = tree.ground_acceleration();
  for (std::size_t i = 0; i < tree.size(); ++i) {
    const Link& link = tree.link(i);
    const SpatialJoint& joint = tree.joint(i);
    matrix own = tree.motion_to_link(i, link.parent ? a[*link.parent] : ground).add(joint.zeta);
    for (unsigned k = 0; k < joint.S.cols(); ++k)
      own = own.add(column(joint.S, k).mul_scalar(vars.coordinates()[link.joint[k]].qdd));
    a[i] = z.bind(own);
  }
  return a;
}

std::variant<LinkTree, std::string> tree_of(const MechanicalSystem& system) { return link_tree_of_bodies(system); }

// the six rows of the force of link i for one unit inertial parameter: (n; f) about the origin
// of m a_o + alpha x h + w x (w x h) and J alpha + w x J w + h x a_o
matrix unit_force(const matrix& w, const matrix& alpha, const matrix& a_o, const ex& m, const matrix& h,
                  const matrix& J) {
  const matrix n = J.mul(alpha).add(cross_matrix(w).mul(J.mul(w))).add(cross_matrix(h).mul(a_o));
  const matrix f = a_o.mul_scalar(m).add(cross_matrix(alpha).mul(h)).add(cross_matrix(w).mul(cross_matrix(w).mul(h)));
  return stacked(n, f);
}

}  // namespace

std::variant<matrix, std::string> derive_newton_euler_torques(const MechanicalSystem& system, Subexpressions& z) {
  std::variant<LinkTree, std::string> links = tree_of(system);
  if (auto* reason = std::get_if<std::string>(&links)) return *reason;
  const SpatialTree tree(system, std::move(std::get<LinkTree>(links)), z);
  const Variables& vars = system.variables();
  const std::vector<matrix> a = accelerations(tree, vars, z);
  std::vector<matrix> force(tree.size());
  for (std::size_t i = 0; i < tree.size(); ++i)
    force[i] = tree.spatial_inertia(i).mul(a[i]).add(tree.velocity_product_force(i));
  const GiNaC::exvector loads = tree.load_forces();
  matrix tau(static_cast<unsigned>(vars.coordinate_count()), 1);
  std::vector<bool> held(tau.rows(), false);
  for (std::size_t i = tree.size(); i-- > 0;) {
    const Link& link = tree.link(i);
    const matrix f = z.bind(force[i]);
    const matrix s = projected(tree.joint(i).S, f);
    for (unsigned k = 0; k < s.rows(); ++k) {
      tau(link.joint[k], 0) = z.bind(s(k, 0) - loads[link.joint[k]]);
      held[link.joint[k]] = true;
    }
    if (link.parent) force[*link.parent] = force[*link.parent].add(tree.force_to_parent(i, f));
  }
  // a coordinate no body's joint holds (moving nothing with mass) has only its loads
  for (unsigned k = 0; k < tau.rows(); ++k)
    if (!held[k]) tau(k, 0) = z.bind(-loads[k]);
  return tau;
}

std::variant<RegressorTerms, std::string> derive_regressor(const MechanicalSystem& system, Subexpressions& z) {
  std::variant<LinkTree, std::string> links = tree_of(system);
  if (auto* reason = std::get_if<std::string>(&links)) return *reason;
  const SpatialTree tree(system, std::move(std::get<LinkTree>(links)), z);
  const Variables& vars = system.variables();
  const std::vector<matrix> a = accelerations(tree, vars, z);
  const auto n = static_cast<unsigned>(vars.coordinate_count()), bodies = static_cast<unsigned>(tree.size());
  RegressorTerms out;
  out.Y = matrix(n, 10 * bodies);
  out.parameters = matrix(10 * bodies, 1);
  // the unit parameters in Pinocchio's order: m, h, then J by its rows (xx, xy, yy, xz, yz, zz)
  const unsigned J_entries[6][2] = {{0, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}, {2, 2}};
  const char* names[10] = {"m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz"};
  for (unsigned i = 0; i < bodies; ++i) {
    const Link& link = tree.link(i);
    const RigidInertia own = tree.rigid_inertia(i);
    out.parameters(10 * i, 0) = own.m;
    for (unsigned k = 0; k < 3; ++k) out.parameters(10 * i + 1 + k, 0) = own.h(k, 0);
    for (unsigned k = 0; k < 6; ++k) out.parameters(10 * i + 4 + k, 0) = own.J(J_entries[k][0], J_entries[k][1]);
    for (const char* name : names) out.names.push_back(link.name + "." + name);
    out.origins.push_back(system.point(link.origin).name);
    const matrix& w = tree.joint(i).omega;
    const matrix alpha = spatial_block(a[i], 0), a_o = spatial_block(a[i], 3);
    matrix F(6, 10);
    for (unsigned c = 0; c < 10; ++c) {
      matrix h(3, 1), J(3, 3);
      ex m = 0;
      if (c == 0) m = 1;
      else if (c < 4) h(c - 1, 0) = 1;
      else J(J_entries[c - 4][0], J_entries[c - 4][1]) = J(J_entries[c - 4][1], J_entries[c - 4][0]) = 1;
      const matrix f = z.bind(unit_force(w, alpha, a_o, m, h, J));
      for (unsigned r = 0; r < 6; ++r) F(r, c) = f(r, 0);
    }
    // the forces carried inward: every ancestor's joint takes its projection
    for (std::size_t j = i;;) {
      const matrix s = projected(tree.joint(j).S, F);
      for (unsigned r = 0; r < s.rows(); ++r)
        for (unsigned c = 0; c < 10; ++c) out.Y(tree.link(j).joint[r], 10 * i + c) = z.bind(s(r, c));
      if (!tree.link(j).parent) break;
      for (unsigned c = 0; c < 10; ++c) {
        const matrix moved = z.bind(tree.force_to_parent(j, column(F, c)));
        for (unsigned r = 0; r < 6; ++r) F(r, c) = moved(r, 0);
      }
      j = *tree.link(j).parent;
    }
  }
  return out;
}

}  // namespace eomgen
