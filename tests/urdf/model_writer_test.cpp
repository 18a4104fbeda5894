// What an imported URDF means, against independent formulations: the pose of every link against
// URDF's own forward kinematics (T = T_parent T(xyz) R(rpy) R(axis, q), in Eigen), a pendulum's
// equation by hand, an inertia given in turned axes against the same inertia turned by hand, a
// fixed joint against the one rigid body it makes (masses, mass centres and inertias combined by
// the parallel-axis theorem), damping and mimic joints against their definitions.
#include <Eigen/Dense>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

Model imported(const std::string& urdf) {
  const urdf::ImportResult result = urdf::write_model(urdf::read_robot(urdf, "robot.urdf"));
  return parse_model(result.text, "robot.urdf (as imported)");
}

struct Evaluated {
  Model model;
  ModelEquations eom;
  explicit Evaluated(const std::string& urdf) : model(imported(urdf)), eom(derive_equations(model)) {}
  NumericEquations at(const NamedValues& values) const { return evaluate_equations(model, eom, values); }
};

double output(const NumericEquations& e, const std::string& label) {
  for (const auto& [name, value] : e.outputs)
    if (name == label) return value;
  ADD_FAILURE() << "no output " << label;
  return NAN;
}

std::string text(double v) { return fmt::format("{:.17g}", v); }

Eigen::Matrix3d rpy_rotation(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy(2), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy(1), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy(0), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Isometry3d pose(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = xyz;
  T.linear() = rpy_rotation(rpy);
  return T;
}

const char* link(const std::string& name, double mass) {
  static std::string s;
  s = fmt::format(R"(<link name="{}"><inertial><mass value="{}"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.015"/></inertial></link>)",
                  name, mass);
  return s.c_str();
}

TEST(UrdfModel, PendulumTurnsByPlusQAboutItsAxisAsURDFSays) {
  // mass centre L along x of the link, axis +y or -y: the centre's height is -L sin q for +y
  // (R_y(q) turns x towards -z), +L sin q for -y, so F = -dV/dq = +-m g L cos q
  for (const int sign : {1, -1}) {
    const std::string urdf = fmt::format(R"(<robot name="p">
      <link name="base"/>
      <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
        <origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 {} 0"/></joint>
      <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial></link>
    </robot>)", sign);
    const Evaluated e(urdf);
    for (const double q : {0.0, 0.4, -1.3, 2.9}) {
      const NumericEquations n = e.at({{"hinge", q}, {"hinge_dot", 0.7}});
      EXPECT_NEAR(n.mass_matrix(0, 0), 0.03 + 2 * 0.25, 1e-14);
      EXPECT_NEAR(n.forcing(0), sign * 2 * 9.81 * 0.5 * std::cos(q), 1e-13) << "axis sign " << sign << ", q " << q;
    }
  }
}

TEST(UrdfModel, LinkPosesAreURDFsForwardKinematics) {
  // offsets and turns of every kind: a 3-2-1 origin, a principal and a general axis (one not of
  // unit length), a prismatic joint along -z, a fixed joint with a turn, a continuous joint
  struct JointSpec {
    const char* name;
    const char* type;
    Eigen::Vector3d xyz, rpy, axis;
  };
  const std::vector<JointSpec> joints{
      {"j1", "revolute", {0.1, -0.2, 0.3}, {0.3, -0.7, 1.1}, {0, 0, 1}},
      {"j2", "continuous", {0.0, 0.4, 0.05}, {0, 0.5, 0}, {0.6, 0, 0.8}},
      {"j3", "prismatic", {0.2, 0, 0}, {-1.2, 0, 0.4}, {0, 0, -1}},
      {"j4", "fixed", {0.01, 0.02, 0.03}, {0.2, 0.3, -0.4}, {1, 0, 0}},
      {"j5", "revolute", {0, 0, 0.1}, {0, 0, 0}, {1, 1, 0}},
  };
  std::string urdf = R"(<robot name="chain"><link name="l0"/>)";
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const JointSpec& j = joints[i];
    urdf += fmt::format(R"(<joint name="{}" type="{}"><parent link="l{}"/><child link="l{}"/>
      <origin xyz="{} {} {}" rpy="{} {} {}"/><axis xyz="{} {} {}"/></joint>)",
                        j.name, j.type, i, i + 1, j.xyz(0), j.xyz(1), j.xyz(2), j.rpy(0), j.rpy(1), j.rpy(2),
                        j.axis(0), j.axis(1), j.axis(2));
    urdf += link("l" + std::to_string(i + 1), 1.0 + 0.1 * static_cast<double>(i));
  }
  urdf += "</robot>";
  const Evaluated e(urdf);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-2, 2);
  for (int trial = 0; trial < 5; ++trial) {
    NamedValues state;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (const JointSpec& j : joints) {
      T = T * pose(j.xyz, j.rpy);
      const std::string type = j.type;
      if (type == "fixed") continue;
      const double q = value(random);
      state[j.name] = q;
      const Eigen::Vector3d axis = j.axis.normalized();
      if (type == "prismatic") {
        T.translation() += T.linear() * axis * q;
      } else {
        T = T * Eigen::Isometry3d(Eigen::AngleAxisd(q, axis));
      }
    }
    const NumericEquations n = e.at(state);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(output(n, fmt::format("l5_position_{}", k + 1)), T.translation()(k), 1e-13);
      for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(output(n, fmt::format("l5_axis_{}_{}", axis + 1, k + 1)), T.linear()(k, axis), 1e-13)
            << "axis " << axis + 1 << " component " << k + 1;
    }
  }
}

// a two-link arm whose second link's inertia is `inertial` (an <inertial> element)
std::string arm_with(const std::string& inertial) {
  return R"(<robot name="arm"><link name="base"/>
    <joint name="q1" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/></joint>
    <link name="upper"><inertial><origin xyz="0.2 0 0"/><mass value="1.5"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>
    <joint name="q2" type="revolute"><parent link="upper"/><child link="lower"/>
      <origin xyz="0.4 0 0" rpy="0.3 0 0"/><axis xyz="0 1 0"/></joint>
    <link name="lower">)" +
         inertial + R"(</link></robot>)";
}

TEST(UrdfModel, AnInertiaInTurnedAxesIsTurnedExactly) {
  const Eigen::Vector3d rpy(0.4, -0.9, 1.7);
  Eigen::Matrix3d J;
  J << 0.031, 0.002, -0.004, 0.002, 0.025, 0.003, -0.004, 0.003, 0.012;
  const std::string turned = fmt::format(R"(<inertial><origin xyz="0.1 0.02 -0.03" rpy="{} {} {}"/><mass value="0.8"/>
      <inertia ixx="{}" ixy="{}" ixz="{}" iyy="{}" iyz="{}" izz="{}"/></inertial>)",
                                         text(rpy(0)), text(rpy(1)), text(rpy(2)), text(J(0, 0)), text(J(0, 1)),
                                         text(J(0, 2)), text(J(1, 1)), text(J(1, 2)), text(J(2, 2)));
  // the same inertia in the link's axes: J_link = R J R^T, R taking the inertia axes' components
  // to the link's
  const Eigen::Matrix3d R = rpy_rotation(rpy);
  const Eigen::Matrix3d Jl = R * J * R.transpose();
  const std::string in_link_axes = fmt::format(R"(<inertial><origin xyz="0.1 0.02 -0.03"/><mass value="0.8"/>
      <inertia ixx="{}" ixy="{}" ixz="{}" iyy="{}" iyz="{}" izz="{}"/></inertial>)",
                                               text(Jl(0, 0)), text(Jl(0, 1)), text(Jl(0, 2)), text(Jl(1, 1)),
                                               text(Jl(1, 2)), text(Jl(2, 2)));
  const Evaluated a(arm_with(turned)), b(arm_with(in_link_axes));
  // and one whose axes are dropped, as importers that lose <inertial><origin rpy> do: different
  const Evaluated dropped(arm_with(fmt::format(R"(<inertial><origin xyz="0.1 0.02 -0.03"/><mass value="0.8"/>
      <inertia ixx="{}" ixy="{}" ixz="{}" iyy="{}" iyz="{}" izz="{}"/></inertial>)",
                                               text(J(0, 0)), text(J(0, 1)), text(J(0, 2)), text(J(1, 1)),
                                               text(J(1, 2)), text(J(2, 2)))));
  for (const auto& [q1, q2] : {std::pair{0.3, -0.8}, std::pair{-2.0, 1.1}}) {
    const NamedValues state{{"q1", q1}, {"q2", q2}, {"q1_dot", 0.5}, {"q2_dot", -1.2}};
    const NumericEquations na = a.at(state), nb = b.at(state), nd = dropped.at(state);
    EXPECT_LT((na.mass_matrix - nb.mass_matrix).norm(), 1e-14 * nb.mass_matrix.norm());
    EXPECT_LT((na.forcing - nb.forcing).norm(), 1e-13 * (1 + nb.forcing.norm()));
    EXPECT_GT((nd.mass_matrix - nb.mass_matrix).norm(), 1e-4 * nb.mass_matrix.norm());
  }
}

TEST(UrdfModel, AFixedJointMakesOneRigidBodyWithItsParent) {
  // link "upper" carries "tool" on a fixed joint; the single link "merged" has their combined
  // mass, mass centre and inertia (parallel-axis theorem), all resolved in upper's axes
  const double m1 = 1.5, m2 = 0.7;
  const Eigen::Vector3d c1(0.2, 0.01, 0), xyz(0.35, -0.05, 0.02), rpy(0.5, -0.2, 0.9), c2_tool(0.03, 0.0, 0.04);
  Eigen::Matrix3d J1, J2;
  J1 << 0.002, 0.0001, 0, 0.0001, 0.02, 0, 0, 0, 0.021;
  J2 << 0.004, 0, 0.0005, 0, 0.003, 0, 0.0005, 0, 0.005;
  const Eigen::Matrix3d R = rpy_rotation(rpy);
  const Eigen::Vector3d c2 = xyz + R * c2_tool;
  const double m = m1 + m2;
  const Eigen::Vector3d c = (m1 * c1 + m2 * c2) / m;
  const auto shift = [](double mass, const Eigen::Vector3d& d) {
    return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  };
  const Eigen::Matrix3d J = J1 + shift(m1, c1 - c) + R * J2 * R.transpose() + shift(m2, c2 - c);
  const auto inertial = [](double mass, const Eigen::Vector3d& at, const Eigen::Matrix3d& I) {
    return fmt::format(R"(<inertial><origin xyz="{} {} {}"/><mass value="{}"/>
        <inertia ixx="{}" ixy="{}" ixz="{}" iyy="{}" iyz="{}" izz="{}"/></inertial>)",
                       text(at(0)), text(at(1)), text(at(2)), text(mass), text(I(0, 0)), text(I(0, 1)), text(I(0, 2)),
                       text(I(1, 1)), text(I(1, 2)), text(I(2, 2)));
  };
  const std::string head = R"(<robot name="r"><link name="base"/>
    <joint name="q1" type="revolute"><parent link="base"/><child link="upper"/>
      <origin xyz="0 0 0.3" rpy="0.2 0 0"/><axis xyz="0 1 0"/></joint>)";
  const std::string two_links =
      head + "<link name=\"upper\">" + inertial(m1, c1, J1) + "</link>" +
      fmt::format(R"(<joint name="weld" type="fixed"><parent link="upper"/><child link="tool"/>
        <origin xyz="{} {} {}" rpy="{} {} {}"/><axis xyz="0 0 0"/></joint>)",
                  text(xyz(0)), text(xyz(1)), text(xyz(2)), text(rpy(0)), text(rpy(1)), text(rpy(2))) +
      "<link name=\"tool\">" + inertial(m2, c2_tool, J2) + "</link></robot>";
  const std::string one_link = head + "<link name=\"upper\">" + inertial(m, c, J) + "</link></robot>";
  const Evaluated welded(two_links), merged(one_link);
  for (const double q : {0.0, 0.7, -2.2}) {
    const NamedValues state{{"q1", q}, {"q1_dot", 1.3}};
    const NumericEquations a = welded.at(state), b = merged.at(state);
    EXPECT_NEAR(a.mass_matrix(0, 0), b.mass_matrix(0, 0), 1e-14 * b.mass_matrix(0, 0));
    EXPECT_NEAR(a.forcing(0), b.forcing(0), 1e-13 * (1 + std::abs(b.forcing(0))));
    EXPECT_NEAR(a.potential_energy, b.potential_energy, 1e-13);
  }
}

TEST(UrdfModel, DampingIsMinusCTimesTheRateAndMimicIsItsConstraint) {
  const std::string urdf = R"(<robot name="gripper"><link name="base"/>
    <joint name="finger1" type="prismatic"><parent link="base"/><child link="left"/><axis xyz="0 1 0"/>
      <dynamics damping="0.3" friction="0.1"/></joint>
    <link name="left"><inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>
    <joint name="finger2" type="prismatic"><parent link="base"/><child link="right"/><axis xyz="0 -1 0"/>
      <mimic joint="finger1" multiplier="2" offset="-0.01"/></joint>
    <link name="right"><inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>
  </robot>)";
  const Evaluated e(urdf);
  ASSERT_EQ(e.model.system.variables().inputs().size(), 1u);  // the mimic joint is driven, not actuated
  const NumericEquations n = e.at({{"finger1", 0.02}, {"finger2", 0.05}, {"finger1_dot", 0.4}, {"finger1_force", 1.5}});
  EXPECT_NEAR(n.forcing(0), -0.3 * 0.4 + 1.5, 1e-15);  // horizontal: no gravity along the fingers
  EXPECT_NEAR(n.forcing(1), 0, 1e-15);
  ASSERT_EQ(n.holonomic_residuals.size(), 1);
  // finger2 = 2 finger1 - 0.01 as the constraint finger2 - (2 finger1 - 0.01) = 0
  EXPECT_NEAR(n.holonomic_residuals(0), 0.05 - (2 * 0.02 - 0.01), 1e-15);
  EXPECT_NEAR(n.constraint_jacobian(0, 0), -2, 1e-15);
  EXPECT_NEAR(n.constraint_jacobian(0, 1), 1, 1e-15);
}

TEST(UrdfModel, AFloatingJointIsAFreeBodyAndAPlanarJointMovesInItsPlane) {
  const std::string urdf = R"(<robot name="free"><link name="world"/>
    <joint name="base" type="floating"><parent link="world"/><child link="body"/></joint>
    <link name="body"><inertial><mass value="3"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.25"/></inertial></link>
    <joint name="slider" type="planar"><parent link="world"/><child link="puck"/><origin xyz="0 0 0.5"/>
      <axis xyz="0 0 1"/></joint>
    <link name="puck"><inertial><mass value="0.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial></link>
  </robot>)";
  const Evaluated e(urdf);
  const NumericEquations n = e.at({});  // every angle 0: the translations and the angles decouple
  ASSERT_EQ(n.mass_matrix.rows(), 9);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(n.mass_matrix(i, i), 3, 1e-15);
  // yaw, pitch, roll at zero turn about z, y, x: izz, iyy, ixx
  EXPECT_NEAR(n.mass_matrix(3, 3), 0.25, 1e-15);
  EXPECT_NEAR(n.mass_matrix(4, 4), 0.2, 1e-15);
  EXPECT_NEAR(n.mass_matrix(5, 5), 0.1, 1e-15);
  EXPECT_NEAR(n.forcing(2), -3 * 9.81, 1e-13);  // gravity on z
  // the puck: x, y in the plane, theta about z
  EXPECT_NEAR(n.mass_matrix(6, 6), 0.5, 1e-15);
  EXPECT_NEAR(n.mass_matrix(7, 7), 0.5, 1e-15);
  EXPECT_NEAR(n.mass_matrix(8, 8), 0.02, 1e-15);
  EXPECT_NEAR(n.forcing(6), 0, 1e-15);
  EXPECT_NEAR(n.forcing(7), 0, 1e-15);
}

std::string written(const std::string& urdf, const urdf::ImportOptions& options = {}) {
  return urdf::write_model(urdf::read_robot(urdf, "robot.urdf"), options).text;
}

TEST(UrdfModel, AnglesThatAreTheDoubleNearestAMultipleOfQuarterPiAreWrittenAsThatMultiple) {
  const std::string urdf = R"(<robot name="r"><link name="base"/>
    <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
      <origin rpy="0 1.5707963267948966 0"/><axis xyz="0 0 1"/></joint>
    <link name="l1"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
    <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
      <origin rpy="-3.141592653589793 0.7853981633974483 1.57079632679"/><axis xyz="0 0 1"/></joint>
    <link name="l2"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  </robot>)";
  const std::string text = written(urdf);
  EXPECT_THAT(text, ::testing::HasSubstr("frame j1_frame = rotate(base, 2, pi/2)"));
  // 1.57079632679 is 4.9e-12 short of pi/2: kept as written
  EXPECT_THAT(text, ::testing::HasSubstr("frame j2_frame = euler(l1, 321, 1.57079632679, pi/4, -pi)"));
}

TEST(UrdfModel, InertialEntriesGivenAsZeroAreWrittenZeroAndTheOthersAreParameters) {
  const std::string text = written(R"(<robot name="r"><link name="base"/>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
    <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0.002" iyy="0.03" iyz="0" izz="0.02"/></inertial></link></robot>)");
  EXPECT_THAT(text, ::testing::HasSubstr("parameter arm_com_x = 0.3"));
  EXPECT_THAT(text, ::testing::Not(::testing::HasSubstr("parameter arm_com_y")));
  EXPECT_THAT(text, ::testing::HasSubstr("parameter arm_ixz = 0.002"));
  EXPECT_THAT(text, ::testing::HasSubstr("# 0 in the file, and written 0: com_y, com_z, ixy, iyz"));
  EXPECT_THAT(text, ::testing::HasSubstr("inertia = [[arm_ixx, 0, arm_ixz],"));
}

TEST(UrdfModel, LinksWeldedToTheGroundAreNoBodiesAndTheirInertiaIsNotChecked) {
  // the base's inertia is no body's (its largest moment exceeds the sum of the others), as
  // published robots' fixed bases often have: it never enters the equations
  const std::string urdf = R"(<robot name="r"><link name="world"/>
    <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>
    <link name="base"><inertial><mass value="4"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1"/></inertial></link>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
    <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial></link></robot>)";
  const std::string text = written(urdf);
  EXPECT_THAT(text, ::testing::HasSubstr("# its mass (4) is fixed to the ground: it does not enter the equations"));
  EXPECT_THAT(text, ::testing::Not(::testing::HasSubstr("base_body")));
  const Evaluated e(urdf);
  EXPECT_NEAR(e.at({}).mass_matrix(0, 0), 0.02 + 2 * 0.09, 1e-15);
}

TEST(UrdfModel, AJointThatRepeatsTheMotionOfTheOneBeforeItIsRefusedAsASingularMassMatrix) {
  // two revolute joints about one axis through one point, the only mass beyond the second:
  // both turn the same body the same way, so M = [[I, I], [I, I]] at every state
  const std::string urdf = R"(<robot name="r"><link name="base"/>
    <joint name="j1" type="revolute"><parent link="base"/><child link="middle"/><axis xyz="0 0 1"/></joint>
    <link name="middle"/>
    <joint name="j2" type="revolute"><parent link="middle"/><child link="arm"/><axis xyz="0 0 1"/></joint>
    <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial></link></robot>)";
  try {
    written(urdf);
    ADD_FAILURE() << "accepted";
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().line, 4) << e.what();
    EXPECT_THAT(e.message(), ::testing::HasSubstr("joint 'j2' (revolute): the mass matrix would be singular"));
  }
  // the same with the second axis turned away: regular
  std::string turned = urdf;
  const std::string axis = "<axis xyz=\"0 0 1\"/>";
  turned.replace(turned.rfind(axis), axis.size(), "<axis xyz=\"0 1 0\"/>");
  EXPECT_NO_THROW(written(turned));
}

TEST(UrdfModel, AMimicOnAFixedJointAndAVisualOfAnotherGeometryAreKeptAsComments) {
  const std::string text = written(R"(<robot name="r"><link name="base"/>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
    <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial>
      <visual><geometry><capsule radius="0.1" length="0.3"/></geometry></visual></link>
    <joint name="pad" type="fixed"><parent link="arm"/><child link="tip"/><mimic joint="j"/></joint>
    <link name="tip"/></robot>)");
  EXPECT_THAT(text, ::testing::HasSubstr("# visual 1: <capsule> (not drawn"));
  EXPECT_THAT(text, ::testing::HasSubstr("#   mimics 'j' (multiplier 1, offset 0): a fixed joint moves nothing"));
  EXPECT_THAT(text, ::testing::Not(::testing::HasSubstr("constraint")));
}

// a two-link arm whose links are drawn by meshes: a package:// name, a relative one with a
// scale (a mirror), one a model file cannot quote, one flattened by a zero scale
const std::string meshed_arm = R"(<robot name="r"><link name="base"/>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
    <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial>
      <visual><geometry><mesh filename="package://arm_description/meshes/arm.stl"/></geometry></visual>
      <visual><origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/>
        <geometry><mesh filename="meshes/cover.STL" scale="0.001 -0.001 0.001"/></geometry></visual>
      <visual><geometry><mesh filename="say&quot;hi.stl"/></geometry></visual>
      <visual><geometry><mesh filename="flat.stl" scale="1 0 1"/></geometry></visual></link></robot>)";

TEST(UrdfModel, MeshVisualsBecomeMeshShapesPlacedByTheirOrigins) {
  const Model model = imported(meshed_arm);
  ASSERT_EQ(model.shapes.size(), 2u);
  const VisualShape& first = model.shapes[0];
  EXPECT_EQ(first.kind, VisualShape::Kind::mesh);
  EXPECT_EQ(first.name, "arm_visual1");
  EXPECT_EQ(first.body, "arm_body");
  EXPECT_EQ(first.file, "package://arm_description/meshes/arm.stl");
  EXPECT_EQ(model.system.frame(*first.frame).name, "arm");
  const VisualShape& cover = model.shapes[1];
  EXPECT_EQ(cover.file, "meshes/cover.STL");  // as written: the model is read where the URDF is
  EXPECT_EQ(model.system.point(cover.at).name, "arm_visual2_at");
  EXPECT_EQ(model.system.frame(*cover.frame).name, "arm_visual2_frame");
  const double scale[3] = {0.001, -0.001, 0.001};
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_DOUBLE_EQ(GiNaC::ex_to<GiNaC::numeric>(cover.scale[k].evalf()).to_double(), scale[k]);
  const std::string text = written(meshed_arm);
  EXPECT_THAT(text, ::testing::HasSubstr("shape arm_visual1 = mesh(body = arm_body, file = "
                                         "\"package://arm_description/meshes/arm.stl\", at = arm_origin, frame = arm)"));
  EXPECT_THAT(text, ::testing::HasSubstr("shape arm_visual2 = mesh(body = arm_body, file = \"meshes/cover.STL\", "
                                         "scale = [0.001, -0.001, 0.001], at = arm_visual2_at, frame = arm_visual2_frame)"));
  EXPECT_THAT(text, ::testing::HasSubstr("# visual 3: mesh 'say?hi.stl' (not drawn: its name has a quote"));
  EXPECT_THAT(text, ::testing::HasSubstr("# visual 4: mesh 'flat.stl' (not drawn: a scale of 0 flattens it)"));
}

TEST(UrdfModel, ALinkWhoseVisualsAreAllMeshesThatAreNotSTLIsDrawnByItsCollisionGeometry) {
  const std::string text = written(R"(<robot name="r"><link name="base"/>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
    <link name="arm"><inertial><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial>
      <visual><geometry><mesh filename="arm.dae"/></geometry></visual>
      <collision><geometry><box/></geometry></collision>
      <collision><origin xyz="0 0 0.1"/><geometry><mesh filename="arm.STL"/></geometry></collision></link>
    <joint name="k" type="revolute"><parent link="arm"/><child link="hand"/><axis xyz="0 0 1"/></joint>
    <link name="hand"><inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial>
      <visual><geometry><mesh filename="hand.dae"/></geometry></visual>
      <visual><geometry><sphere radius="0.05"/></geometry></visual>
      <collision><geometry><mesh filename="hand.stl"/></geometry></collision></link></robot>)");
  // a collision geometry this reader would refuse as a visual (a box without a size) is left out
  EXPECT_THAT(text, ::testing::HasSubstr("# visual 1: mesh 'arm.dae' (not STL, which is all the animation draws: the "
                                         "link is drawn by its collision geometry instead)"));
  EXPECT_THAT(text, ::testing::HasSubstr("point arm_collision1_at = arm_origin + [0, 0, 0.1] in arm\n"
                                         "shape arm_collision1 = mesh(body = arm_body, file = \"arm.STL\", at = "
                                         "arm_collision1_at, frame = arm)"));
  // a link with one visual that can be drawn keeps its visuals
  EXPECT_THAT(text, ::testing::HasSubstr("shape hand_visual2 = sphere("));
  EXPECT_THAT(text, ::testing::HasSubstr("shape hand_visual1 = mesh(body = hand_body, file = \"hand.dae\""));
  EXPECT_THAT(text, ::testing::Not(::testing::HasSubstr("hand.stl")));
}

TEST(UrdfModel, AMeshNamedRelativeToTheURDFIsNamedRelativeToWhereTheModelIsWritten) {
  urdf::ImportOptions options;
  options.model_directory = "/robots/out/models";
  const urdf::ImportResult result = urdf::write_model(urdf::read_robot(meshed_arm, "/robots/arm/urdf/arm.urdf"), options);
  EXPECT_THAT(result.text, ::testing::HasSubstr("file = \"../../arm/urdf/meshes/cover.STL\""));
  EXPECT_THAT(result.text, ::testing::HasSubstr("file = \"package://arm_description/meshes/arm.stl\""));
  options.model_directory = "/robots/arm/urdf";
  EXPECT_THAT(urdf::write_model(urdf::read_robot(meshed_arm, "/robots/arm/urdf/arm.urdf"), options).text,
              ::testing::HasSubstr("file = \"meshes/cover.STL\""));
}

TEST(UrdfModel, AFloatingBaseMakesTheRootAFreeBodyCarryingTheRest) {
  const std::string urdf = R"(<robot name="quad">
    <link name="base"><inertial><mass value="1.5"/><inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.04"/></inertial></link>
    <joint name="gimbal" type="revolute"><parent link="base"/><child link="camera"/><origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/></joint>
    <link name="camera"><inertial><origin xyz="0.02 0 0"/><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  </robot>)";
  urdf::ImportOptions floating;
  floating.floating_base = true;
  const Model model = parse_model(written(urdf, floating), "robot.urdf (as imported)");
  const ModelEquations eom = derive_equations(model);
  ASSERT_EQ(model.system.variables().coordinate_count(), 7u);
  const NumericEquations n = evaluate_equations(model, eom, {{"gimbal", 0.4}, {"base_yaw", 0.3}});
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(n.mass_matrix(i, i), 1.6, 1e-15);  // both bodies translate with the base
  EXPECT_NEAR(n.forcing(2), -1.6 * 9.81, 1e-13);                             // and both fall
  // fixed to the ground instead, the base's mass enters nothing
  const Evaluated fixed(urdf);
  EXPECT_EQ(fixed.model.system.variables().coordinate_count(), 1u);
}

TEST(UrdfModel, FixMasslessJointsMakesFixedTheJointsThatMoveNoMassAndSaysWhich) {
  // a gripper published without the fingers' inertia: refused, or the fingers welded
  const std::string urdf = R"(<robot name="g"><link name="base"/>
    <joint name="wrist" type="revolute"><parent link="base"/><child link="hand"/><axis xyz="0 0 1"/></joint>
    <link name="hand"><inertial><origin xyz="0.05 0 0"/><mass value="0.5"/>
      <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
    <joint name="finger" type="prismatic"><parent link="hand"/><child link="pad"/><axis xyz="0 1 0"/></joint>
    <link name="pad"/>
    <joint name="finger_tip" type="revolute"><parent link="pad"/><child link="tip"/><axis xyz="1 0 0"/></joint>
    <link name="tip"/></robot>)";
  EXPECT_THROW(written(urdf), SourceError);
  urdf::ImportOptions fix;
  fix.fix_massless_joints = true;
  const urdf::ImportResult result = urdf::write_model(urdf::read_robot(urdf, "robot.urdf"), fix);
  ASSERT_EQ(result.locked.size(), 2u);
  EXPECT_THAT(result.locked[0], ::testing::HasSubstr("joint 'finger' (prismatic) moves only links without mass"));
  EXPECT_THAT(result.locked[1], ::testing::HasSubstr("joint 'finger_tip' (revolute)"));
  const Model model = parse_model(result.text, "robot.urdf (as imported)");
  ASSERT_EQ(model.system.variables().coordinate_count(), 1u);
  const ModelEquations eom = derive_equations(model);
  EXPECT_NEAR(evaluate_equations(model, eom, {}).mass_matrix(0, 0), 1e-3 + 0.5 * 0.0025, 1e-15);
}

TEST(UrdfModel, ShippedRobotsImportIntoModelsWithTheirJointsAsCoordinates) {
  struct Expected {
    const char* file;
    std::size_t coordinates, inputs, constraints;
  };
  for (const Expected& r : {Expected{"ur5", 6, 6, 0}, Expected{"iiwa14", 7, 7, 0}, Expected{"panda", 9, 8, 1},
                            Expected{"two_arm_torso", 8, 8, 0}}) {
    const Model m = load_model((testing::source_dir() / "models" / "robots" / (std::string(r.file) + ".urdf")).string());
    EXPECT_EQ(m.system.variables().coordinate_count(), r.coordinates) << r.file;
    EXPECT_EQ(m.system.variables().inputs().size(), r.inputs) << r.file;
    EXPECT_EQ(m.system.constraints().size(), r.constraints) << r.file;
  }
}

}  // namespace
}  // namespace eomgen
