#pragma once
// The spatial kinematics of a link tree (link_tree.hpp), shared by the recursive algorithms: the
// articulated-body forward dynamics (articulated_body.hpp) and the composite-rigid-body M with the
// Newton-Euler F (composite_body.hpp). Spatial quantities of a link are 6-vectors (angular;
// linear) resolved in the link's frame, the linear part at its origin (link_tree.hpp: the hinge
// of a pendulum), with classical accelerations. Every intermediate is bound in the caller's Subexpressions, so the algorithms
// stay linear in the size of the tree.
#include <ginac/ginac.h>

#include <optional>

#include <cstddef>
#include <vector>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"
#include "link_tree.hpp"

namespace eomgen {

/// The joint of link i to its parent p: Phi_i = [[E, 0], [-E r^x, E]] maps the parent's spatial
/// velocity and acceleration into link i's, S its partials with respect to qd_J(i), zeta the part
/// of its acceleration at qdd = 0 that Phi_i does not carry over from the parent.
struct SpatialJoint {
  GiNaC::matrix E;      ///< C_{f_i f_p}
  GiNaC::matrix r;      ///< r^{o_i o_p} between the origins, in f_i: Phi_i = [[1, 0], [-r^x, 1]] diag(E, E)
  /// The same vector in f_p, where the transforms take it when it is constant there and not in
  /// f_i (a URDF joint's origin, offset in its parent and turned about itself): a shift by
  /// constants after the rotation, not by sines and cosines before it; shift_in_parent says so.
  GiNaC::matrix r_parent;
  bool shift_in_parent = false;
  /// E = C_k(q) F for a joint of one coordinate turning about axis k of a frame that quarter
  /// turns F (a signed permutation, often 1) place in the parent: blocks are then turned in the
  /// products sin^2 q and sin q cos q, and one isotropic about the axis stays as it is.
  struct Turn {
    int axis;              // k: 1, 2 or 3
    GiNaC::matrix F;       // entries 0, 1 and -1
    GiNaC::ex c, s;        // cos q, sin q (bound)
    GiNaC::ex ss, sc;      // sin^2 q, sin q cos q (bound)
  };
  std::optional<Turn> turn;
  GiNaC::matrix S;      ///< 6 x |J(i)|
  GiNaC::matrix omega;  ///< omega_i, in f_i
  GiNaC::matrix zeta;   ///< 6x1
};

/// A rigid body's spatial inertia about a link's origin, as its ten numbers: the mass m, the
/// first moment h = m c and the inertia J about the origin, so that the 6x6 is
/// [[J, h^x], [(h^x)^T, m 1]]. Composite inertias stay rigid, and moving ten numbers costs about
/// half of moving the matrix.
struct RigidInertia {
  GiNaC::ex m;
  GiNaC::matrix h;  ///< 3x1
  GiNaC::matrix J;  ///< 3x3, symmetric
  GiNaC::matrix spatial() const;
  RigidInertia add(const RigidInertia& other) const;
};

class SpatialTree {
 public:
  /// The joints of every link, bound in `z`, which must outlive this object.
  SpatialTree(const MechanicalSystem& system, LinkTree tree, Subexpressions& z);

  std::size_t size() const { return links_.size(); }
  const Link& link(std::size_t i) const { return links_[i]; }
  const SpatialJoint& joint(std::size_t i) const { return joints_[i]; }
  /// Whether some link has link i as its parent.
  bool has_children(std::size_t i) const { return has_children_[i]; }

  /// Q_k of every load but gravity, bound (n entries).
  GiNaC::exvector load_forces() const;
  /// (0; -g) in the inertial frame: the ground's acceleration that stands for gravity acting on
  /// every link.
  GiNaC::matrix ground_acceleration() const;
  /// [[J_o, m c^x], [-m c^x, m 1]] about the origin o, with c the mass centre from o and
  /// J_o = J - m c^x c^x: (n_o; f) = I (alpha; a_o) + velocity_product_force
  GiNaC::matrix spatial_inertia(std::size_t i) const;
  /// (omega x J_o omega; m omega x (omega x c)): the force of link i at zero acceleration
  GiNaC::matrix velocity_product_force(std::size_t i) const;

  /// Phi_i A: a spatial motion of the parent's frame in link i's
  GiNaC::matrix motion_to_link(std::size_t i, const GiNaC::matrix& A) const;
  /// Phi_i^T F: a spatial force on link i as one on its parent
  GiNaC::matrix force_to_parent(std::size_t i, const GiNaC::matrix& F) const;
  /// Phi_i^T I Phi_i for a symmetric spatial inertia I of link i
  GiNaC::matrix inertia_to_parent(std::size_t i, const GiNaC::matrix& I) const;
  /// link i's own inertia as its ten numbers
  RigidInertia rigid_inertia(std::size_t i) const;
  /// Phi_i^T I Phi_i for a rigid inertia of link i (the ten numbers bound)
  RigidInertia rigid_inertia_to_parent(std::size_t i, const RigidInertia& I) const;

  /// X^T A X for a symmetric A, each entry of the upper triangle bound once
  GiNaC::matrix congruence(const GiNaC::matrix& X, const GiNaC::matrix& A) const;
  /// E^T A E of link i's joint for a 3x3 A (symmetric or not): in sin^2 q and sin q cos q where the
  /// joint turns about an axis (SpatialJoint::turn), else by congruence or products
  GiNaC::matrix turned(std::size_t i, const GiNaC::matrix& A, bool symmetric) const;
  /// [[A, B], [B^T, C]] moved by r: [[A - B R + R H^T, H], [H^T, C]], H = B + R C, R = r^x
  GiNaC::matrix shifted(const GiNaC::matrix& A, const GiNaC::matrix& B, const GiNaC::matrix& C,
                        const GiNaC::matrix& r) const;
  /// the upper triangle of a symmetric matrix, bound once and mirrored
  GiNaC::matrix bind_symmetric(const GiNaC::matrix& A) const;

 private:
  SpatialJoint make_joint(std::size_t i) const;
  std::optional<SpatialJoint::Turn> turn_of(const Link& link, FrameId fp) const;
  GiNaC::matrix origin_inertia(std::size_t i) const;

  const MechanicalSystem& s_;
  const Variables& vars_;
  std::vector<Link> links_;
  Subexpressions& z_;
  std::vector<SpatialJoint> joints_;
  std::vector<GiNaC::matrix> centre_offsets_;  // c of every link, in its frame
  std::vector<bool> has_children_;
};

/// rows first..first+2 of a 6x1 column
GiNaC::matrix spatial_block(const GiNaC::matrix& v, unsigned first);
/// (top; bottom) of two 3x1 columns
GiNaC::matrix stacked(const GiNaC::matrix& top, const GiNaC::matrix& bottom);

}  // namespace eomgen
