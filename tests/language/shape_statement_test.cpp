// The shape statement: each kind read into the VisualShape the animation draws (its frame, its
// points, its dimensions at the parameters' defaults, its axis in its frame), the defaults, each
// error at the argument that is wrong; and the contacts of roll and wheel, whose multipliers
// times their directions are the force of the surface on the body.
//
// Conventions (docs/conventions.md): M qdd = F + Xi^T lambda; C_ba of rotate(a, k, x) is Ck(x).
#include <Eigen/Dense>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

using testing::expect_model_error;
using ShapeKind = VisualShape::Kind;

double number(const GiNaC::ex& e, const Model& model) {
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(model.system.parameter_defaults()).evalf()).to_double();
}

std::string point_name(const Model& model, PointId p) { return model.system.point(p).name; }
std::string frame_name(const Model& model, FrameId f) { return model.system.frame(f).name; }

// a pendulum arm b turned by q about a.3, with its body, a bob particle and a frame c turned a
// constant quarter turn from b about b.3; lines 1-11, each case appends its shapes from line 12
const std::string arm =
    "parameter l = 0.5 [m]\n"
    "parameter m = 2 [kg]\n"
    "parameter d = l/10 [m]\n"
    "coordinate q\n"
    "frame b = rotate(a, 3, q)\n"
    "frame c = rotate(b, 3, pi/2)\n"
    "point mid = w + l/2*b.1\n"
    "point tip = w + l*b.1\n"
    "body link(mass = m, centre = mid, frame = b, inertia = m*l^2/12*diag(0, 1, 1))\n"
    "particle bob(mass = m, at = tip)\n"
    "point slab = w - l*a.2\n";

Model with_shapes(const std::string& shapes) { return parse_model(arm + shapes, "arm.eom"); }

// the error of one shape statement on line 12, after the arm
void expect(const std::string& shape, int column, const std::string& message) {
  expect_model_error(arm + shape + "\n", 12, column, message);
}

TEST(ShapeStatement, SphereOfABodyIsAtItsCentreInItsFrame) {
  const Model model = with_shapes("shape ball = sphere(body = link, radius = d)\n");
  ASSERT_EQ(model.shapes.size(), 1u);
  const VisualShape& s = model.shapes[0];
  EXPECT_EQ(s.kind, ShapeKind::sphere);
  EXPECT_EQ(s.name, "ball");
  EXPECT_EQ(s.body, "link");
  ASSERT_TRUE(s.frame);
  EXPECT_EQ(frame_name(model, *s.frame), "b");
  EXPECT_EQ(point_name(model, s.at), "mid");
  EXPECT_DOUBLE_EQ(number(s.radius, model), 0.05);
  EXPECT_EQ(s.location.line, 12);
  EXPECT_EQ(s.location.column, 7);
}

TEST(ShapeStatement, SphereOfAParticleHasNoFrameAndSitsAtTheParticle) {
  const Model model = with_shapes("shape ball = sphere(body = bob, radius = 0.1*l)\n");
  const VisualShape& s = model.shapes.at(0);
  EXPECT_EQ(s.body, "bob");
  EXPECT_FALSE(s.frame);
  EXPECT_EQ(point_name(model, s.at), "tip");
  EXPECT_DOUBLE_EQ(number(s.radius, model), 0.05);
}

TEST(ShapeStatement, BoxWithoutBodyIsAtItsPointInTheInertialFrameOrTheOneGiven) {
  const Model model = with_shapes("shape ground = box(size = [4*l, l/10, 2*l], at = slab)\n"
                                  "shape plate = box(size = [l, l, d], at = tip, frame = c)\n");
  ASSERT_EQ(model.shapes.size(), 2u);
  const VisualShape& ground = model.shapes[0];
  EXPECT_EQ(ground.kind, ShapeKind::box);
  EXPECT_EQ(ground.body, "");
  EXPECT_EQ(frame_name(model, *ground.frame), "a");
  EXPECT_EQ(point_name(model, ground.at), "slab");
  EXPECT_DOUBLE_EQ(number(ground.size[0], model), 2.0);
  EXPECT_DOUBLE_EQ(number(ground.size[1], model), 0.05);
  EXPECT_DOUBLE_EQ(number(ground.size[2], model), 1.0);
  EXPECT_EQ(frame_name(model, *model.shapes[1].frame), "c");
}

TEST(ShapeStatement, CylinderKeepsItsAxisInTheBodyFrame) {
  const Model model = with_shapes("shape barrel = cylinder(body = link, radius = d, length = l, axis = 2*b.1)\n");
  const VisualShape& s = model.shapes.at(0);
  EXPECT_EQ(s.kind, ShapeKind::cylinder);
  EXPECT_DOUBLE_EQ(number(s.length, model), 0.5);
  EXPECT_DOUBLE_EQ(number(s.axis[0], model), 2.0);
  EXPECT_DOUBLE_EQ(number(s.axis[1], model), 0.0);
  EXPECT_DOUBLE_EQ(number(s.axis[2], model), 0.0);
}

TEST(ShapeStatement, AxisGivenInAFrameFixedToTheBodyIsResolvedInTheBodyFrame) {
  // c is b turned a quarter turn about b.3, so c.1 is b.2
  const Model model = with_shapes("shape rim = disk(body = link, radius = d, axis = c.1)\n");
  const VisualShape& s = model.shapes.at(0);
  EXPECT_NEAR(number(s.axis[0], model), 0, 1e-15);
  EXPECT_NEAR(number(s.axis[1], model), 1, 1e-15);
  EXPECT_NEAR(number(s.axis[2], model), 0, 1e-15);
}

TEST(ShapeStatement, DiskIsATenthOfItsRadiusThickUnlessGivenAThickness) {
  const Model model = with_shapes("shape coin = disk(body = link, radius = d, axis = b.3)\n"
                                  "shape plate = disk(body = link, radius = d, axis = b.3, thickness = l/100, at = tip)\n");
  EXPECT_EQ(model.shapes.at(0).kind, ShapeKind::disk);
  EXPECT_DOUBLE_EQ(number(model.shapes[0].length, model), 0.005);
  EXPECT_DOUBLE_EQ(number(model.shapes[1].length, model), 0.005);
  EXPECT_EQ(point_name(model, model.shapes[1].at), "tip");
}

TEST(ShapeStatement, RodRunsBetweenTwoPointsAndIsALineWithoutRadius) {
  const Model model = with_shapes("shape line = rod(from = w, to = tip)\n"
                                  "shape stick = rod(from = mid, to = tip, radius = d, body = bob)\n");
  const VisualShape& line = model.shapes.at(0);
  EXPECT_EQ(line.kind, ShapeKind::rod);
  EXPECT_FALSE(line.frame);
  EXPECT_EQ(point_name(model, line.at), "w");
  EXPECT_EQ(point_name(model, line.to), "tip");
  EXPECT_DOUBLE_EQ(number(line.radius, model), 0.0);
  EXPECT_EQ(model.shapes[1].body, "bob");
  EXPECT_DOUBLE_EQ(number(model.shapes[1].radius, model), 0.05);
}

TEST(ShapeStatement, ShapesInALoopTakeTheirNamesFromIt) {
  const Model model = with_shapes("for i in 1..3\n  shape s{i} = sphere(at = tip, radius = i*d)\nend\n");
  ASSERT_EQ(model.shapes.size(), 3u);
  EXPECT_EQ(model.shapes[2].name, "s3");
  EXPECT_DOUBLE_EQ(number(model.shapes[2].radius, model), 0.15);
}

TEST(ShapeStatement, ShapesLeaveTheEquationsAlone) {
  const Model without = with_shapes("");
  const Model with = with_shapes("shape ball = sphere(body = bob, radius = d)\nshape line = rod(from = w, to = tip)\n");
  EXPECT_EQ(with.system.points().size(), without.system.points().size());
  const NumericEquations x = evaluate_equations(without, derive_equations(without), {{"q", 0.3}, {"q_dot", 1.0}});
  const NumericEquations y = evaluate_equations(with, derive_equations(with), {{"q", 0.3}, {"q_dot", 1.0}});
  EXPECT_EQ(y.mass_matrix, x.mass_matrix);
  EXPECT_EQ(y.forcing, x.forcing);
}

// --- errors, each at the argument that is wrong, line 12 ---

TEST(ShapeStatement, ErrorsSayWhatWasExpected) {
  expect("shape s = cone(body = link, radius = d)", 11, "shape 's': unknown kind of shape 'cone': expected sphere, box, cylinder, disk, rod or mesh");
  expect("shape s = sphere(body = lnk, radius = d)", 25, "unknown body or particle 'lnk'");
  expect("shape s = sphere(body = tip, radius = d)", 25,
         "shape 's' (sphere): 'tip' is a point, not a body or a particle: expected the name of a 'body' or 'particle'");
  expect("shape s = box(body = bob, size = [d, d, d])", 22,
         "shape 's' (box): 'bob' is a particle, which has no attitude: a box needs one; expected 'frame = FRAME'");
  expect("shape s = disk(body = bob, radius = d, axis = a.3)", 23, "a disk needs one");
  expect("shape s = cylinder(body = link, radius = d, length = l, axis = a.1)", 64,
         "shape 's' (cylinder): the axis turns relative to the shape's frame 'b': expected a direction fixed in it");
  expect("shape s = disk(body = link, radius = d, axis = 0*b.1)", 48, "'axis': the vector is zero");
  expect("shape s = sphere(body = link, radius = q*d)", 40,
         "shape 's' (sphere): 'radius' must be a positive constant (numbers, consts and parameters");
  expect("shape s = sphere(body = link, radius = -d)", 40, "positive at the parameters' default values), got -0.05");
  expect("shape s = box(at = tip, size = [d, 0, d])", 36, "edge 2 of 'size' must be a positive constant");
  expect("shape s = box(at = tip, size = d)", 32, "'size' must be [X, Y, Z], the edge lengths");
  expect("shape s = cylinder(body = link, radius = d, axis = b.1)", 1, "shape 's' (cylinder): missing argument 'length'");
  expect("shape s = sphere(radius = d)", 1, "shape 's' (sphere): missing argument 'at'");
  expect("shape s = rod(from = w, radius = d)", 1, "shape 's' (rod): missing argument 'to'");
  expect("shape s = sphere(body = link, radius = d, axis = b.1)", 43,
         "shape 's' (sphere): unknown argument 'axis'; expected body, radius, at, frame");
  expect("shape s = rod(from = w, to = tip, frame = b)", 35, "unknown argument 'frame'");
  expect("shape s = sphere(body = link, radius = d, at = nowhere)", 48, "nowhere");
  expect("shape link = sphere(body = link, radius = d)", 7, "duplicate name 'link'");
  expect("shape for = sphere(body = link, radius = d)", 7, "keyword");
  expect("shape s = sphere(body = link, radius = m/4)", 40,
         "shape 's' (sphere): the term '1/4*m' has dimension kg, expected m for 'radius' (a length)");
}

TEST(ShapeStatement, MeshKeepsItsFileAsWrittenAndItsScaleAlongTheFramesAxes) {
  const Model model = with_shapes(
      "shape hull = mesh(body = link, file = \"package://arm/meshes/Link 1.STL\", scale = [0.001, -0.001, d/l/100], at = tip, frame = c)\n"
      "shape plain = mesh(body = link, file = \"../meshes/link.stl\")\n"
      "shape even = mesh(at = slab, file = \"/abs/base.stl\", scale = 2*d/l)\n");
  ASSERT_EQ(model.shapes.size(), 3u);
  const VisualShape& hull = model.shapes[0];
  EXPECT_EQ(hull.kind, ShapeKind::mesh);
  EXPECT_EQ(hull.file, "package://arm/meshes/Link 1.STL");
  EXPECT_EQ(point_name(model, hull.at), "tip");
  ASSERT_TRUE(hull.frame);
  EXPECT_EQ(frame_name(model, *hull.frame), "c");
  EXPECT_DOUBLE_EQ(number(hull.scale[0], model), 0.001);
  EXPECT_DOUBLE_EQ(number(hull.scale[1], model), -0.001);  // a negative factor mirrors
  EXPECT_DOUBLE_EQ(number(hull.scale[2], model), 0.001);
  // the defaults: the body's centre and frame, unscaled
  const VisualShape& plain = model.shapes[1];
  EXPECT_EQ(plain.file, "../meshes/link.stl");
  EXPECT_EQ(point_name(model, plain.at), "mid");
  EXPECT_EQ(frame_name(model, *plain.frame), "b");
  for (const GiNaC::ex& f : plain.scale) EXPECT_DOUBLE_EQ(number(f, model), 1.0);
  // one factor for the three axes; no body: the inertial frame
  const VisualShape& even = model.shapes[2];
  EXPECT_TRUE(even.body.empty());
  EXPECT_EQ(frame_name(model, *even.frame), "a");
  for (const GiNaC::ex& f : even.scale) EXPECT_DOUBLE_EQ(number(f, model), 0.2);
}

TEST(ShapeStatement, MeshErrorsSayWhatWasExpected) {
  expect("shape s = mesh(body = link)", 1, "shape 's' (mesh): missing argument 'file' (the mesh's STL file, a string");
  expect("shape s = mesh(body = link, file = link)", 36, "shape 's' (mesh): 'file' must be a string in double quotes");
  expect("shape s = mesh(body = link, file = \"\")", 36, "shape 's' (mesh): 'file' is empty");
  expect("shape s = mesh(body = link, file = \"a.stl\", scale = 0)", 53,
         "shape 's' (mesh): 'scale' must be a constant that is not zero (numbers, consts and parameters, not zero at "
         "the parameters' default values), got 0");
  expect("shape s = mesh(body = link, file = \"a.stl\", scale = [1, q, 1])", 57,
         "shape 's' (mesh): factor 2 of 'scale' must be a constant that is not zero");
  expect("shape s = mesh(body = link, file = \"a.stl\", scale = [1, 1])", 53, "'scale' must be one factor or [X, Y, Z]");
  expect("shape s = mesh(body = link, file = \"a.stl\", scale = d)", 53,
         "the term 'd' has dimension m, expected dimensionless for 'scale' (a pure number)");
  expect("shape s = mesh(body = link, file = \"a.stl\", radius = d)", 45, "unknown argument 'radius'; expected body, file, scale, at, frame");
  // a string is a file name and nothing else
  expect("shape s = sphere(body = link, radius = \"d\")", 40,
         "expected an expression, got the string \"d\" (only a mesh's 'file' is a string)");
  expect("shape s = mesh(body = \"link\", file = \"a.stl\")", 23, "shape 's' (mesh): argument 'body' must name a body or a particle");
  expect("shape s = mesh(body = link, file = \"a.stl\" + 1)", 44, "or ')' after an argument");
}

TEST(ShapeStatement, DimensionsAreLengthsInAModelWithUnits) {
  expect_model_error(arm + "shape s = sphere(body = link, radius = 0.1)\n", 12, 40, "expected m");
  expect_model_error(arm + "shape s = box(at = tip, size = [d, d, m])\n", 12, 39, "expected m");
  // without units, numbers are lengths
  const Model plain = parse_model("coordinate q\npoint p = w + q*a.1\nparticle bob(mass = 1, at = p)\n"
                                  "shape ball = sphere(body = bob, radius = 0.1)\n", "plain.eom");
  EXPECT_DOUBLE_EQ(number(plain.shapes.at(0).radius, plain), 0.1);
}

// --- contacts of roll and wheel ---

Eigen::Vector3d direction(const ContactForce::Row& row, const Model& model) {
  return {number(row.direction[0], model), number(row.direction[1], model), number(row.direction[2], model)};
}

TEST(ShapeStatement, RollingCoinsContactIsItsRollAlongTheTangents) {
  const Model model = load_model(testing::shipped_model_path("rolling_coin"));
  ASSERT_EQ(model.contacts.size(), 1u);
  const ContactForce& c = model.contacts[0];
  EXPECT_EQ(c.name, "no_slip");
  EXPECT_EQ(point_name(model, c.point), "u");
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(model.system.constraints()[c.rows[0].constraint].name, "no_slip_1");
  EXPECT_EQ(model.system.constraints()[c.rows[1].constraint].name, "no_slip_2");
  // n = a.3: t1 = a.2, t2 = -a.1
  EXPECT_TRUE(direction(c.rows[0], model).isApprox(Eigen::Vector3d(0, 1, 0)));
  EXPECT_TRUE(direction(c.rows[1], model).isApprox(Eigen::Vector3d(-1, 0, 0)));
  ASSERT_TRUE(c.plane_normal);
  EXPECT_DOUBLE_EQ(number((*c.plane_normal)[2], model), 1.0);
  EXPECT_EQ(point_name(model, c.plane_point), "u");
}

TEST(ShapeStatement, RollWithoutNormalHasARowPerInertialAxisThatIsNotZero) {
  // a ball rolling on the plane z = 0 at its lowest point: the vertical row is identically zero
  const Model model = parse_model("parameter r = 0.1\ncoordinate x, y, p1, p2, p3\n"
                                  "frame b = euler(a, 123, p1, p2, p3)\npoint c = w + x*a.1 + y*a.2 + r*a.3\n"
                                  "point k = c - r*a.3\nbody ball(mass = 1, centre = c, frame = b, inertia = diag(1, 1, 1))\n"
                                  "roll stick(body = ball, contact = k)\n", "ball.eom");
  const ContactForce& c = model.contacts.at(0);
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_FALSE(c.plane_normal);
  EXPECT_EQ(model.system.constraints()[c.rows[1].constraint].name, "stick_2");
  EXPECT_TRUE(direction(c.rows[0], model).isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(direction(c.rows[1], model).isApprox(Eigen::Vector3d(0, 1, 0)));
}

TEST(ShapeStatement, WhippleBicyclesContactsAreItsTwoWheels) {
  const Model model = load_model(testing::shipped_model_path("whipple_bicycle"));
  ASSERT_EQ(model.contacts.size(), 2u);
  for (const ContactForce& c : model.contacts) {
    EXPECT_EQ(point_name(model, c.point), c.name + "_contact");
    ASSERT_TRUE(c.plane_normal);
    for (const ContactForce::Row& row : c.rows) {
      EXPECT_EQ(model.system.constraints()[row.constraint].name.rfind(c.name + "_", 0), 0u);
      EXPECT_NEAR(direction(row, model).norm(), 1, 1e-15);
    }
  }
  // the rear wheel is placed on the plane; the front one is held there by its contact row
  EXPECT_EQ(model.contacts[0].rows.size(), 2u);
  ASSERT_EQ(model.contacts[1].rows.size(), 3u);
  EXPECT_TRUE(direction(model.contacts[1].rows[2], model).isApprox(Eigen::Vector3d(0, 0, -1)));
}

// a disk of radius r, its centre free, standing on the plane z = 0 (the free disk of
// wheel_statement_test.cpp), pushed along a.1 at its centre
const std::string free_disk =
    "parameter r = 0.3 [m]\nparameter m = 2 [kg]\nparameter g = 9.81 [m/s^2]\nparameter P = 0 [N]\n"
    "coordinate x, y, z, psi, theta, spin\n"
    "frame h = rotate(a, 3, psi)\nframe l = rotate(h, 1, theta)\nframe d = rotate(l, 2, spin)\n"
    "point c = w + x*a.1 + y*a.2 + z*a.3\n"
    "body disk(mass = m, centre = c, frame = d, inertia = diag(m*r^2/4, m*r^2/2, m*r^2/4))\n"
    "gravity = -g*a.3\nforce push(at = c, force = P*a.1)\n"
    "wheel rim(body = disk, centre = c, axle = l.2, radius = r, normal = a.3)\n";

// the sum of lambda_row times the row's direction
Eigen::Vector3d contact_force(const Model& model, const NamedValues& state) {
  const AccelerationSolution x = solve_accelerations(evaluate_equations(model, derive_equations(model), state));
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (const ContactForce::Row& row : model.contacts.at(0).rows) f += x.lambda(row.constraint) * direction(row, model);
  return f;
}

TEST(ShapeStatement, MultipliersTimesDirectionsAreTheForceOfThePlaneOnTheWheel) {
  const Model model = parse_model(free_disk, "disk.eom");
  ASSERT_EQ(model.contacts.at(0).rows.size(), 3u);
  EXPECT_EQ(point_name(model, model.contacts[0].point), "rim_contact");
  EXPECT_EQ(point_name(model, model.contacts[0].plane_point), "w");
  const double m = 2, g = 9.81, r = 0.3, P = 1.5;
  // standing: the weight, carried along the normal
  EXPECT_LT((contact_force(model, {{"z", r}}) - Eigen::Vector3d(0, 0, m * g)).norm(), 1e-12);
  // pushed: friction -P/3 along a.1 (m a = P + F, J alpha = -r F, a = r alpha, J = m r^2/2)
  EXPECT_LT((contact_force(model, {{"z", r}, {"P", P}}) - Eigen::Vector3d(-P / 3, 0, m * g)).norm(), 1e-12);
}

}  // namespace
}  // namespace eomgen
