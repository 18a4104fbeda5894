// The numeric mass matrix of a URDF robot and its first singular joint (joint_space_inertia.hpp).
#include "joint_space_inertia.hpp"

#include <cmath>
#include <random>
#include <set>

namespace eomgen::urdf {
namespace {

// one coordinate's motion, in the world: a velocity v of every point plus a turn w about o
struct Twist {
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero(), o = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_at(const Eigen::Vector3d& p) const { return v + w.cross(p - o); }
};

Eigen::Vector3d vector(const Triple& t) { return {t[0].value, t[1].value, t[2].value}; }

// R = Rz(yaw) Ry(pitch) Rx(roll), taking a frame's components to its parent's
Eigen::Matrix3d rpy_rotation(const Triple& rpy) {
  return (Eigen::AngleAxisd(rpy[2].value, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy[1].value, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0].value, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Isometry3d pose(const Origin& o) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rpy_rotation(o.rpy);
  T.translation() = vector(o.xyz);
  return T;
}

int coordinate_count(Joint::Type t) {
  switch (t) {
    case Joint::Type::revolute:
    case Joint::Type::continuous:
    case Joint::Type::prismatic: return 1;
    case Joint::Type::fixed: return 0;
    case Joint::Type::planar: return 3;
    case Joint::Type::floating: return 6;
  }
  return 0;
}

}  // namespace

const Joint* first_singular_joint(const Robot& robot, const std::vector<const Joint*>& order,
                                  const std::function<std::optional<BodyData>(const Link&)>& body) {
  std::map<std::string, const Link*> links;
  for (const Link& l : robot.links) links[l.name] = &l;
  std::map<std::string, const Joint*> joints;
  for (const Joint* j : order) joints[j->name] = j;
  // a generic configuration, the same in every run
  std::mt19937 random(20261205);
  std::uniform_real_distribution<double> value(-1.0, 1.0);

  std::vector<Twist> twists;                     // per coordinate
  std::vector<const Joint*> owner;               // per coordinate
  std::map<std::string, std::size_t> first_of;   // joint -> its first coordinate
  std::map<std::string, Eigen::Isometry3d> pose_of;
  std::map<std::string, std::vector<std::size_t>> moved_by;  // link -> the coordinates that move it
  std::size_t count = 0;
  for (const Joint* j : order) count += static_cast<std::size_t>(coordinate_count(j->type));
  if (count > largest_checked) return nullptr;
  std::set<std::string> children;
  for (const Joint* j : order) children.insert(j->child);
  // a joint whose parent is "" joins its child to the world (a floating base)
  pose_of[""] = Eigen::Isometry3d::Identity();
  moved_by[""] = {};
  for (const Link& l : robot.links)
    if (children.count(l.name) == 0) {
      pose_of[l.name] = Eigen::Isometry3d::Identity();
      moved_by[l.name] = {};
    }
  for (const Joint* j : order) {
    const Eigen::Isometry3d J = pose_of.at(j->parent) * pose(j->origin);
    const Eigen::Matrix3d& R = J.linear();
    std::vector<std::size_t> moving = moved_by.at(j->parent);
    first_of[j->name] = twists.size();
    const auto add = [&](const Twist& t) {
      moving.push_back(twists.size());
      twists.push_back(t);
      owner.push_back(j);
    };
    Eigen::Isometry3d child = J;
    const Eigen::Vector3d axis = vector(j->axis).normalized();
    switch (j->type) {
      case Joint::Type::revolute:
      case Joint::Type::continuous: {
        const double q = value(random);
        add(Twist{Eigen::Vector3d::Zero(), R * axis, J.translation()});
        child = J * Eigen::AngleAxisd(q, axis);
        break;
      }
      case Joint::Type::prismatic: {
        const double q = value(random);
        add(Twist{R * axis, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
        child = J * Eigen::Translation3d(axis * q);
        break;
      }
      case Joint::Type::fixed:
        break;
      case Joint::Type::planar: {
        // x, y along the plane's axes in cyclic order after the normal, theta about the normal
        int k = 0;
        for (int i = 0; i < 3; ++i)
          if (std::abs(axis(i)) > 0.5) k = i;
        const double sign = axis(k) > 0 ? 1 : -1;
        const Eigen::Vector3d u = Eigen::Vector3d::Unit((k + 1) % 3), v = Eigen::Vector3d::Unit((k + 2) % 3);
        const double x = value(random), y = value(random), theta = value(random);
        const Eigen::Vector3d offset = x * u + y * v;
        add(Twist{R * u, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
        add(Twist{R * v, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
        add(Twist{Eigen::Vector3d::Zero(), R * (sign * Eigen::Vector3d::Unit(k)), J * offset});
        child = J * Eigen::Translation3d(offset) * Eigen::AngleAxisd(sign * theta, Eigen::Vector3d::Unit(k));
        break;
      }
      case Joint::Type::floating: {
        // x, y, z along the joint frame's axes, then yaw, pitch, roll (3-2-1)
        const Eigen::Vector3d xyz(value(random), value(random), value(random));
        const double yaw = value(random), pitch = value(random), roll = value(random);
        for (int i = 0; i < 3; ++i) add(Twist{R * Eigen::Vector3d::Unit(i), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
        const Eigen::Vector3d o = J * xyz;
        const Eigen::Matrix3d Rz = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const Eigen::Matrix3d Ry = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
        add(Twist{Eigen::Vector3d::Zero(), R * Eigen::Vector3d::UnitZ(), o});
        add(Twist{Eigen::Vector3d::Zero(), R * Rz * Eigen::Vector3d::UnitY(), o});
        add(Twist{Eigen::Vector3d::Zero(), R * Rz * Ry * Eigen::Vector3d::UnitX(), o});
        child = J * Eigen::Translation3d(xyz) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
        break;
      }
    }
    pose_of[j->child] = child;
    moved_by[j->child] = std::move(moving);
  }

  const auto n = static_cast<Eigen::Index>(twists.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (const auto& [name, T] : pose_of) {
    if (links.count(name) == 0) continue;  // the world
    const std::optional<BodyData> b = body(*links.at(name));
    if (!b) continue;
    const Link& l = *links.at(name);
    const Eigen::Vector3d centre = T * vector(l.inertial->origin.xyz);
    const Eigen::Matrix3d R = T.linear() * rpy_rotation(l.inertial->origin.rpy);
    const Eigen::Matrix3d J = R * b->inertia * R.transpose();
    const std::vector<std::size_t>& moving = moved_by.at(name);
    Eigen::MatrixXd Jv = Eigen::MatrixXd::Zero(3, n), Jw = Eigen::MatrixXd::Zero(3, n);
    for (std::size_t c : moving) {
      Jv.col(static_cast<Eigen::Index>(c)) = twists[c].velocity_at(centre);
      Jw.col(static_cast<Eigen::Index>(c)) = twists[c].w;
    }
    M += b->mass * Jv.transpose() * Jv + Jw.transpose() * J * Jw;
  }

  // a joint that mimics another moves with it: its column counts as the other's, times the multiplier
  std::vector<std::size_t> independent;  // coordinates
  std::map<std::size_t, Eigen::Index> column_of;
  for (std::size_t c = 0; c < twists.size(); ++c) {
    const Joint* j = owner[c];
    if (j->mimic && joints.count(j->mimic->joint) != 0) continue;
    column_of[c] = static_cast<Eigen::Index>(independent.size());
    independent.push_back(c);
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(independent.size()));
  for (std::size_t c = 0; c < twists.size(); ++c) {
    const Joint* j = owner[c];
    if (column_of.count(c) != 0) {
      T(static_cast<Eigen::Index>(c), column_of.at(c)) = 1;
    } else {
      const std::size_t leader = first_of.at(j->mimic->joint);
      if (column_of.count(leader) != 0) T(static_cast<Eigen::Index>(c), column_of.at(leader)) = j->mimic->multiplier.value;
    }
  }
  const Eigen::MatrixXd A = T.transpose() * M * T;
  // LDL^T without pivoting: the leading block of k coordinates is singular, those before it
  // being regular, exactly when the k-th pivot vanishes, i.e. the k-th coordinate moves nothing
  // the ones before it do not
  const Eigen::Index m = A.rows();
  const double scale = m == 0 ? 0.0 : A.diagonal().cwiseAbs().maxCoeff();
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    double pivot = A(k, k);
    for (Eigen::Index j = 0; j < k; ++j) pivot -= L(k, j) * L(k, j) * d(j);
    if (!(pivot > 1e-12 * scale)) return owner[independent[static_cast<std::size_t>(k)]];
    d(k) = pivot;
    for (Eigen::Index i = k + 1; i < m; ++i) {
      double sum = A(i, k);
      for (Eigen::Index j = 0; j < k; ++j) sum -= L(i, j) * L(k, j) * d(j);
      L(i, k) = sum / pivot;
    }
  }
  return nullptr;
}

}  // namespace eomgen::urdf
