// `eomgen simulate --animate`: the page's scene (docs/animation.md) holds what the generated
// code recorded, checked against hand formulas of the shipped models, for every shipped model;
// the CSV is the same with or without it, and bad requests leave no file.
//
// The compiled simulations are cached in EOMGEN_TEST_CACHE_DIR (in the build tree).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::testing::Outcome;
using eomgen::testing::quote;
using eomgen::testing::slurp;
using ::testing::HasSubstr;
using ::testing::Not;
using nlohmann::json;

/// The scene of a page: the JSON of its <script type="application/json" id="scene">, with the
/// `<\/` the page writes for `</` read back.
json scene_of(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"scene\">";
  const std::size_t begin = page.find(open);
  if (begin == std::string::npos) return json();
  const std::size_t end = page.find("</script>", begin);
  std::string text = page.substr(begin + open.size(), end - begin - open.size());
  for (std::size_t at; (at = text.find("<\\/")) != std::string::npos;) text.replace(at, 3, "</");
  return json::parse(text);
}

const json& named(const json& list, const std::string& name) {
  for (const json& item : list)
    if (item["name"] == name) return item;
  static const json none;
  ADD_FAILURE() << "no entry named " << name;
  return none;
}

class Animate : public eomgen::testing::CliFixture {
 protected:
  Outcome simulate(const std::string& arguments) {
    return eomgen("simulate " + arguments + " --cache-dir " + quote(EOMGEN_TEST_CACHE_DIR));
  }
  std::string shipped(const std::string& model) const {
    return quote(std::string(EOMGEN_SOURCE_DIR) + "/models/" + model + ".eom");
  }
  std::string work(const std::string& name) const { return (dir_ / "work" / name).string(); }
};

TEST_F(Animate, TheDoublePendulumsBobsAreWhereItsAnglesPutThemAndTheCsvIsUnchanged) {
  const std::string run = shipped("double_pendulum") + " --t-end 10 --init theta1=1.8,theta2=-0.6 --no-plot";
  const Outcome plain = simulate(run + " -o " + quote(work("plain.csv")));
  ASSERT_EQ(plain.status, 0) << plain.err;
  const Outcome animated = simulate(run + " -o " + quote(work("run.csv")) + " --animate " + quote(work("run.html")));
  ASSERT_EQ(animated.status, 0) << animated.err;
  EXPECT_THAT(animated.out, HasSubstr("animation: " + work("run.html") + " ("));
  EXPECT_EQ(slurp(work("plain.csv")), slurp(work("run.csv")));

  const std::string page = slurp(work("run.html"));
  EXPECT_LT(page.size(), 2u << 20) << "the issue's bound for a 10 s double pendulum";
  const json scene = scene_of(page);
  ASSERT_TRUE(scene.is_object());
  EXPECT_EQ(scene["model"], "double_pendulum");
  const std::vector<double> t = scene["times"];
  ASSERT_EQ(t.size(), 1001u);
  EXPECT_DOUBLE_EQ(t.back(), 10.0);
  const std::vector<double> theta1 = named(scene["series"], "theta1")["values"];
  const std::vector<double> theta2 = named(scene["series"], "theta2")["values"];
  const std::vector<double> p2 = named(scene["points"], "p2")["positions"];
  ASSERT_EQ(p2.size(), 3 * t.size());
  // the outer bob from the hand derivation, l1 = 0.6, l2 = 0.4; the page keeps 6 digits
  for (std::size_t i = 0; i < t.size(); i += 50) {
    EXPECT_NEAR(p2[3 * i], 0.6 * std::sin(theta1[i]) + 0.4 * std::sin(theta1[i] + theta2[i]), 2e-5) << t[i];
    EXPECT_NEAR(p2[3 * i + 1], -0.6 * std::cos(theta1[i]) - 0.4 * std::cos(theta1[i] + theta2[i]), 2e-5) << t[i];
  }
  EXPECT_EQ(scene["up"], json::array({0, 1, 0}));  // gravity is -g a.2
  EXPECT_EQ(scene["links"], json::parse("[[0,1],[1,2]]"));
  EXPECT_EQ(scene["ground"], json());

  // the same page from a second process, byte for byte
  const Outcome again = simulate(run + " -o " + quote(work("again.csv")) + " --animate " + quote(work("again.html")));
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(slurp(work("again.html")), page);
}

TEST_F(Animate, AnAnimationThatCannotBeWrittenIsRefusedBeforeAnythingRuns) {
  const std::string run = shipped("simple_pendulum") + " --t-end 1 --no-plot -o " + quote(work("run.csv"));
  const Outcome missing_dir = simulate(run + " --animate " + quote(work("no/such/dir/run.html")));
  EXPECT_EQ(missing_dir.status, 2);
  EXPECT_THAT(missing_dir.err, HasSubstr("--animate"));
  const Outcome same_as_csv = simulate(run + " --animate " + quote(work("run.csv")));
  EXPECT_EQ(same_as_csv.status, 2);
  EXPECT_THAT(same_as_csv.err, HasSubstr("--animate"));
  EXPECT_FALSE(fs::exists(work("run.csv")));
}

TEST_F(Animate, AShapeThatTheRunsParametersMakeNoLengthIsRefusedBeforeAnythingRuns) {
  const Outcome r = simulate(shipped("rolling_coin") + " --t-end 1 --set r=-0.01 --no-plot -o " + quote(work("run.csv")) +
                             " --animate " + quote(work("run.html")));
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.err, HasSubstr("rolling_coin.eom:"));
  EXPECT_THAT(r.err, HasSubstr("shape 'coin_disk': its radius is -0.01 at the parameters of this run: expected a "
                               "finite positive length"));
  EXPECT_THAT(r.err, Not(HasSubstr("compiling")));
  EXPECT_FALSE(fs::exists(work("run.csv")));
  EXPECT_FALSE(fs::exists(work("run.html")));
}

// a body with no shape is drawn as the box of its mass and inertia; this one's inertia is not
// diagonal in its frame, which is the inertial one: principal moments 1, 3, 3 about (1, -1, 0),
// (1, 1, 0), (0, 0, 1) over root 2, so with m = 6 the edges sqrt(6 (7 - 2 J_k) / 6) = sqrt(5), 1, 1
TEST_F(Animate, ABodyWithoutAShapeIsTheBoxOfItsInertiaAlongItsPrincipalAxes) {
  const std::string path = model("slider.eom",
                                 "model slider\n"
                                 "coordinate x\n"
                                 "point c = w + x*a.1\n"
                                 "body block(mass = 6, centre = c, frame = a, inertia = [[2, 1, 0], [1, 2, 0], [0, 0, 3]])\n");
  const Outcome r = simulate(quote(path) + " --t-end 1 --init x_dot=1 --no-plot -o " + quote(work("run.csv")) +
                             " --animate " + quote(work("run.html")));
  ASSERT_EQ(r.status, 0) << r.err;
  const json scene = scene_of(slurp(work("run.html")));
  ASSERT_EQ(scene["shapes"].size(), 1u);
  const json& box = scene["shapes"][0];
  EXPECT_EQ(box["kind"], "box");
  EXPECT_EQ(box["inferred"], true);
  const std::vector<double> size = box["size"];
  ASSERT_EQ(size.size(), 3u);
  EXPECT_NEAR(size[0], std::sqrt(5.0), 1e-5);
  EXPECT_NEAR(size[1], 1.0, 1e-5);
  EXPECT_NEAR(size[2], 1.0, 1e-5);
  ASSERT_EQ(scene["frames"].size(), 1u);
  const json& frame = scene["frames"][box["frame"].get<std::size_t>()];
  EXPECT_EQ(frame["name"], "a (principal axes of block)");
  const std::vector<double> c = frame["rotations"];
  // the first principal axis, column 0 of every sample: +-(1, -1, 0)/sqrt(2)
  for (std::size_t i = 0; i < c.size(); i += 9 * 100) {
    EXPECT_NEAR(std::abs(c[i + 0]), std::sqrt(0.5), 1e-5);
    EXPECT_NEAR(c[i + 0] + c[i + 3], 0.0, 1e-5);
    EXPECT_NEAR(c[i + 6], 0.0, 1e-5);
  }
  const std::vector<double> x = named(scene["points"], "c")["positions"];
  EXPECT_NEAR(x[x.size() - 3], 1.0, 1e-5);  // x = t: it slides at 1 m/s
}

/// Each shipped model with a start that satisfies its constraints (tests/support/shipped_runs.txt,
/// which the browser test reads too).
struct ShippedRun {
  std::string model, init;
};
std::vector<ShippedRun> shipped_runs() {
  std::ifstream in(std::string(EOMGEN_SOURCE_DIR) + "/tests/support/shipped_runs.txt");
  std::vector<ShippedRun> runs;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    ShippedRun run;
    if (line.empty() || line[0] == '#' || !(fields >> run.model >> run.init)) continue;
    runs.push_back(run);
  }
  return runs;
}

/// What every page must hold: arrays of one entry per sample, indices that exist, rotations.
void expect_consistent_scene(const json& scene) {
  const std::size_t n = scene["times"].size(), points = scene["points"].size(), frames = scene["frames"].size();
  ASSERT_GT(n, 1u);
  for (const json& p : scene["points"]) EXPECT_EQ(p["positions"].size(), 3 * n) << p["name"];
  for (const json& s : scene["series"]) EXPECT_EQ(s["values"].size(), n) << s["name"];
  for (const json& f : scene["frames"]) {
    const std::vector<double> c = f["rotations"];
    ASSERT_EQ(c.size(), 9 * n) << f["name"];
    for (std::size_t i = 0; i < n; i += n / 7 + 1)  // columns orthonormal: C^T C = 1 (6 digits kept)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          double dot = 0;
          for (int k = 0; k < 3; ++k) dot += c[9 * i + 3 * k + a] * c[9 * i + 3 * k + b];
          EXPECT_NEAR(dot, a == b ? 1.0 : 0.0, 1e-5) << f["name"] << " at sample " << i;
        }
  }
  for (const json& s : scene["shapes"]) {
    EXPECT_LT(s["at"].get<std::size_t>(), points) << s["name"];
    EXPECT_GE(s["frame"].get<long>(), -1) << s["name"];
    EXPECT_LT(s["frame"].get<long>(), static_cast<long>(frames)) << s["name"];
    if (s["kind"] == "rod") {
      EXPECT_LT(s["to"].get<std::size_t>(), points) << s["name"];
    }
  }
  for (const json& l : scene["links"]) EXPECT_LT(l[1].get<std::size_t>(), points);
  for (const json& t : scene["trails"]) EXPECT_LT(t.get<std::size_t>(), points);
  for (const json& f : scene["forces"]) EXPECT_EQ(f["vectors"].size(), 3 * n) << f["name"];
}

// --- meshes -----------------------------------------------------------------------------

// a binary STL of the triangles (9 floats each), written as the format has it: an 80-byte
// header, the count, and per triangle a normal, three vertices and two attribute bytes
void write_binary_stl(const fs::path& path, const std::vector<float>& vertices) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  const std::string header = "solid but binary";  // as some exporters begin their binary files
  out << header << std::string(80 - header.size(), ' ');
  const auto u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.put(static_cast<char>((v >> (8 * k)) & 0xff));
  };
  const auto f32 = [&](float f) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    u32(bits);
  };
  u32(static_cast<std::uint32_t>(vertices.size() / 9));
  for (std::size_t t = 0; t < vertices.size() / 9; ++t) {
    for (int k = 0; k < 3; ++k) f32(0);
    for (int k = 0; k < 9; ++k) f32(vertices[9 * t + static_cast<std::size_t>(k)]);
    out.put(0), out.put(0);
  }
}

// the floats of the page's little-endian base64
std::vector<float> decoded(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    buffer = (buffer << 6) | static_cast<std::uint32_t>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) bytes.push_back(static_cast<unsigned char>((buffer >> (bits - 8)) & 0xff)), bits -= 8;
  }
  std::vector<float> out;
  for (std::size_t i = 0; i + 3 < bytes.size(); i += 4) {
    const std::uint32_t v = bytes[i] | bytes[i + 1] << 8 | bytes[i + 2] << 16 | static_cast<std::uint32_t>(bytes[i + 3]) << 24;
    float f;
    std::memcpy(&f, &v, 4);
    out.push_back(f);
  }
  return out;
}

// a tetrahedron's four faces
const std::vector<float> tetrahedron{0, 0, 0, 1, 0, 0, 0, 1, 0,  0, 0, 0, 0, 0, 1, 1, 0, 0,
                                     0, 0, 0, 0, 1, 0, 0, 0, 1,  1, 0, 0, 0, 0, 1, 0, 1, 0};

// two links, each drawn by meshes: found beside the model, in a package above it, in one of
// $ROS_PACKAGE_PATH; one not STL, one not found, one broken
const std::string meshed_links = R"(coordinate q1, q2
parameter l = 1
parameter k = 0.5
frame b = rotate(a, 3, q1)
frame c = rotate(b, 3, q2)
point p1 = w + l*b.1
point m1 = w + l/2*b.1
point m2 = p1 + l/2*c.1
body link1(mass = 1, centre = m1, frame = b, inertia = diag(0.01, 0.1, 0.1))
body link2(mass = 1, centre = m2, frame = c, inertia = diag(0.01, 0.1, 0.1))
gravity = -9.81*a.2
shape hull = mesh(body = link1, file = "meshes/tet.stl", scale = [k, -1, 2], at = w, frame = b)
shape twin = mesh(body = link1, file = "package://arm_pkg/meshes/tet.stl", scale = [k, -1, 2], at = p1)
shape again = mesh(body = link1, file = "meshes/tet.stl", scale = [k, -1, 2], at = m1)
shape other = mesh(body = link1, file = "package://other_pkg/tet.STL", at = m1)
shape cover = mesh(body = link2, file = "meshes/cover.dae", at = p1, frame = c)
shape gone = mesh(body = link2, file = "meshes/gone.stl", at = p1, frame = c)
shape broken = mesh(body = link2, file = "package://arm_pkg/meshes/broken.stl", at = p1, frame = c)
)";

TEST_F(Animate, MeshesAreDrawnFromTheirSTLFilesAndTheOthersAreNamedWithStandIns) {
  const fs::path package = dir_ / "work" / "ws" / "arm_pkg";
  write_binary_stl(package / "robot" / "meshes" / "tet.stl", tetrahedron);
  write_binary_stl(package / "meshes" / "tet.stl", tetrahedron);
  write_binary_stl(dir_ / "work" / "elsewhere" / "other_pkg" / "tet.STL", tetrahedron);
  std::ofstream(package / "meshes" / "broken.stl", std::ios::binary) << std::string(90, 'x');
  std::ofstream(package / "robot" / "meshes" / "cover.dae") << "<COLLADA/>";
  std::ofstream(package / "robot" / "model.eom") << meshed_links;
  ::setenv("ROS_PACKAGE_PATH", (dir_ / "work" / "nowhere").string().append(":").append((dir_ / "work" / "elsewhere").string()).c_str(), 1);
  const Outcome r = simulate(quote((package / "robot" / "model.eom").string()) + " --t-end 0.5 --no-plot -o " +
                             quote(work("run.csv")) + " --animate " + quote(work("run.html")));
  ::unsetenv("ROS_PACKAGE_PATH");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: shape 'cover': mesh \"meshes/cover.dae\" not drawn (a stand-in is): not STL (a "
                               ".dae file; only STL files are drawn)"));
  EXPECT_THAT(r.err, HasSubstr("warning: shape 'gone': mesh \"meshes/gone.stl\" not drawn (a stand-in is): not found "
                               "(searched " + (package / "robot" / "meshes" / "gone.stl").string() + ")"));
  EXPECT_THAT(r.err, HasSubstr("warning: shape 'broken': mesh \"package://arm_pkg/meshes/broken.stl\" not drawn (a "
                               "stand-in is): " + (package / "meshes" / "broken.stl").string() + " cannot be drawn: "));

  const json scene = scene_of(slurp(work("run.html")));
  ASSERT_TRUE(scene.is_object());
  // again shares hull's triangles (one file, one scale); twin's are the same numbers from another
  // file; other's are unscaled
  ASSERT_EQ(scene["meshes"].size(), 3u);
  EXPECT_EQ(named(scene["shapes"], "again")["mesh"], named(scene["shapes"], "hull")["mesh"]);
  const json& hull = named(scene["shapes"], "hull");
  const json& twin = named(scene["shapes"], "twin");
  const json& other = named(scene["shapes"], "other");
  EXPECT_EQ(hull["kind"], "mesh");
  EXPECT_EQ(hull["body"], "link1");
  EXPECT_NE(hull["mesh"], twin["mesh"]) << "two files, even of the same content, are two meshes";
  const json& hull_mesh = scene["meshes"][hull["mesh"].get<std::size_t>()];
  EXPECT_EQ(hull_mesh["file"], "meshes/tet.stl");
  EXPECT_EQ(hull_mesh["triangles"], 4);
  const std::vector<float> v = decoded(hull_mesh["vertices"].get<std::string>());
  ASSERT_EQ(v.size(), tetrahedron.size());
  const float scale[3] = {0.5f, -1.0f, 2.0f};
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_EQ(v[i], scale[i % 3] * tetrahedron[i]) << i;
  EXPECT_EQ(hull["bounds"], json::parse("[0,-1,0,0.5,0,2]"));
  const json& other_mesh = scene["meshes"][other["mesh"].get<std::size_t>()];
  EXPECT_EQ(other_mesh["file"], "package://other_pkg/tet.STL");
  EXPECT_EQ(decoded(other_mesh["vertices"].get<std::string>()), tetrahedron);
  EXPECT_EQ(other["bounds"], json::parse("[0,0,0,1,1,1]"));

  // the three left out are listed; link2 has no mesh drawn, so its stand-in is its inertia's box
  ASSERT_EQ(scene["missing_meshes"].size(), 3u);
  EXPECT_EQ(scene["missing_meshes"][0]["shape"], "cover");
  EXPECT_EQ(scene["missing_meshes"][1]["file"], "meshes/gone.stl");
  EXPECT_THAT(scene["missing_meshes"][2]["reason"].get<std::string>(), HasSubstr("cannot be drawn"));
  for (const char* missing : {"cover", "gone", "broken"})
    for (const json& shape : scene["shapes"]) EXPECT_NE(shape["name"], missing);
  const json& stand_in = named(scene["shapes"], "link2");
  EXPECT_EQ(stand_in["inferred"], true);
  for (const json& shape : scene["shapes"]) EXPECT_NE(shape["name"], "link1") << "link1 is drawn by its meshes";
}

TEST_F(Animate, EveryShippedModelAnimates) {
  const std::vector<ShippedRun> runs = shipped_runs();
  std::vector<std::string> models;
  for (const auto& entry : fs::directory_iterator(fs::path(EOMGEN_SOURCE_DIR) / "models"))
    if (entry.path().extension() == ".eom") models.push_back(entry.path().stem().string());
  EXPECT_EQ(runs.size(), models.size()) << "tests/support/shipped_runs.txt lists every shipped model";
  for (const ShippedRun& run : runs) {
    SCOPED_TRACE(run.model);
    const std::string page = work(run.model + ".html");
    const Outcome r = simulate(shipped(run.model) + " --t-end 1 --init " + run.init + " --no-plot -o " +
                               quote(work(run.model + ".csv")) + " --animate " + quote(page));
    ASSERT_EQ(r.status, 0) << r.err;
    const json scene = scene_of(slurp(page));
    ASSERT_TRUE(scene.is_object());
    EXPECT_EQ(scene["model"], run.model);
    expect_consistent_scene(scene);
    EXPECT_FALSE(scene["shapes"].empty()) << "every shipped model has something to draw";
  }
}

}  // namespace
