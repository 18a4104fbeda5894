// The shipped robots (models/robots/*.urdf) as eomgen imports them, against MuJoCo 2.2.2
// reading the same URDF: an independent implementation of rigid-body dynamics (recursive
// algorithms on spatial vectors, its own URDF reader) against eomgen's symbolic derivation.
// At random states (fixed seeds) the mass matrix, the bias forces, the accelerations under
// joint torques and every link's pose agree to 1e-10 relative.
//
// Relative difference, everywhere below: max |eomgen - mujoco| over the entries, divided by
// max |mujoco| over the entries (the max norm of the difference over the max norm of MuJoCo's
// value). For positions the divisor is the largest coordinate of any link's origin at that
// state (the robot's size), so that a link near the origin is not held to its own small size;
// DCM entries are compared as they are (a rotation's entries are at most 1).
//
// Conventions (docs/conventions.md): M qdd = F + Xi^T lambda, F holding every force but the
// constraint forces: velocity terms, gravity, the dampers' -c qd and the inputs.
// C_ba converts components, v_b = C_ba v_a; MuJoCo's xmat maps a body's components to the
// world's, v_a = xmat v_L, so C_La = xmat^T.
//
// The MuJoCo side (support/mujoco_robot.hpp) reads a prepared copy of the URDF text: links
// kept apart (no fusestatic), no geoms, no limits, no friction loss, and each inertia on its
// exact principal axes, which MuJoCo 2.2.2 would otherwise find only to about 1e-6.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "support/mujoco_robot.hpp"
#include "support/source_dir.hpp"

namespace {

using eomgen::NamedValues;
using eomgen::NumericEquations;
using eomgen::testing::MujocoRobot;
using eomgen::testing::UrdfJointSummary;
using eomgen::testing::UrdfSummary;

constexpr double tolerance = 1e-10;
const std::vector<unsigned> seeds = {1, 2, 3, 5, 8};

/// The relative difference of the file's comment: max |actual - expected| / max |expected|.
double relative_difference(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  EXPECT_EQ(actual.rows(), expected.rows());
  EXPECT_EQ(actual.cols(), expected.cols());
  if (actual.rows() != expected.rows() || actual.cols() != expected.cols()) return INFINITY;
  return (actual - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
}

/// A URDF name as the import makes it an identifier: every character outside [A-Za-z0-9_]
/// replaced by '_'.
std::string identifier(std::string name) {
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  return name;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Outputs for every link L: its origin's position in a (xcheck_L_position_1..3) and its basis
/// vectors resolved in a (xcheck_L_axis_i_1..3), the rows of its DCM: C_La(i, j) = L.i . a.j.
/// (An output dcm(L, a) entry by entry would write the product of the chain's rotations out,
/// beyond the language's limit for the iiwa's deeper links.)
std::string pose_outputs(const UrdfSummary& urdf) {
  std::string text = "\n# the tests' pose outputs of every link\n";
  for (const std::string& link : urdf.links) {
    const std::string l = identifier(link);
    text += "output xcheck_" + l + "_position = position(" + l + "_origin)\n";
    for (const char* i : {"1", "2", "3"}) text += "output xcheck_" + l + "_axis_" + i + " = " + l + "." + i + "\n";
  }
  return text;
}

/// One robot on both sides. eomgen reads the model load_model(path) reads (the import's text),
/// with pose_outputs appended; MuJoCo the prepared URDF, its joints in eomgen's coordinate order.
struct Robot {
  Robot(const std::string& urdf_text, const std::string& model_text)
      : urdf(eomgen::testing::read_urdf_summary(urdf_text)),
        model(eomgen::parse_model(model_text + pose_outputs(urdf), "robot.eom")),
        equations(eomgen::derive_equations(model)),
        joints(joints_in_coordinate_order(urdf, model)),
        mujoco(urdf_text, joint_names(joints)) {}

  static Robot shipped(const std::string& name) {
    const std::string path = (eomgen::testing::source_dir() / "models" / "robots" / (name + ".urdf")).string();
    return Robot(read_file(path), eomgen::urdf::import_urdf(path).text);
  }

  UrdfSummary urdf;
  eomgen::Model model;
  eomgen::ModelEquations equations;
  std::vector<UrdfJointSummary> joints;  ///< the URDF joint of each coordinate
  MujocoRobot mujoco;

 private:
  static std::vector<UrdfJointSummary> joints_in_coordinate_order(const UrdfSummary& urdf, const eomgen::Model& model) {
    std::vector<UrdfJointSummary> joints;
    for (const auto& coordinate : model.system.variables().coordinates()) {
      const auto it = std::find_if(urdf.joints.begin(), urdf.joints.end(),
                                   [&](const UrdfJointSummary& j) { return j.moves() && identifier(j.name) == coordinate.name; });
      if (it == urdf.joints.end()) throw std::runtime_error("no URDF joint for the coordinate " + coordinate.name);
      joints.push_back(*it);
    }
    return joints;
  }
  static std::vector<std::string> joint_names(const std::vector<UrdfJointSummary>& joints) {
    std::vector<std::string> names;
    for (const auto& j : joints) names.push_back(j.name);
    return names;
  }
};

/// A state in eomgen's coordinate order: q inside the joint's limits (continuous joints in
/// [-pi, pi]), rates up to 2 rad/s or 0.2 m/s, and with_inputs, torques up to 10 N m and forces up
/// to 10 N on the actuated joints. A mimic joint follows the joint it mimics, in q and qd.
struct State {
  Eigen::VectorXd q, qd, u;
};

State random_state(const Robot& robot, unsigned seed, bool with_inputs) {
  std::mt19937 rng(seed);
  const auto n = static_cast<Eigen::Index>(robot.joints.size());
  State s{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  const auto uniform = [&](double low, double high) { return std::uniform_real_distribution<double>(low, high)(rng); };
  for (Eigen::Index k = 0; k < n; ++k) {
    const UrdfJointSummary& j = robot.joints[k];
    const bool prismatic = j.type == "prismatic";
    s.q[k] = j.lower && j.upper ? uniform(*j.lower, *j.upper) : uniform(-M_PI, M_PI);
    s.qd[k] = prismatic ? uniform(-0.2, 0.2) : uniform(-2, 2);
    if (with_inputs && !j.mimicked) s.u[k] = uniform(-10, 10);
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    const UrdfJointSummary& j = robot.joints[k];
    if (!j.mimicked) continue;
    const auto leader = std::find_if(robot.joints.begin(), robot.joints.end(),
                                     [&](const UrdfJointSummary& other) { return other.name == *j.mimicked; });
    const Eigen::Index l = leader - robot.joints.begin();
    s.q[k] = j.mimic_multiplier * s.q[l] + j.mimic_offset;
    s.qd[k] = j.mimic_multiplier * s.qd[l];
  }
  return s;
}

/// The state by the names of eomgen's model: coordinates, rates (NAME_dot) and the inputs
/// <joint>_torque (revolute, continuous) or <joint>_force (prismatic) of the import's contract.
NamedValues named(const Robot& robot, const State& s) {
  NamedValues values;
  for (std::size_t k = 0; k < robot.joints.size(); ++k) {
    const auto& coordinate = robot.model.system.variables().coordinates()[k];
    values[coordinate.name] = s.q[k];
    values[coordinate.name + "_dot"] = s.qd[k];
    if (robot.joints[k].mimicked) continue;
    const bool prismatic = robot.joints[k].type == "prismatic";
    values[coordinate.name + (prismatic ? "_force" : "_torque")] = s.u[k];
  }
  return values;
}

NumericEquations eomgen_at(const Robot& robot, const State& s) {
  return eomgen::evaluate_equations(robot.model, robot.equations, named(robot, s));
}

double output(const NumericEquations& eq, const std::string& label) {
  for (const auto& [name, value] : eq.outputs)
    if (name == label) return value;
  ADD_FAILURE() << "no output " << label;
  return NAN;
}

/// Fails the test at a relative difference above `tolerance`, and records the largest one as the
/// test's property largest_relative_difference (in ctest's or --gtest_output's report).
class LargestDifference {
 public:
  void add(double difference, const std::string& where) {
    EXPECT_LE(difference, tolerance) << where;
    largest_ = std::max(largest_, difference);
  }
  ~LargestDifference() {
    std::ostringstream text;
    text << std::scientific << std::setprecision(2) << largest_;
    ::testing::Test::RecordProperty("largest_relative_difference", text.str());
  }

 private:
  double largest_ = 0;
};

class MujocoCrossCheck : public ::testing::TestWithParam<std::string> {
 protected:
  Robot robot = Robot::shipped(GetParam());
};

TEST_P(MujocoCrossCheck, MujocoHasEveryLinkAsABodyWithTheUrdfMassAndInertia) {
  // the MuJoCo side alone: the preparation keeps every link a body (MuJoCo's world body stands
  // for a root link named "world"), and its principal axes rebuild each inertia about the mass
  // centre, in the link frame, to rounding
  const UrdfSummary& urdf = robot.urdf;
  EXPECT_EQ(robot.mujoco.model().nbody, static_cast<int>(urdf.links.size()) + (urdf.links.front() == "world" ? 0 : 1));
  for (std::size_t k = 0; k < urdf.links.size(); ++k) {
    if (!urdf.inertials[k]) continue;
    EXPECT_EQ(robot.mujoco.mass(urdf.links[k]), urdf.inertials[k]->mass) << urdf.links[k];
    EXPECT_LE(relative_difference(robot.mujoco.inertia(urdf.links[k]), urdf.inertials[k]->inertia_in_link()), 1e-14)
        << urdf.links[k];
  }
}

TEST_P(MujocoCrossCheck, MassMatrixEqualsMujocosFullM) {
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const State s = random_state(robot, seed, false);
    robot.mujoco.forward(s.q, s.qd, s.u);
    largest.add(relative_difference(eomgen_at(robot, s).mass_matrix, robot.mujoco.mass_matrix()),
                "seed " + std::to_string(seed));
  }
}

TEST_P(MujocoCrossCheck, ForcingAtZeroInputIsMujocosPassiveMinusBiasForces) {
  // eomgen's F holds the dampers' -c qd; MuJoCo keeps damping in qfrc_passive, apart from the
  // velocity and gravity terms of qfrc_bias: -F = qfrc_bias - qfrc_passive
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const State s = random_state(robot, seed, false);
    robot.mujoco.forward(s.q, s.qd, s.u);
    largest.add(relative_difference(-eomgen_at(robot, s).forcing,
                                    robot.mujoco.bias_forces() - robot.mujoco.passive_forces()),
                "seed " + std::to_string(seed));
  }
}

TEST_P(MujocoCrossCheck, AccelerationsUnderJointTorquesEqualMujocosWithoutTheMimicConstraint) {
  // MuJoCo 2.2.2 ignores <mimic>, so for the Panda this compares the accelerations without the
  // mimic constraint, M^-1 (F + tau), on both sides (eomgen's F holds the inputs tau); the
  // constrained ones are MujocoCrossCheckPanda.FingerAccelerationsUnderTheMimicConstraint... below
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const State s = random_state(robot, seed, true);
    robot.mujoco.forward(s.q, s.qd, s.u);
    const NumericEquations eq = eomgen_at(robot, s);
    const Eigen::LLT<Eigen::MatrixXd> cholesky(eq.mass_matrix);
    ASSERT_EQ(cholesky.info(), Eigen::Success);
    largest.add(relative_difference(cholesky.solve(eq.forcing), robot.mujoco.accelerations()),
                "seed " + std::to_string(seed));
    if (eq.constraint_jacobian.rows() == 0)  // eomgen's own solve then is the same Cholesky
      largest.add(relative_difference(eomgen::solve_accelerations(eq).qdd, robot.mujoco.accelerations()),
                  "solve_accelerations, seed " + std::to_string(seed));
  }
}

TEST_P(MujocoCrossCheck, EveryLinkPoseEqualsMujocosXposAndXmat) {
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const State s = random_state(robot, seed, false);
    robot.mujoco.forward(s.q, s.qd, s.u);
    const NumericEquations eq = eomgen_at(robot, s);
    double size = 0;
    for (const std::string& link : robot.urdf.links)
      size = std::max(size, robot.mujoco.position(link).cwiseAbs().maxCoeff());
    for (const std::string& link : robot.urdf.links) {
      const std::string name = "xcheck_" + identifier(link);
      Eigen::Vector3d position;
      Eigen::Matrix3d dcm;  // C_La
      for (int i = 0; i < 3; ++i) {
        position[i] = output(eq, name + "_position_" + std::to_string(i + 1));
        for (int j = 0; j < 3; ++j)
          dcm(i, j) = output(eq, name + "_axis_" + std::to_string(i + 1) + "_" + std::to_string(j + 1));
      }
      const std::string where = link + ", seed " + std::to_string(seed);
      largest.add((position - robot.mujoco.position(link)).cwiseAbs().maxCoeff() / size, where + ": position");
      largest.add((dcm - robot.mujoco.orientation(link).transpose()).cwiseAbs().maxCoeff(), where + ": C_La = xmat^T");
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedRobots, MujocoCrossCheck, ::testing::Values("ur5", "iiwa14", "panda", "two_arm_torso"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(MujocoCrossCheckPanda, FingerAccelerationsUnderTheMimicConstraintEqualAKktSolveOnMujocosDynamics) {
  // MuJoCo has no exact joint coupling (its equality constraints are soft), so the constrained
  // accelerations on its side are the KKT solve of docs/conventions.md on its M and forces, with
  // the mimic q2 = k q1 + c written here from the URDF: Xi = [.., -k, .., 1], b = 0
  Robot robot = Robot::shipped("panda");
  const auto n = static_cast<Eigen::Index>(robot.joints.size());
  Eigen::MatrixXd xi = Eigen::MatrixXd::Zero(1, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!robot.joints[k].mimicked) continue;
    for (Eigen::Index l = 0; l < n; ++l)
      if (robot.joints[l].name == *robot.joints[k].mimicked) xi(0, l) = -robot.joints[k].mimic_multiplier;
    xi(0, k) = 1;
  }
  ASSERT_EQ((xi.array() != 0).count(), 2) << "the Panda's one mimic joint and its leader";
  LargestDifference largest;
  for (unsigned seed : seeds) {
    const State s = random_state(robot, seed, true);
    robot.mujoco.forward(s.q, s.qd, s.u);
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + 1, n + 1);
    kkt.topLeftCorner(n, n) = robot.mujoco.mass_matrix();
    kkt.topRightCorner(n, 1) = -xi.transpose();
    kkt.bottomLeftCorner(1, n) = -xi;
    Eigen::VectorXd right = Eigen::VectorXd::Zero(n + 1);
    right.head(n) = s.u + robot.mujoco.passive_forces() - robot.mujoco.bias_forces();
    const Eigen::VectorXd mujoco_qdd = kkt.fullPivLu().solve(right).head(n);
    const NumericEquations eq = eomgen_at(robot, s);
    ASSERT_EQ(eq.constraint_jacobian.rows(), 1);
    largest.add(relative_difference(eomgen::solve_accelerations(eq).qdd, mujoco_qdd), "seed " + std::to_string(seed));
  }
}

// A pendulum by hand, on both sides: one revolute joint about y at height 1, its link's mass
// centre 0.5 below the joint and an inertia given with products in turned axes, damping c.
// The mass centre is at (-0.5 sin q, 0, 1 - 0.5 cos q), so
//   M = J_yy + m 0.5^2 (J in the link frame),   F = -m g 0.5 sin q - c qd + tau,
// and the link's frame is a turned by +q about a.2: xmat = Ry(q), C_La = Ry(q)^T.
TEST(MujocoCrossCheckPendulum, BothSidesMatchTheClosedFormOfAPendulumWithTurnedInertiaAndDamping) {
  const std::string urdf = R"(<robot name="pendulum">
  <link name="base"/>
  <joint name="hinge" type="revolute">
    <parent link="base"/> <child link="arm"/>
    <origin xyz="0 0 1" rpy="0 0 0"/> <axis xyz="0 1 0"/> <dynamics damping="0.4"/>
  </joint>
  <link name="arm">
    <inertial>
      <origin xyz="0 0 -0.5" rpy="0.3 0.2 0.1"/> <mass value="2"/>
      <inertia ixx="0.1" ixy="0.01" ixz="-0.02" iyy="0.2" iyz="0.03" izz="0.15"/>
    </inertial>
  </link>
</robot>)";
  Robot robot(urdf, eomgen::urdf::write_model(eomgen::urdf::read_robot(urdf, "pendulum.urdf")).text);
  const double m = 2, g = 9.81, c = 0.4;
  Eigen::Matrix3d given;
  given << 0.1, 0.01, -0.02, 0.01, 0.2, 0.03, -0.02, 0.03, 0.15;
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())).toRotationMatrix();
  const double mass_matrix = (turn * given * turn.transpose())(1, 1) + m * 0.25;
  for (const auto& [q, qd, tau] : {std::tuple{0.4, -1.1, 2.0}, std::tuple{-2.0, 0.7, -3.0}, std::tuple{1.3, 2.5, 0.5}}) {
    const State s{Eigen::VectorXd::Constant(1, q), Eigen::VectorXd::Constant(1, qd), Eigen::VectorXd::Constant(1, tau)};
    const double forcing = -m * g * 0.5 * std::sin(q) - c * qd + tau;
    Eigen::Matrix3d turned_by_q;  // Ry(q), the link's axes in a
    turned_by_q << std::cos(q), 0, std::sin(q), 0, 1, 0, -std::sin(q), 0, std::cos(q);
    const std::string where = "q = " + std::to_string(q);

    robot.mujoco.forward(s.q, s.qd, s.u);
    EXPECT_LE(std::fabs(robot.mujoco.mass_matrix()(0, 0) / mass_matrix - 1), tolerance) << where;
    EXPECT_LE(std::fabs((tau + robot.mujoco.passive_forces()[0] - robot.mujoco.bias_forces()[0]) / forcing - 1), tolerance)
        << where;
    EXPECT_LE(std::fabs(robot.mujoco.accelerations()[0] * mass_matrix / forcing - 1), tolerance) << where;
    EXPECT_LE((robot.mujoco.position("arm") - Eigen::Vector3d(0, 0, 1)).norm(), tolerance) << where;
    EXPECT_LE((robot.mujoco.orientation("arm") - turned_by_q).cwiseAbs().maxCoeff(), tolerance) << where;

    const NumericEquations eq = eomgen_at(robot, s);
    EXPECT_LE(std::fabs(eq.mass_matrix(0, 0) / mass_matrix - 1), tolerance) << where;
    EXPECT_LE(std::fabs(eq.forcing[0] / forcing - 1), tolerance) << where;
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::fabs(output(eq, "xcheck_arm_position_" + std::to_string(i + 1)) - (i == 2 ? 1 : 0)), tolerance);
      for (int j = 0; j < 3; ++j)  // C_La = Ry(q)^T
        EXPECT_LE(std::fabs(output(eq, "xcheck_arm_axis_" + std::to_string(i + 1) + "_" + std::to_string(j + 1)) -
                            turned_by_q(j, i)),
                  tolerance)
            << where << ", C_La(" << i << ", " << j << ")";
    }
  }
}

// The preparation writes principal axes as roll, pitch, yaw. Most of the UR5's links (cylinders
// whose largest moment is about their z axis) get them at pitch +-pi/2 exactly, where a naive
// reading of roll and yaw from the matrix's small entries loses every digit (and near it, digits
// in proportion).
TEST(MujocoCrossCheckPreparation, RollPitchYawRebuildsRotationsAtAndNearPitchOfHalfPi) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (double pitch : {M_PI / 2, -M_PI / 2, M_PI / 2 - 1e-9, -M_PI / 2 + 1e-6, M_PI / 2 - 1e-3, 0.3}) {
    for (int k = 0; k < 20; ++k) {
      const Eigen::Matrix3d c = eomgen::testing::rotation_from_rpy(Eigen::Vector3d(angle(rng), pitch, angle(rng)));
      const Eigen::Vector3d rpy = eomgen::testing::roll_pitch_yaw(c);
      EXPECT_LE((eomgen::testing::rotation_from_rpy(rpy) - c).cwiseAbs().maxCoeff(), 1e-15) << "pitch " << pitch;
    }
  }
}

}  // namespace
