// The functions a controller calls, in the headers generated from the shipped robots
// (models/robots/*.urdf, eomgen_add_model at build time), against MuJoCo 2.2.2 reading the
// same URDF (tests/support/mujoco_robot.hpp prepares it as mujoco_cross_check_test.cpp does:
// every link a body, no geoms, limits or friction loss, inertias on exact principal axes).
// At random states (fixed seeds), to 1e-10 relative:
//  - inverse_dynamics(t, q, qd, qdd, u, c, tau) against mj_inverse's qfrc_inverse;
//  - gravity_forces, coriolis_matrix (C qd + G) and the regressor (Y pi) against the same;
//  - every output_jacobian_<link>_position (the origin of a leaf link, resolved in the world)
//    against mj_jac's jacp at that link's body origin, and every
//    output_jacobian_<link>_angular_velocity against its jacr;
// and output_bias_<link>_* (Jdot qd) against central differences of J(q + s qd) qd in s, to
// 1e-6 relative.
//
// Relative difference, everywhere below: max |eomgen - reference| over the entries, divided by
// max |reference| over the entries.
//
// Conventions. Ours: tau = M qdd - F, F holding every force but the constraint forces:
// velocity terms, gravity, the dampers' -c qd and the inputs u (docs/conventions.md). MuJoCo's:
// qfrc_inverse = M qacc + qfrc_bias - qfrc_passive - qfrc_constraint, the "net external force"
// (qfrc_applied + qfrc_actuator) that produces qacc; qfrc_bias = C qd + G, qfrc_passive holds the
// dampers' -c qd (the URDF's <dynamics damping>, which the preparation keeps: the iiwa14's, the
// torso's and the Panda's joints have dampers, so they enter on both sides), and
// qfrc_constraint is zero here (nefc = 0, checked). So at u = 0, tau = qfrc_inverse, and with
// inputs on the driven joints tau + u = qfrc_inverse. MuJoCo 2.2.2's mj_inverse is the
// continuous-time inverse (it converts no discrete-time acceleration for the Euler integrator's
// implicit damping: the model's default integrator stays, and the dampers agree to rounding).
//
// The Panda: its second finger mimics the first (a constraint, nc = 1), which MuJoCo 2.2.2
// ignores, so MuJoCo's qfrc_inverse is M qdd - F of the tree without it. Our inverse_dynamics
// splits that same M qdd - F into tau, orthogonal to the rows of Xi, and Xi^T lambda. With Xi
// written here from the URDF's <mimic> (q2 = k q1 + offset: Xi = [.., -k, .., 1]) and qdd
// satisfying it, the comparison is well defined: tau + Xi^T lambda = qfrc_inverse, Xi tau = 0,
// lambda = (Xi Xi^T)^-1 Xi qfrc_inverse.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "iiwa14.hpp"
#include "panda.hpp"
#include "support/mujoco_robot.hpp"
#include "support/source_dir.hpp"
#include "two_arm_torso.hpp"
#include "ur5.hpp"

namespace {

using eomgen::testing::MujocoRobot;
using eomgen::testing::UrdfJointSummary;

constexpr double tolerance = 1e-10;
constexpr double bias_tolerance = 1e-6;  // central differences with a step of 1e-5
const std::vector<unsigned> seeds = {1, 2, 3, 5, 8};

/// The relative difference of the file's comment: max |actual - expected| / max |expected|.
double relative_difference(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  EXPECT_EQ(actual.rows(), expected.rows());
  EXPECT_EQ(actual.cols(), expected.cols());
  if (actual.rows() != expected.rows() || actual.cols() != expected.cols()) return INFINITY;
  return (actual - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
}

/// Fails the test at a relative difference above `limit`, and records the largest one as the
/// test's property largest_relative_difference (in ctest's or --gtest_output's report).
class LargestDifference {
 public:
  explicit LargestDifference(double limit = tolerance) : limit_(limit) {}
  void add(double difference, const std::string& where) {
    EXPECT_LE(difference, limit_) << where;
    largest_ = std::max(largest_, difference);
  }
  LargestDifference(const LargestDifference&) = delete;
  LargestDifference& operator=(const LargestDifference&) = delete;
  ~LargestDifference() {
    std::ostringstream text;
    text << std::scientific << std::setprecision(2) << largest_;
    ::testing::Test::RecordProperty("largest_relative_difference", text.str());
  }

 private:
  double limit_, largest_ = 0;
};

/// A URDF name as the import makes it an identifier: every character outside [A-Za-z0-9_]
/// replaced by '_'.
std::string identifier(std::string name) {
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  return name;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// The output Jacobians and biases of one leaf link (a tool frame) of a header: its origin's
/// position and its angular velocity, both resolved in the world frame a.
template <class Model>
struct Tool {
  using Vec = typename Model::template Vector<double>;
  using Consts = typename Model::template Constants<double>;
  using Jacobian = Eigen::Matrix<double, 3, Model::nq>;
  std::string link;
  std::function<void(const Vec&, const Consts&, Jacobian&)> position_jacobian, angular_jacobian;
  std::function<void(const Vec&, const Vec&, const Consts&, Eigen::Vector3d&)> position_bias, angular_bias;
};

// The header's functions of the leaf link LINK (a URDF link name that is an identifier).
#define EOMGEN_TEST_TOOL(M, LINK)                                                                   \
  Tool<M> {                                                                                         \
    #LINK, [](const auto& q, const auto& c, auto& J) { M::output_jacobian_##LINK##_position(0.0, q, c, J); },  \
        [](const auto& q, const auto& c, auto& J) { M::output_jacobian_##LINK##_angular_velocity(0.0, q, c, J); }, \
        [](const auto& q, const auto& qd, const auto& c, auto& b) { M::output_bias_##LINK##_position(0.0, q, qd, c, b); }, \
        [](const auto& q, const auto& qd, const auto& c, auto& b) {                                 \
          M::output_bias_##LINK##_angular_velocity(0.0, q, qd, c, b);                               \
        }                                                                                           \
  }

// The robots: their header's Model, their URDF file's stem and their leaf links.
struct Ur5 {
  using Model = eomgen_models::ur5::Model;
  static constexpr const char* name = "ur5";
  static std::vector<Tool<Model>> tools() { return {EOMGEN_TEST_TOOL(Model, tool0)}; }
};
struct Iiwa14 {
  using Model = eomgen_models::iiwa14::Model;
  static constexpr const char* name = "iiwa14";
  static std::vector<Tool<Model>> tools() {
    return {EOMGEN_TEST_TOOL(Model, iiwa_link_ee), EOMGEN_TEST_TOOL(Model, iiwa_link_ee_kuka)};
  }
};
struct TwoArmTorso {
  using Model = eomgen_models::two_arm_torso::Model;
  static constexpr const char* name = "two_arm_torso";
  static std::vector<Tool<Model>> tools() {
    return {EOMGEN_TEST_TOOL(Model, left_ee), EOMGEN_TEST_TOOL(Model, right_ee)};
  }
};
struct Panda {
  using Model = eomgen_models::panda::Model;
  static constexpr const char* name = "panda";
  static std::vector<Tool<Model>> tools() {
    return {EOMGEN_TEST_TOOL(Model, panda_hand_tcp), EOMGEN_TEST_TOOL(Model, panda_leftfinger),
            EOMGEN_TEST_TOOL(Model, panda_rightfinger)};
  }
};

/// MuJoCo's side of a robot: the prepared URDF (MujocoRobot) and an mjData of this file's own
/// for mj_inverse and mj_jac, read and written in the header's coordinate order.
class Mujoco {
 public:
  Mujoco(const std::string& urdf_text, const std::vector<std::string>& joints)
      : robot_(urdf_text, joints), data_(mj_makeData(&robot_.model()), mj_deleteData) {
    const mjModel& m = robot_.model();
    for (const std::string& joint : joints) {
      const int id = mj_name2id(&m, mjOBJ_JOINT, joint.c_str());
      qpos_address_.push_back(m.jnt_qposadr[id]);
      dof_address_.push_back(m.jnt_dofadr[id]);
    }
  }

  /// mj_inverse at (q, qd, qacc = qdd), which runs the position and velocity stages itself.
  /// \throws std::runtime_error if MuJoCo adds constraint rows or warns.
  void inverse(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
    const mjModel* m = &robot_.model();
    mjData* d = data_.get();
    mj_resetData(m, d);
    for (std::size_t k = 0; k < dof_address_.size(); ++k) {
      d->qpos[qpos_address_[k]] = q[static_cast<Eigen::Index>(k)];
      d->qvel[dof_address_[k]] = qd[static_cast<Eigen::Index>(k)];
      d->qacc[dof_address_[k]] = qdd[static_cast<Eigen::Index>(k)];
    }
    mj_inverse(m, d);
    if (d->nefc != 0) throw std::runtime_error("Mujoco: MuJoCo has constraint rows");
    for (int w = 0; w < mjNWARNING; ++w)
      if (d->warning[w].number != 0) throw std::runtime_error("Mujoco: MuJoCo warns (" + std::to_string(w) + ")");
  }
  Eigen::VectorXd inverse_forces() const { return in_order(data_->qfrc_inverse); }  ///< qfrc_inverse
  Eigen::VectorXd bias_forces() const { return in_order(data_->qfrc_bias); }        ///< qfrc_bias
  Eigen::VectorXd passive_forces() const { return in_order(data_->qfrc_passive); }  ///< qfrc_passive

  /// The origin of body `link` in the world, xpos (after inverse()).
  Eigen::Vector3d position(const std::string& link) const {
    return Eigen::Map<const Eigen::Vector3d>(data_->xpos + 3 * body(link));
  }
  /// The largest coordinate of any body's origin: the robot's size at this state.
  double size() const {
    return Eigen::Map<const Eigen::VectorXd>(data_->xpos, 3 * robot_.model().nbody).cwiseAbs().maxCoeff();
  }
  /// mj_jac at the origin of body `link` (after inverse(), which ran mj_kinematics and
  /// mj_comPos): jacp (rows: world components of the point's velocity) and jacr (of the body's
  /// angular velocity), columns in the header's coordinate order.
  void jacobians(const std::string& link, Eigen::MatrixXd& jacp, Eigen::MatrixXd& jacr) const {
    const mjModel* m = &robot_.model();
    const int b = body(link);
    using RowMajor = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
    RowMajor p(3, m->nv), r(3, m->nv);
    mj_jac(m, data_.get(), p.data(), r.data(), data_->xpos + 3 * b, b);
    const auto n = static_cast<Eigen::Index>(dof_address_.size());
    jacp.resize(3, n);
    jacr.resize(3, n);
    for (Eigen::Index k = 0; k < n; ++k) {
      jacp.col(k) = p.col(dof_address_[static_cast<std::size_t>(k)]);
      jacr.col(k) = r.col(dof_address_[static_cast<std::size_t>(k)]);
    }
  }

 private:
  int body(const std::string& link) const {
    const int id = mj_name2id(&robot_.model(), mjOBJ_BODY, link.c_str());
    if (id < 0) throw std::runtime_error("Mujoco: MuJoCo has no body '" + link + "'");
    return id;
  }
  Eigen::VectorXd in_order(const mjtNum* by_dof) const {
    Eigen::VectorXd v(static_cast<Eigen::Index>(dof_address_.size()));
    for (std::size_t k = 0; k < dof_address_.size(); ++k) v[static_cast<Eigen::Index>(k)] = by_dof[dof_address_[k]];
    return v;
  }

  MujocoRobot robot_;
  std::unique_ptr<mjData, void (*)(mjData*)> data_;
  std::vector<int> qpos_address_, dof_address_;  // per coordinate of the header
};

/// The URDF joint of each of the header's coordinates, in coordinate order.
template <class Model>
std::vector<UrdfJointSummary> joints_of_coordinates(const eomgen::testing::UrdfSummary& urdf) {
  std::vector<UrdfJointSummary> joints;
  for (const char* coordinate : Model::coordinate_names) {
    const auto it = std::find_if(urdf.joints.begin(), urdf.joints.end(), [&](const UrdfJointSummary& j) {
      return j.moves() && identifier(j.name) == coordinate;
    });
    if (it == urdf.joints.end()) throw std::runtime_error(std::string("no URDF joint for the coordinate ") + coordinate);
    joints.push_back(*it);
  }
  return joints;
}

std::vector<std::string> names_of(const std::vector<UrdfJointSummary>& joints) {
  std::vector<std::string> names;
  for (const auto& j : joints) names.push_back(j.name);
  return names;
}

/// One robot on both sides: its header's Model and MuJoCo reading its URDF.
template <class Robot>
struct Sides {
  using Model = typename Robot::Model;
  using Vec = typename Model::template Vector<double>;

  Sides() : Sides(read_file((eomgen::testing::source_dir() / "models" / "robots" / (std::string(Robot::name) + ".urdf")).string())) {}

  /// A state in the header's coordinate order: q inside the joint's limits (continuous joints
  /// in [-pi, pi]), rates up to 2 rad/s or 0.2 m/s, accelerations up to 5 rad/s^2 or 0.5 m/s^2;
  /// a mimic joint follows the joint it mimics in q, qd and qdd.
  struct State {
    Vec q, qd, qdd;
  };
  State random_state(unsigned seed) const {
    std::mt19937 rng(seed);
    const auto uniform = [&](double low, double high) { return std::uniform_real_distribution<double>(low, high)(rng); };
    State s{Vec::Zero(), Vec::Zero(), Vec::Zero()};
    for (int k = 0; k < Model::nq; ++k) {
      const UrdfJointSummary& j = joints[static_cast<std::size_t>(k)];
      const double scale = j.type == "prismatic" ? 0.1 : 1;
      s.q[k] = j.lower && j.upper ? uniform(*j.lower, *j.upper) : uniform(-M_PI, M_PI);
      s.qd[k] = scale * uniform(-2, 2);
      s.qdd[k] = scale * uniform(-5, 5);
    }
    for (int k = 0; k < Model::nq; ++k) {
      const UrdfJointSummary& j = joints[static_cast<std::size_t>(k)];
      if (!j.mimicked) continue;
      const int l = leader(k);
      s.q[k] = j.mimic_multiplier * s.q[l] + j.mimic_offset;
      s.qd[k] = j.mimic_multiplier * s.qd[l];
      s.qdd[k] = j.mimic_multiplier * s.qdd[l];
    }
    return s;
  }

  /// The index of the coordinate that coordinate k mimics.
  int leader(int k) const {
    const UrdfJointSummary& j = joints[static_cast<std::size_t>(k)];
    const auto it = std::find_if(joints.begin(), joints.end(),
                                 [&](const UrdfJointSummary& other) { return other.name == *j.mimicked; });
    if (it == joints.end()) throw std::runtime_error("no leader for the mimic joint " + j.name);
    return static_cast<int>(it - joints.begin());
  }

  /// Xi of the URDF's mimic joints, q_k = mult q_l + offset: the row [.., -mult (l), .., 1 (k), ..].
  Eigen::MatrixXd mimic_jacobian() const {
    std::vector<int> followers;
    for (int k = 0; k < Model::nq; ++k)
      if (joints[static_cast<std::size_t>(k)].mimicked) followers.push_back(k);
    Eigen::MatrixXd xi = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(followers.size()), Model::nq);
    for (std::size_t r = 0; r < followers.size(); ++r) {
      const auto row = static_cast<Eigen::Index>(r);
      xi(row, leader(followers[r])) = -joints[static_cast<std::size_t>(followers[r])].mimic_multiplier;
      xi(row, followers[r]) = 1;
    }
    return xi;
  }

  /// The generalized forces of the inputs u, per coordinate (input <coordinate>_torque or _force).
  Vec applied(const typename Model::template Inputs<double>& u) const {
    Vec a = Vec::Zero();
    for (int i = 0; i < Model::nu; ++i) {
      bool found = false;
      for (int k = 0; k < Model::nq; ++k)
        for (const char* suffix : {"_torque", "_force"})
          if (std::string(Model::coordinate_names[static_cast<std::size_t>(k)]) + suffix ==
              Model::input_names[static_cast<std::size_t>(i)]) {
            a[k] += u[i];
            found = true;
          }
      if (!found) throw std::runtime_error(std::string("no coordinate for the input ") + Model::input_names[static_cast<std::size_t>(i)]);
    }
    return a;
  }

  bool has_dampers() const {
    return std::any_of(joints.begin(), joints.end(), [](const UrdfJointSummary& j) { return j.damping > 0; });
  }

  std::vector<UrdfJointSummary> joints;
  std::unique_ptr<Mujoco> mujoco;
  const typename Model::template Constants<double> c{typename Model::template Parameters<double>()};

 private:
  explicit Sides(const std::string& urdf_text)
      : joints(joints_of_coordinates<Model>(eomgen::testing::read_urdf_summary(urdf_text))),
        mujoco(std::make_unique<Mujoco>(urdf_text, names_of(joints))) {}
};

template <class Robot>
class MujocoControllerFunctions : public ::testing::Test {
 protected:
  using Model = typename Robot::Model;
  using Vec = typename Model::template Vector<double>;
  using Inputs = typename Model::template Inputs<double>;
  Sides<Robot> sides;
};

struct RobotName {
  template <class Robot>
  static std::string GetName(int) {
    return Robot::name;
  }
};
using ShippedRobots = ::testing::Types<Ur5, Iiwa14, TwoArmTorso, Panda>;
TYPED_TEST_SUITE(MujocoControllerFunctions, ShippedRobots, RobotName);

TYPED_TEST(MujocoControllerFunctions, InverseDynamicsEqualsMujocosQfrcInverse) {
  using Model = typename TestFixture::Model;
  using Vec = typename TestFixture::Vec;
  auto& sides = this->sides;
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    const std::string where = "seed " + std::to_string(seed);
    sides.mujoco->inverse(s.q, s.qd, s.qdd);
    const Eigen::VectorXd reference = sides.mujoco->inverse_forces();
    if (sides.has_dampers()) {  // the dampers are exercised: MuJoCo's passive forces are theirs
      ASSERT_GT(sides.mujoco->passive_forces().cwiseAbs().maxCoeff(), 0) << where;
    }
    Vec tau;
    if constexpr (Model::nc == 0) {
      Model::inverse_dynamics(0.0, s.q, s.qd, s.qdd, TestFixture::Inputs::Zero(), sides.c, tau);
      largest.add(relative_difference(tau, reference), where + ": tau vs qfrc_inverse");
    } else {
      // the comment's split of MuJoCo's M qdd - F by the URDF's mimic
      typename Model::template ConstraintVector<double> lambda;
      Model::inverse_dynamics(0.0, s.q, s.qd, s.qdd, TestFixture::Inputs::Zero(), sides.c, tau, lambda);
      const Eigen::MatrixXd xi = sides.mimic_jacobian();
      ASSERT_EQ(xi.rows(), Model::nc);
      const double scale = reference.cwiseAbs().maxCoeff();
      largest.add(relative_difference(tau + xi.transpose() * lambda, reference),
                  where + ": tau + Xi^T lambda vs qfrc_inverse");
      largest.add((xi * tau).cwiseAbs().maxCoeff() / scale, where + ": Xi tau = 0, relative to max |qfrc_inverse|");
      const Eigen::VectorXd mujoco_lambda = (xi * xi.transpose()).ldlt().solve(xi * reference);
      largest.add((lambda - mujoco_lambda).cwiseAbs().maxCoeff() / scale,
                  where + ": lambda vs (Xi Xi^T)^-1 Xi qfrc_inverse, relative to max |qfrc_inverse|");
    }
  }
}

TYPED_TEST(MujocoControllerFunctions, InverseDynamicsWithInputsIsMujocosQfrcInverseLessTheInputs) {
  // F holds the inputs: the tau to add is what MuJoCo's net external force lacks beyond them
  using Model = typename TestFixture::Model;
  using Vec = typename TestFixture::Vec;
  auto& sides = this->sides;
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    std::mt19937 rng(seed + 100);
    typename TestFixture::Inputs u;
    for (int i = 0; i < Model::nu; ++i) u[i] = std::uniform_real_distribution<double>(-10, 10)(rng);
    sides.mujoco->inverse(s.q, s.qd, s.qdd);
    const Eigen::VectorXd reference = sides.mujoco->inverse_forces();
    Vec tau;
    Eigen::VectorXd total;
    if constexpr (Model::nc == 0) {
      Model::inverse_dynamics(0.0, s.q, s.qd, s.qdd, u, sides.c, tau);
      total = tau;
    } else {
      typename Model::template ConstraintVector<double> lambda;
      Model::inverse_dynamics(0.0, s.q, s.qd, s.qdd, u, sides.c, tau, lambda);
      total = tau + sides.mimic_jacobian().transpose() * lambda;
    }
    largest.add(relative_difference(total + sides.applied(u), reference), "seed " + std::to_string(seed));
  }
}

TYPED_TEST(MujocoControllerFunctions, GravityForcesAndCoriolisTermsAreMujocosBiasForces) {
  // qfrc_bias = C qd + G (without the dampers, which MuJoCo keeps in qfrc_passive)
  using Model = typename TestFixture::Model;
  auto& sides = this->sides;
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    const std::string where = "seed " + std::to_string(seed);
    typename TestFixture::Vec G;
    typename Model::template MassMatrix<double> C;
    Model::gravity_forces(s.q, sides.c, G);
    Model::coriolis_matrix(s.q, s.qd, sides.c, C);
    sides.mujoco->inverse(s.q, s.qd, s.qdd);
    largest.add(relative_difference(C * s.qd + G, sides.mujoco->bias_forces()), where + ": C qd + G vs qfrc_bias");
    sides.mujoco->inverse(s.q, TestFixture::Vec::Zero(), TestFixture::Vec::Zero());
    largest.add(relative_difference(G, sides.mujoco->bias_forces()), where + ": G vs qfrc_bias at rest");
  }
}

TYPED_TEST(MujocoControllerFunctions, RegressorTimesInertialParametersIsMujocosInverseDynamicsWithoutDampers) {
  // Y pi = M qdd - F + (the dampers' and inputs' forces) = qfrc_inverse + qfrc_passive at u = 0
  using Model = typename TestFixture::Model;
  auto& sides = this->sides;
  Eigen::Matrix<double, Model::npi, 1> pi;
  Model::inertial_parameters(sides.c, pi);
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    Eigen::Matrix<double, Model::nq, Model::npi> Y;
    Model::regressor(0.0, s.q, s.qd, s.qdd, sides.c, Y);
    sides.mujoco->inverse(s.q, s.qd, s.qdd);
    largest.add(relative_difference(Y * pi, sides.mujoco->inverse_forces() + sides.mujoco->passive_forces()),
                "seed " + std::to_string(seed));
  }
}

TYPED_TEST(MujocoControllerFunctions, EveryLeafLinkIsAnOutputAndAMujocoBodyAtTheOutputsPosition) {
  // the tools below are every position output of the header, and each is the origin of the
  // MuJoCo body of the same name (the preparation keeps fixed-joint links apart)
  using Model = typename TestFixture::Model;
  auto& sides = this->sides;
  const auto tools = TypeParam::tools();
  std::set<std::string> listed, in_header;
  for (const auto& tool : tools) listed.insert(tool.link);
  for (const char* output : Model::output_names)
    if (ends_with(output, "_position_1")) in_header.insert(std::string(output).substr(0, std::string(output).size() - 11));
  EXPECT_EQ(listed, in_header);

  LargestDifference largest;
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    typename Model::template OutputVector<double> y;
    Model::outputs(0.0, s.q, s.qd, TestFixture::Inputs::Zero(), sides.c, y);
    sides.mujoco->inverse(s.q, s.qd, s.qdd);
    for (const auto& tool : tools) {
      const auto at = std::find(Model::output_names.begin(), Model::output_names.end(), tool.link + "_position_1");
      ASSERT_NE(at, Model::output_names.end()) << tool.link;
      const auto first = static_cast<Eigen::Index>(at - Model::output_names.begin());
      largest.add((y.template segment<3>(first) - sides.mujoco->position(tool.link)).cwiseAbs().maxCoeff() /
                      sides.mujoco->size(),
                  tool.link + ", seed " + std::to_string(seed) + ": position vs xpos, relative to the robot's size");
    }
  }
}

TYPED_TEST(MujocoControllerFunctions, ToolJacobiansEqualMujocosJacpAndJacr) {
  using Model = typename TestFixture::Model;
  auto& sides = this->sides;
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    sides.mujoco->inverse(s.q, s.qd, s.qdd);
    for (const auto& tool : TypeParam::tools()) {
      const std::string where = tool.link + ", seed " + std::to_string(seed);
      typename Tool<Model>::Jacobian J, W;
      tool.position_jacobian(s.q, sides.c, J);
      tool.angular_jacobian(s.q, sides.c, W);
      Eigen::MatrixXd jacp, jacr;
      sides.mujoco->jacobians(tool.link, jacp, jacr);
      largest.add(relative_difference(J, jacp), where + ": position Jacobian vs jacp");
      largest.add(relative_difference(W, jacr), where + ": angular velocity Jacobian vs jacr");
    }
  }
}

TYPED_TEST(MujocoControllerFunctions, ToolBiasesAreTheRateOfTheirJacobianTimesRatesAlongTheRates) {
  // Jdot qd = d/ds [J(q + s qd) qd] at s = 0, by central differences (error ~ h^2 and
  // rounding / h, about 1e-10 of the value here)
  using Model = typename TestFixture::Model;
  using Vec = typename TestFixture::Vec;
  auto& sides = this->sides;
  constexpr double h = 1e-5;
  LargestDifference largest(bias_tolerance);
  for (unsigned seed : seeds) {
    const auto s = sides.random_state(seed);
    const Vec ahead = s.q + h * s.qd, behind = s.q - h * s.qd;
    for (const auto& tool : TypeParam::tools()) {
      const std::string where = tool.link + ", seed " + std::to_string(seed);
      typename Tool<Model>::Jacobian J_ahead, J_behind;
      Eigen::Vector3d b;
      tool.position_jacobian(ahead, sides.c, J_ahead);
      tool.position_jacobian(behind, sides.c, J_behind);
      tool.position_bias(s.q, s.qd, sides.c, b);
      largest.add(relative_difference(b, (J_ahead - J_behind) * s.qd / (2 * h)), where + ": position");
      tool.angular_jacobian(ahead, sides.c, J_ahead);
      tool.angular_jacobian(behind, sides.c, J_behind);
      tool.angular_bias(s.q, s.qd, sides.c, b);
      largest.add(relative_difference(b, (J_ahead - J_behind) * s.qd / (2 * h)), where + ": angular velocity");
    }
  }
}

}  // namespace
