// scene_recording: what `simulate --animate` records at each sample, as expressions of the
// state, checked against hand-derived positions and against each other.
#include "eomgen/derivation/scene_recording.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eomgen/language/model_file.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

using ::testing::ElementsAre;
using ::testing::Pair;

Model shipped(const std::string& name) { return load_model(testing::shipped_model_path(name)); }

double value(const GiNaC::ex& e, const GiNaC::exmap& at) {
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(at, GiNaC::subs_options::no_pattern).evalf()).to_double();
}

/// Parameters at their defaults, coordinates and rates random.
GiNaC::exmap random_state(const MechanicalSystem& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  GiNaC::exmap at = s.parameter_defaults();
  for (const Coordinate& c : s.variables().coordinates()) at[c.q] = uniform(rng), at[c.qd] = uniform(rng);
  at[s.variables().time()] = uniform(rng);
  return at;
}

TEST(SceneRecording, TheDoublePendulumsBobsAreWhereTheHandDerivationPutsThem) {
  const Model model = shipped("double_pendulum");
  const SceneRecording r = scene_recording(model);
  EXPECT_TRUE(r.frames.empty());  // no rigid body and no shape turns with a frame
  ASSERT_EQ(r.points.size(), 3u);  // w, p1, p2
  ASSERT_EQ(r.components.size(), 9u);
  EXPECT_THAT(r.links, ElementsAre(Pair(0u, 1u), Pair(1u, 2u)));  // the two rods
  EXPECT_THAT(r.trails, ElementsAre(2u));                         // the outer bob
  const Variables& v = model.system.variables();
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const GiNaC::exmap at = random_state(model.system, seed);
    const double t1 = value(v.coordinates()[0].q, at), t2 = value(v.coordinates()[1].q, at);
    const double l1 = 0.6, l2 = 0.4;
    EXPECT_NEAR(value(r.components[6], at), l1 * std::sin(t1) + l2 * std::sin(t1 + t2), 1e-14);
    EXPECT_NEAR(value(r.components[7], at), -l1 * std::cos(t1) - l2 * std::cos(t1 + t2), 1e-14);
    EXPECT_NEAR(value(r.components[8], at), 0.0, 1e-14);
  }
}

TEST(SceneRecording, ABodysAttitudeIsARotationThatCarriesItsCentreFromThePivot) {
  // the heavy top: centre = w + l b.3, so the centre's recorded position is l times the third
  // column of the recorded C_ab; the two come from different code (the frame tree, the points)
  const Model model = shipped("heavy_top");
  const SceneRecording r = scene_recording(model);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(model.system.frame(r.frames[0].first).name, "b");
  EXPECT_EQ(r.frames[0].second, "top");
  ASSERT_EQ(r.points.size(), 2u);  // w, centre
  ASSERT_EQ(r.components.size(), 9u + 6u);
  EXPECT_THAT(r.trails, ElementsAre(1u));
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const GiNaC::exmap at = random_state(model.system, seed);
    double c[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] = value(r.components[3 * i + j], at);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double cct = 0;
        for (int k = 0; k < 3; ++k) cct += c[k][i] * c[k][j];
        EXPECT_NEAR(cct, i == j ? 1.0 : 0.0, 1e-14);
      }
    const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                       c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
                       c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0]);
    EXPECT_NEAR(det, 1.0, 1e-14);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(value(r.components[12 + i], at), 0.05 * c[i][2], 1e-15);
  }
}

TEST(SceneRecording, AnOffsetThatHoldsACoordinateIsAFreedomNotALink) {
  // cart_pole: the cart slides along a.1 (x*a.1: no link from w); the pole's points hang from
  // the hinge by offsets fixed in the pole's frame
  const Model model = shipped("cart_pole");
  const SceneRecording r = scene_recording(model);
  std::vector<std::pair<std::string, std::string>> links;
  for (const auto& [parent, child] : r.links)
    links.emplace_back(model.system.point(PointId{parent}).name, model.system.point(PointId{child}).name);
  EXPECT_THAT(links, ElementsAre(Pair("hinge", "pole_centre"), Pair("hinge", "pole_tip")));
}

TEST(SceneRecording, TheSceneOutputTakesANameNoOutputOfTheModelHas) {
  Model model = shipped("double_pendulum");
  model.outputs.push_back(Output{"scene", {GiNaC::ex(1)}, {"scene"}, {}});
  model.outputs.push_back(Output{"scene_x", {GiNaC::ex(1)}, {"scene__0"}, {}});
  const SceneRecording r = scene_recording(model);
  const Model recorded = with_scene_output(model, r);
  ASSERT_EQ(recorded.outputs.size(), model.outputs.size() + 1);
  const Output& scene = recorded.outputs.back();
  EXPECT_EQ(scene.name, "scene___");
  EXPECT_EQ(scene.labels.front(), "scene____0");
  EXPECT_EQ(scene.components.size(), r.components.size());
}

}  // namespace
}  // namespace eomgen
