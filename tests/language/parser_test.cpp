// The model language read into a Model: declarations, loops, frames and points in any order,
// every rotation kind and vector expression checked against the C++ API that builds the same
// thing, outputs, constraints, and reproducible results.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "support/model_lookup.hpp"
#include "support/symbolic_checks.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::numeric;
using testing::equal_after_simplification;
using testing::symbol_named;

Model parse(const std::string& text, const std::map<std::string, double>& overrides = {}) {
  return parse_model(text, "test.eom", overrides);
}

FrameId frame(const Model& m, const std::string& name) {
  const auto f = m.system.find_frame(name);
  if (!f) ADD_FAILURE() << "no frame '" << name << "'";
  return f.value_or(m.system.inertial_frame());
}

PointId point(const Model& m, const std::string& name) {
  const auto p = m.system.find_point(name);
  if (!p) ADD_FAILURE() << "no point '" << name << "'";
  return p.value_or(m.system.origin());
}

const Output& output(const Model& m, const std::string& name) {
  const Output* o = testing::find_output(m, name);
  if (!o) ADD_FAILURE() << "no output '" << name << "'";
  return o ? *o : m.outputs.at(0);
}

matrix column(const ex& x, const ex& y, const ex& z) { return matrix(3, 1, GiNaC::lst{x, y, z}); }

void expect_output(const Model& m, const std::string& name, const matrix& expected) {
  const Output& o = output(m, name);
  ASSERT_EQ(o.components.size(), expected.rows()) << name;
  matrix actual(expected.rows(), 1);
  for (unsigned i = 0; i < actual.rows(); ++i) actual(i, 0) = o.components[i];
  EXPECT_TRUE(equal_after_simplification(actual, expected));
}

TEST(Parser, ModelNameDescriptionAndParametersWithUnits) {
  const Model m = parse(R"(model demo "A demo"
parameter g = 9.81 [m/s^2]
parameter mass = 2 [ kg ]
parameter c = 0.5 [m]
coordinate q
frame b = rotate(a, 3, q)
point p = w + c*b.1
particle bob(mass = mass, at = p)
)");
  EXPECT_EQ(m.name, "demo");
  EXPECT_EQ(m.description, "A demo");
  const auto& parameters = m.system.variables().parameters();
  ASSERT_EQ(parameters.size(), 3u);
  EXPECT_EQ(parameters[0].name, "g");
  EXPECT_EQ(parameters[0].unit, "m/s^2");
  EXPECT_DOUBLE_EQ(parameters[0].default_value, 9.81);
  EXPECT_EQ(parameters[1].unit, "kg");
  EXPECT_EQ(parameters[2].unit, "m");
  EXPECT_DOUBLE_EQ(parameters[2].default_value, 0.5);
  EXPECT_EQ(parse_model("coordinate q\npoint p = w + q*a.1\nparticle m(mass = 1, at = p)\n", "dir/slider.eom").name,
            "slider");
}

TEST(Parser, ParameterDefaultsFromConstExpressions) {
  const Model m = parse(R"(const n = 4
const half = 1/2
parameter l = 2/n + half
parameter s = sqrt(2)*pi
parameter k = n^2 - 1
coordinate q
point p = w + l*q*a.1
particle bob(mass = k, at = p)
)");
  const auto& parameters = m.system.variables().parameters();
  ASSERT_EQ(parameters.size(), 3u);
  EXPECT_DOUBLE_EQ(parameters[0].default_value, 1.0);
  EXPECT_DOUBLE_EQ(parameters[1].default_value, std::sqrt(2.0) * M_PI);
  EXPECT_DOUBLE_EQ(parameters[2].default_value, 15.0);
  EXPECT_DOUBLE_EQ(m.constants.at("n"), 4.0);
}

TEST(Parser, DecimalsStayExact) {
  const Model m = parse(R"(coordinate q
point p = w + q*a.1
particle bob(mass = 1, at = p)
output o = 0.1 + 2.5E+2 + 1e-3
output h = 0.1*q
)");
  EXPECT_TRUE(output(m, "o").components.at(0).is_equal(numeric(250101, 1000))) << output(m, "o").components.at(0);
  EXPECT_TRUE(output(m, "h").components.at(0).is_equal(numeric(1, 10) * symbol_named(m.system, "q")));
}

// published robot descriptions write ".649262481663582": a number, exact, where a '.' and a
// digit do not follow a name (there they pick a basis vector, "b.2")
TEST(Parser, NumbersMayStartWithTheirDecimalPoint) {
  const Model m = parse(R"(coordinate q
frame b = rotate(a, 3, q)
point p = w + .5*q*b.2 - (.25)*a.1
particle bob(mass = .649262481663582, at = p)
output o = -.125 + .5e1
)");
  EXPECT_TRUE(output(m, "o").components.at(0).is_equal(numeric(39, 8))) << output(m, "o").components.at(0);
  EXPECT_TRUE(m.system.particles().at(0).mass.is_equal(numeric(649262481663582, 1000000000000000)));
}

TEST(Parser, FramesAndPointsMayBeUsedBeforeTheirDefinition) {
  const Model m = parse(R"(coordinate q1, q2
point p2 = p1 + c.1      # c and p1 come below
particle bob(mass = 1, at = p2)
point p1 = w + b.1
frame c = rotate(b, 3, q2)
frame b = rotate(a, 3, q1)
)");
  const MechanicalSystem& s = m.system;
  EXPECT_EQ(*s.frame(frame(m, "c")).parent, frame(m, "b"));
  EXPECT_EQ(*s.point(point(m, "p2")).parent, point(m, "p1"));
  EXPECT_TRUE(equal_after_simplification(
      resolve(s, position(s, point(m, "p2"), s.origin()), s.inertial_frame()),
      resolve(s, Vector(frame(m, "b"), 1, 0, 0) + Vector(frame(m, "c"), 1, 0, 0), s.inertial_frame())));
}

TEST(Parser, AliasesOfFramesAndPoints) {
  const Model m = parse(R"(coordinate q
frame b0 = a
point o0 = w
frame b1 = rotate(b0, 3, q)
point o1 = o0 + b1.1
particle bob(mass = 1, at = o1)
output r = position(o0)
)");
  EXPECT_EQ(*m.system.frame(frame(m, "b1")).parent, m.system.inertial_frame());
  EXPECT_EQ(*m.system.point(point(m, "o1")).parent, m.system.origin());
  expect_output(m, "r", column(0, 0, 0));
}

const char* const chain = R"(const n = 3
parameter l = 1
parameter m = 1
parameter eps = 0.01
frame b0 = a
point o0 = w
for i in 1..n
  coordinate q{i}
  frame b{i} = rotate(b{i-1}, 3, q{i})
  point c{i} = o{i-1} + l/2*b{i}.1
  point o{i} = o{i-1} + l*b{i}.1
  body rod{i}(mass = m, centre = c{i}, frame = b{i}, inertia = diag(eps, m*l^2/12, m*l^2/12))
end
)";

TEST(Parser, LoopsWithInterpolatedNames) {
  const Model m = parse(chain);
  const auto& coordinates = m.system.variables().coordinates();
  ASSERT_EQ(coordinates.size(), 3u);
  for (int i = 1; i <= 3; ++i) {
    EXPECT_EQ(coordinates[i - 1].name, "q" + std::to_string(i));
    EXPECT_EQ(m.system.rigid_bodies()[i - 1].name, "rod" + std::to_string(i));
    EXPECT_EQ(m.coordinate_locations[i - 1].line, 8);
    EXPECT_EQ(m.coordinate_locations[i - 1].column, 14);
  }
  EXPECT_EQ(*m.system.frame(frame(m, "b3")).parent, frame(m, "b2"));
  EXPECT_EQ(*m.system.point(point(m, "c3")).parent, point(m, "o2"));
}

TEST(Parser, NestedLoopsMayUseTheOuterVariable) {
  const Model m = parse(R"(coordinate q
point p = w + q*a.1
particle bob(mass = 1, at = p)
for i in 1..2
  for j in i..3
    parameter k{i}{j} = 10*i + j
  end
end
)");
  std::string names;
  for (const Parameter& p : m.system.variables().parameters()) {
    names += p.name + " ";
    EXPECT_DOUBLE_EQ(p.default_value, std::stod(p.name.substr(1)));
  }
  EXPECT_EQ(names, "k11 k12 k13 k22 k23 ");
}

TEST(Parser, OverrideOfConstN) {
  const Model m = parse(chain, {{"n", 5}});
  EXPECT_EQ(m.system.variables().coordinate_count(), 5u);
  EXPECT_EQ(m.system.rigid_bodies().back().name, "rod5");
  EXPECT_DOUBLE_EQ(m.constants.at("n"), 5.0);
}

TEST(Parser, EveryRotationKindGivesTheDcmOfTheApi) {
  const Model m = parse(R"(coordinate q1, q2, q3
frame r2 = rotate(a, 2, q1)
frame e313 = euler(a, 313, q1, q2, q3)
frame e321 = euler(a, 321, q1, q2, q3)
frame aa = axis_angle(a, [0.6, 0, 0.8], q1)
frame qt = quaternion(a, [q1, q2, q3], sqrt(1 - q1^2 - q2^2 - q3^2))
frame rg = rodrigues(a, [q1, q2, q3])
frame mr = mrp(a, [q1, q2, q3])
frame dc = dcm(a, [[cos(q1), sin(q1), 0], [-sin(q1), cos(q1), 0], [0, 0, 1]])
particle bob(mass = 1, at = w)
)");
  const ex q1 = symbol_named(m.system, "q1"), q2 = symbol_named(m.system, "q2"), q3 = symbol_named(m.system, "q3");
  const matrix p = column(q1, q2, q3);
  const std::map<std::string, Rotation> expected = {
      {"r2", Rotation::principal(2, q1)},
      {"e313", Rotation::euler(EulerSequence::parse("313"), q1, q2, q3)},
      {"e321", Rotation::euler(EulerSequence::parse("321"), q1, q2, q3)},
      {"aa", Rotation::axis_angle(column(numeric(3, 5), 0, numeric(4, 5)), q1)},
      {"qt", Rotation::quaternion(p, GiNaC::sqrt(1 - q1 * q1 - q2 * q2 - q3 * q3))},
      {"rg", Rotation::rodrigues(p)},
      {"mr", Rotation::modified_rodrigues(p)},
      {"dc", Rotation::explicit_matrix(principal_rotation(3, q1))}};
  for (const auto& [name, rotation] : expected) {
    SCOPED_TRACE(name);
    const Frame& f = m.system.frame(frame(m, name));
    EXPECT_EQ(f.rotation.kind(), rotation.kind());
    EXPECT_TRUE(equal_after_simplification(f.rotation.dcm(), rotation.dcm()));
    EXPECT_TRUE(equal_after_simplification(dcm(m.system, frame(m, name), m.system.inertial_frame()), rotation.dcm()));
  }
}

TEST(Parser, VectorExpressionsMatchTheKinematicsFunctions) {
  const Model m = parse(R"(parameter l = 2
coordinate q1, q2
frame b = rotate(a, 3, q1)
frame c = rotate(b, 1, q2)
point p = w + l*b.1
point s = p + [1, 2, 3] in c
particle bob(mass = 1, at = s)
output e = -c.2 / 2
output r = [1, 2, 3] in c
output x = cross(b.1, c.2)
output d = dot(position(s), c.3)
output n = norm(position(s, p))
output ps = position(s)
output pp = position(s, p)
output v = velocity(s)
output w1 = angular_velocity(c)
output w2 = angular_velocity(c, b)
)");
  const MechanicalSystem& sys = m.system;
  const FrameId a = sys.inertial_frame(), b = frame(m, "b"), c = frame(m, "c");
  const PointId p = point(m, "p"), s = point(m, "s");
  auto in_a = [&](const Vector& u) { return resolve(sys, u, a); };
  expect_output(m, "e", in_a(Vector(c, 0, ex(-1) / 2, 0)));
  expect_output(m, "r", in_a(Vector(c, 1, 2, 3)));
  expect_output(m, "x", in_a(cross(sys, Vector(b, 1, 0, 0), Vector(c, 0, 1, 0))));
  expect_output(m, "d", matrix(1, 1, GiNaC::lst{dot(sys, position(sys, s, sys.origin()), Vector(c, 0, 0, 1))}));
  expect_output(m, "n", matrix(1, 1, GiNaC::lst{GiNaC::sqrt(ex(14))}));
  expect_output(m, "ps", in_a(position(sys, s, sys.origin())));
  expect_output(m, "pp", in_a(position(sys, s, p)));
  expect_output(m, "v", in_a(velocity(sys, s)));
  expect_output(m, "w1", in_a(angular_velocity(sys, c, a)));
  expect_output(m, "w2", in_a(angular_velocity(sys, c, b)));
}

TEST(Parser, ScalarAndVectorOutputsWithLabels) {
  const Model m = parse(R"(coordinate q
frame b = rotate(a, 3, q)
point p = w + 2*b.1
particle bob(mass = 1, at = p)
output height = dot(position(p), a.2)
output vb = velocity(p) in b
output va = velocity(p)
)");
  ASSERT_EQ(m.outputs.size(), 3u);
  EXPECT_EQ(m.outputs[0].labels, std::vector<std::string>{"height"});
  EXPECT_EQ(m.outputs[0].location.line, 5);
  EXPECT_EQ(m.outputs[0].location.column, 8);
  EXPECT_EQ(m.outputs[1].labels, (std::vector<std::string>{"vb_1", "vb_2", "vb_3"}));
  const ex qd = symbol_named(m.system, "q_dot");
  expect_output(m, "vb", column(0, 2 * qd, 0));  // resolved in b
  expect_output(m, "va", resolve(m.system, velocity(m.system, point(m, "p")), m.system.inertial_frame()));
  expect_output(m, "height", matrix(1, 1, GiNaC::lst{2 * GiNaC::sin(symbol_named(m.system, "q"))}));
}

TEST(Parser, ConstraintsAreHolonomicWithoutRatesAndNonholonomicWithThem) {
  const Model m = parse(R"(coordinate x, y, z
point p = w + x*a.1 + y*a.2 + z*a.3
particle bob(mass = 1, at = p)
constraint h: x^2 + y^2 = 1
constraint nh: x_dot = y*z_dot
)");
  const auto& constraints = m.system.constraints();
  ASSERT_EQ(constraints.size(), 2u);
  EXPECT_EQ(constraints[0].name, "h");
  EXPECT_EQ(constraints[0].kind, Constraint::Kind::holonomic);
  const ex x = symbol_named(m.system, "x"), y = symbol_named(m.system, "y");
  EXPECT_TRUE((constraints[0].expression - (x * x + y * y - 1)).expand().is_zero());
  EXPECT_EQ(constraints[1].kind, Constraint::Kind::nonholonomic);
  EXPECT_TRUE((constraints[1].expression - (symbol_named(m.system, "x_dot") - y * symbol_named(m.system, "z_dot")))
                  .expand()
                  .is_zero());
  ASSERT_EQ(m.constraint_locations.size(), 2u);
  EXPECT_EQ(m.constraint_locations[1].line, 5);
  EXPECT_EQ(m.constraint_locations[1].column, 12);
}

TEST(Parser, IndependentSpeedsAreCoordinateIndicesInTheOrderGivenWhereverTheStatementStands) {
  // declared before the coordinates it names (statement order does not matter)
  const std::string knife_edge = R"(coordinate x, y, theta
frame b = rotate(a, 3, theta)
point c = w + x*a.1 + y*a.2
body blade(mass = 1, centre = c, frame = b, inertia = diag(1, 1, 1))
constraint no_side_slip: dot(velocity(c), b.2) = 0
)";
  const Model m = parse("independent theta, x\n" + knife_edge);
  EXPECT_EQ(m.independent_speeds, (std::vector<std::size_t>{2, 0}));
  EXPECT_TRUE(parse(knife_edge).independent_speeds.empty());
}

TEST(Parser, IndependentSpeedsTakeInterpolatedNamesInALoopThatRunsOnce) {
  // the last two links of the chain free, the first tied to the second: q1 = q2
  const Model m = parse(std::string(chain) + "constraint tie: q1 = q2\nfor i in n..n\n  independent q{i-1}, q{i}\nend\n");
  EXPECT_EQ(m.independent_speeds, (std::vector<std::size_t>{1, 2}));
}

TEST(Parser, RollWithANormalGivesTwoTangentialConstraints) {
  // a ball on the plane z = 0; the roll comes before its body (statement order does not matter)
  const Model m = parse(R"(parameter R = 0.5
coordinate x, y, phi, theta, psi
roll r(body = ball, contact = k, normal = a.3)
frame b = euler(a, 313, phi, theta, psi)
point c = w + [x, y, R] in a
point k = c - R*a.3
body ball(mass = 1, centre = c, frame = b, inertia = diag(0.1, 0.1, 0.1))
)");
  const MechanicalSystem& s = m.system;
  const auto& constraints = s.constraints();
  ASSERT_EQ(constraints.size(), 2u);
  EXPECT_EQ(constraints[0].name, "r_1");
  EXPECT_EQ(constraints[1].name, "r_2");
  const Vector slip = velocity(s, point(m, "c")) + cross(s, angular_velocity(s, frame(m, "b"), s.inertial_frame()),
                                                         position(s, point(m, "k"), point(m, "c")));
  // tangents a.3 x a.1 = a.2 and a.3 x a.2 = -a.1
  const ex along_2 = dot(s, slip, Vector(s.inertial_frame(), 0, 1, 0));
  const ex along_1 = dot(s, slip, Vector(s.inertial_frame(), 1, 0, 0));
  for (const Constraint& c : constraints) EXPECT_EQ(c.kind, Constraint::Kind::nonholonomic);
  EXPECT_TRUE(simplify_for_display(constraints[0].expression - along_2).is_zero()) << constraints[0].expression;
  EXPECT_TRUE(simplify_for_display(constraints[1].expression + along_1).is_zero()) << constraints[1].expression;
  ASSERT_EQ(m.constraint_locations.size(), 2u);
  EXPECT_EQ(m.constraint_locations[0].line, 3);
  EXPECT_EQ(m.constraint_locations[0].column, 6);
}

TEST(Parser, StatementsContinueWhileABracketIsOpenAndCommentsAreIgnored) {
  const Model m = parse(R"(# a pendulum written across lines
coordinate q   # the angle

frame b = rotate(a,
                 3,   # about a.3
                 q)
point c = w + [1,
               0, 0] in b
body rod(mass = 1,
         centre = c,
         frame = b,   # the body frame
         inertia = diag(0.01,
                        1/12, 1/12))
output z = 1 # after the last statement)");  // no final newline
  ASSERT_EQ(m.system.rigid_bodies().size(), 1u);
  EXPECT_TRUE(m.system.rigid_bodies()[0].inertia(2, 2).is_equal(numeric(1, 12)));
  EXPECT_EQ(m.coordinate_locations.at(0).line, 2);
  EXPECT_EQ(m.coordinate_locations.at(0).column, 12);
  EXPECT_EQ(output(m, "z").location.line, 14);
}

const char* const double_pendulum = R"(parameter m1 = 1.0 [kg]
parameter m2 = 1.0 [kg]
parameter l1 = 1.0 [m]
parameter l2 = 1.0 [m]
parameter g = 9.81 [m/s^2]
coordinate q1, q2
frame b = rotate(a, 3, q1)
frame c = rotate(b, 3, q2)
point p1 = w + l1*b.1
point p2 = p1 + l2*c.1
particle bob1(mass = m1, at = p1)
particle bob2(mass = m2, at = p2)
gravity = g*a.1
)";

std::string printed_mass_matrix(const Model& m) {
  const EquationsOfMotion eom = derive_equations(m.system);
  std::ostringstream out;
  out << eom.subexpressions.expand(eom.mass_matrix);
  return out.str();
}

TEST(Determinism, ParsingTwiceInOneProcessGivesTheSameMassMatrixUpToSymbolIdentity) {
  // GiNaC orders the terms of a sum by hash values made from each symbol's serial number (and,
  // in GiNaC 1.8, the address of its type name), so the second parse's fresh symbols print in
  // another order; with the first model's symbols substituted it must print the same
  const Model first = parse(double_pendulum), second = parse(double_pendulum);
  GiNaC::exmap same;
  const Variables &v1 = first.system.variables(), &v2 = second.system.variables();
  ASSERT_EQ(v2.coordinate_count(), v1.coordinate_count());
  ASSERT_EQ(v2.parameters().size(), v1.parameters().size());
  for (std::size_t k = 0; k < v1.coordinate_count(); ++k) {
    EXPECT_EQ(v2.coordinates()[k].name, v1.coordinates()[k].name);
    same[v2.coordinates()[k].q] = v1.coordinates()[k].q;
    same[v2.coordinates()[k].qd] = v1.coordinates()[k].qd;
  }
  for (std::size_t k = 0; k < v1.parameters().size(); ++k) {
    EXPECT_EQ(v2.parameters()[k].name, v1.parameters()[k].name);
    same[v2.parameters()[k].symbol] = v1.parameters()[k].symbol;
  }
  const EquationsOfMotion eom = derive_equations(second.system);
  std::ostringstream out;
  out << eom.subexpressions.expand(eom.mass_matrix).subs(same);
  EXPECT_EQ(out.str(), printed_mass_matrix(first));
}

}  // namespace
}  // namespace eomgen
