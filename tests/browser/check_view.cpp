// Checks what an animation page's view shows (docs/animation.md), from the scene in the page and
// the view the page reported in #status at one or more times (the test hook's `view`: the
// camera's matrices as drawn, the camera's choice, the grid's and the axes' geometry, the drawn
// shapes):
//
//   check_view [--follow CHOICE] PAGE.html STATUS.json...
//
// Without --follow (the default view): the camera is fixed (the same at every time) and every
// point of the scene at every sample projects inside the view, as do the axes' tips and every
// corner of every box and of every mesh's bounds, turned by its frame, at every sample; the run
// reaches at least 0.35 of the way from the view's centre to its edge (when the points make its
// size, not the shapes about them). With --follow CHOICE ("mechanism" or
// "body:NAME"), the choice is made, the camera looks at the followed point at the time (the mean
// of the moving points, or the body's point), keeps its place relative to it, and every moving
// point at that time is inside the view. Always: the reported matrices are the camera's
// (perspective and look-at from its fov, aspect, near, far, position, target and up); the grid
// lies in the scene's ground, else in the plane normal to up below every point (at the origin's
// height or lower), its lines parallel, a round cell apart and through the origin's foot,
// covering every point; the axes a.1, a.2, a.3 start at the origin along the inertial unit
// vectors, one length, red, green and blue, labelled beyond their tips; every shape the page can
// draw (a known kind; a mesh whose base64 decodes to its triangles) is drawn and no other, each
// but a rod at its point and turned with its frame, a mesh with three vertices per triangle; a
// mesh's bounds are its vertices' box; the page counts the scene's missing meshes. Prints what it
// checked; fails with the reason.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using json = nlohmann::json;
using Vec = std::array<double, 3>;

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void demand(bool ok, const std::string& what) {
  if (!ok) throw Failure(what);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  demand(static_cast<bool>(in), "cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// the scene: the JSON of <script type="application/json" id="scene"> (its '<' written \u003c)
json scene_of(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"scene\">";
  const std::size_t at = page.find(open);
  demand(at != std::string::npos, "the page has no scene element");
  const std::size_t end = page.find("</script>", at);
  demand(end != std::string::npos, "the scene element is not closed");
  return json::parse(page.substr(at + open.size(), end - at - open.size()));
}

// #status as Chromium's --dump-dom serializes it: text with &, <, > (and no-break spaces) escaped
json status_of(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '&') {
      out += text[i];
      continue;
    }
    const auto entity = [&](const char* name, const char* replacement) {
      const std::string e = name;
      if (text.compare(i, e.size(), e) != 0) return false;
      out += replacement;
      i += e.size() - 1;
      return true;
    };
    if (!entity("&amp;", "&") && !entity("&lt;", "<") && !entity("&gt;", ">") && !entity("&nbsp;", " ")) out += '&';
  }
  return json::parse(out);
}

Vec vec(const json& j, const std::string& what) {
  demand(j.is_array() && j.size() == 3, what + " is not a vector of 3 numbers: " + j.dump());
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}
Vec operator-(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec operator+(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec operator*(double s, const Vec& a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec unit(const Vec& a) { return (1.0 / norm(a)) * a; }
std::string str(const Vec& a) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", a[0], a[1], a[2]); }
void expect_near(double a, double b, double tolerance, const std::string& what) {
  demand(std::abs(a - b) <= tolerance, fmt::format("{}: {:.9g} where {:.9g} was expected", what, a, b));
}
void expect_near(const Vec& a, const Vec& b, double tolerance, const std::string& what) {
  demand(norm(a - b) <= tolerance, fmt::format("{}: {} where {} was expected", what, str(a), str(b)));
}

// a 4x4 matrix, column-major as three.js holds it
using Mat = std::array<double, 16>;
Mat mat(const json& j, const std::string& what) {
  demand(j.is_array() && j.size() == 16, what + " is not a 4x4 matrix");
  Mat m{};
  for (std::size_t i = 0; i < 16; ++i) m[i] = j[i].get<double>();
  return m;
}

// a 3x3 matrix, row-major as the scene holds rotations (its columns a frame's unit vectors)
using Mat3 = std::array<double, 9>;
constexpr Mat3 identity3 = {1, 0, 0, 0, 1, 0, 0, 0, 1};
Vec apply(const Mat3& m, const Vec& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2], m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

// A mesh of the scene's `meshes` as the page decodes it: `vertices` is base64 (atob's forgiving
// decoding: ASCII whitespace dropped, one or two '=' at the end of a length that is a multiple
// of four) of 9 little-endian float32 per triangle; the page draws it only when that decodes to
// exactly `triangles` triangles of finite numbers
struct Mesh {
  bool drawable = false;
  std::string why;              // when not drawable
  std::size_t triangles = 0;
  std::vector<float> vertices;  // 9 per triangle
};
Mesh decode_mesh(const json& m) {
  Mesh out;
  if (!m.is_object()) return out.why = "it is not an object", out;
  if (!m.contains("triangles") || !m["triangles"].is_number_unsigned()) return out.why = "no number of triangles", out;
  out.triangles = m["triangles"].get<std::size_t>();
  if (!m.contains("vertices") || !m["vertices"].is_string()) return out.why = "no base64 vertices", out;
  std::string text;
  for (const char c : m["vertices"].get<std::string>())
    if (c != ' ' && c != '\t' && c != '\n' && c != '\f' && c != '\r') text += c;
  if (text.size() % 4 == 0 && !text.empty() && text.back() == '=') text.pop_back();
  if (text.size() % 4 == 0 && !text.empty() && text.back() == '=') text.pop_back();
  if (text.size() % 4 == 1) return out.why = "its vertices are not base64", out;
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned bits = 0, count = 0;
  for (const char c : text) {
    const std::size_t value = alphabet.find(c);
    if (value == std::string::npos) return out.why = "its vertices are not base64", out;
    bits = (bits << 6) | static_cast<unsigned>(value), count += 6;
    if (count >= 8) count -= 8, bytes.push_back(static_cast<unsigned char>((bits >> count) & 0xff));
  }
  if (bytes.size() != 36 * out.triangles)
    return out.why = fmt::format("{} bytes where {} triangles need {}", bytes.size(), out.triangles, 36 * out.triangles), out;
  for (std::size_t i = 0; i < bytes.size(); i += 4) {
    const std::uint32_t word = static_cast<std::uint32_t>(bytes[i]) | static_cast<std::uint32_t>(bytes[i + 1]) << 8 |
                               static_cast<std::uint32_t>(bytes[i + 2]) << 16 | static_cast<std::uint32_t>(bytes[i + 3]) << 24;
    float v = 0;
    std::memcpy(&v, &word, sizeof v);
    if (!std::isfinite(v)) return out.why = "a vertex is not finite", out;
    out.vertices.push_back(v);
  }
  out.drawable = true;
  return out;
}

struct Scene {
  json data;
  std::vector<double> times;
  std::vector<std::vector<double>> positions;  // per point, 3 n numbers (empty when short)
  std::vector<std::vector<double>> rotations;  // per frame, 9 n numbers (empty when short)
  std::vector<Mesh> meshes;
  double scale = 1;                            // the diagonal of the box of every point and the origin
  double largest_shape = 0;                    // the largest dimension of a shape: a diameter, a length, a box's diagonal

  std::size_t samples() const { return times.size(); }
  // the sample interval holding t and the fraction of the way through it, as the page finds them
  std::pair<std::size_t, double> locate(double t) const {
    const std::size_t n = samples();
    std::size_t k = 0;
    double f = 0;
    if (n >= 2 && t > times.front()) {
      if (t >= times.back()) {
        k = n - 2, f = 1;
      } else {
        k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
        const double span = times[k + 1] - times[k];
        f = span > 0 ? (t - times[k]) / span : 0;
      }
    }
    return {k, f};
  }
  // a point at time t, interpolated linearly between samples as the page does
  Vec at(std::size_t point, double t) const {
    const std::vector<double>& x = positions.at(point);
    const std::size_t n = samples();
    const auto [k, f] = locate(t);
    const std::size_t b = n > 1 ? k + 1 : k;
    return {x[3 * k] + f * (x[3 * b] - x[3 * k]), x[3 * k + 1] + f * (x[3 * b + 1] - x[3 * k + 1]),
            x[3 * k + 2] + f * (x[3 * b + 2] - x[3 * k + 2])};
  }
  // where a shape's point is at time t: the origin when it names no point with positions
  Vec shape_point(const json& shape, double t) const {
    const json& at = shape.contains("at") ? shape["at"] : json();
    if (!at.is_number_integer() || at.get<long>() < 0 || at.get<std::size_t>() >= positions.size() ||
        positions[at.get<std::size_t>()].empty())
      return {0, 0, 0};
    return this->at(at.get<std::size_t>(), t);
  }
  // a frame's rotation at sample k (the inertial frame's, the identity, for -1 or a frame without rotations)
  Mat3 rotation(const json& frame, std::size_t k) const {
    if (!frame.is_number_integer() || frame.get<long>() < 0 || frame.get<std::size_t>() >= rotations.size()) return identity3;
    const std::vector<double>& r = rotations[frame.get<std::size_t>()];
    if (r.empty()) return identity3;
    Mat3 m{};
    for (std::size_t i = 0; i < 9; ++i) m[i] = r[9 * k + i];
    return m;
  }
  // the rotation at time t, the samples' matrices interpolated linearly (the page slerps: they
  // differ by the square of the angle between samples)
  Mat3 rotation_at(const json& frame, double t) const {
    if (samples() == 0) return identity3;
    const auto [k, f] = locate(t);
    const Mat3 a = rotation(frame, k), b = rotation(frame, samples() > 1 ? k + 1 : k);
    Mat3 m{};
    for (std::size_t i = 0; i < 9; ++i) m[i] = a[i] + f * (b[i] - a[i]);
    return m;
  }
  // the mesh a shape draws, or none when it is no mesh shape or its mesh cannot be drawn
  const Mesh* mesh_of(const json& shape) const {
    if (shape.value("kind", "") != "mesh" || !shape.contains("mesh") || !shape["mesh"].is_number_unsigned()) return nullptr;
    const std::size_t k = shape["mesh"].get<std::size_t>();
    return k < meshes.size() && meshes[k].drawable ? &meshes[k] : nullptr;
  }
  // whether the page draws a shape: a known kind, and a mesh it can decode
  bool drawn(const json& shape) const {
    static const std::set<std::string> kinds = {"sphere", "box", "cylinder", "disk", "rod"};
    return shape.is_object() && (kinds.count(shape.value("kind", "")) != 0 || mesh_of(shape) != nullptr);
  }
  // the corners of a box or mesh shape's box in its frame's components from its point
  std::vector<Vec> corners(const json& shape) const {
    Vec lo, hi;
    if (shape.value("kind", "") == "box" && shape.contains("size") && shape["size"].is_array() && shape["size"].size() == 3) {
      hi = 0.5 * vec(shape["size"], "a box's size"), lo = -1.0 * hi;
    } else if (const Mesh* m = mesh_of(shape); m != nullptr && !m->vertices.empty()) {
      const json& b = shape.at("bounds");
      lo = {b[0].get<double>(), b[1].get<double>(), b[2].get<double>()}, hi = {b[3].get<double>(), b[4].get<double>(), b[5].get<double>()};
    } else {
      return {};
    }
    std::vector<Vec> out;
    for (int k = 0; k < 8; ++k) out.push_back({k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]});
    return out;
  }
  Vec sample(std::size_t point, std::size_t k) const {
    const std::vector<double>& x = positions.at(point);
    return {x[3 * k], x[3 * k + 1], x[3 * k + 2]};
  }
  // the largest distance a point moves from its first place
  double travel(std::size_t point) const {
    double d = 0;
    for (std::size_t k = 0; k < positions[point].size() / 3; ++k) d = std::max(d, norm(sample(point, k) - sample(point, 0)));
    return d;
  }
};

Scene load_scene(const std::string& page_path) {
  Scene s;
  s.data = scene_of(read_file(page_path));
  if (s.data.contains("times") && s.data["times"].is_array())
    for (const json& t : s.data["times"]) s.times.push_back(t.get<double>());
  Vec lo{0, 0, 0}, hi{0, 0, 0};
  if (s.data.contains("points") && s.data["points"].is_array()) {
    for (const json& p : s.data["points"]) {
      std::vector<double> x;
      if (p.contains("positions") && p["positions"].is_array())
        for (const json& v : p["positions"]) x.push_back(v.get<double>());
      if (x.size() < 3 * s.samples() || s.samples() == 0) x.clear();
      for (std::size_t i = 0; i < x.size(); ++i) lo[i % 3] = std::min(lo[i % 3], x[i]), hi[i % 3] = std::max(hi[i % 3], x[i]);
      s.positions.push_back(std::move(x));
    }
  }
  // without points the page frames a unit box about the origin
  bool any = false;
  for (const std::vector<double>& x : s.positions) any = any || !x.empty();
  s.scale = any ? std::max(norm(hi - lo), 1e-3) : 1.0;
  if (s.data.contains("frames") && s.data["frames"].is_array()) {
    for (const json& f : s.data["frames"]) {
      std::vector<double> r;
      if (f.contains("rotations") && f["rotations"].is_array())
        for (const json& v : f["rotations"]) r.push_back(v.get<double>());
      if (r.size() < 9 * s.samples() || s.samples() == 0) r.clear();
      s.rotations.push_back(std::move(r));
    }
  }
  if (s.data.contains("meshes") && s.data["meshes"].is_array())
    for (const json& m : s.data["meshes"]) s.meshes.push_back(decode_mesh(m));
  for (const json& shape : s.data.value("shapes", json::array())) {
    s.largest_shape = std::max({s.largest_shape, 2 * shape.value("radius", 0.0), shape.value("length", 0.0)});
    const json size = shape.value("size", json::array());
    if (size.size() == 3) s.largest_shape = std::max(s.largest_shape, norm(vec(size, "a box's size")));
    // a mesh shape: its bounds are its vertices' box (the float32 numbers, as written with six
    // significant digits)
    const Mesh* mesh = s.mesh_of(shape);
    if (mesh == nullptr || mesh->vertices.empty()) continue;
    const json& b = shape.contains("bounds") ? shape["bounds"] : json();
    demand(b.is_array() && b.size() == 6, fmt::format("mesh shape {} has no bounds of 6 numbers: {}", shape.value("name", "?"), b.dump()));
    std::array<double, 6> box{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < mesh->vertices.size(); ++i)
      box[i % 3] = std::min(box[i % 3], static_cast<double>(mesh->vertices[i])), box[3 + i % 3] = std::max(box[3 + i % 3], static_cast<double>(mesh->vertices[i]));
    const double diagonal = std::hypot(box[3] - box[0], box[4] - box[1], box[5] - box[2]);
    for (std::size_t i = 0; i < 6; ++i)
      expect_near(b[i].get<double>(), box[i], 1e-5 * std::max(diagonal, std::abs(box[i])) + 1e-12,
                  fmt::format("mesh shape {}'s bounds[{}] against its vertices' box", shape.value("name", "?"), i));
    s.largest_shape = std::max(s.largest_shape, diagonal);
  }
  return s;
}

struct Projected {
  double x, y, z;
  bool in_front;
};
Projected project(const Mat& projection, const Mat& view, const Vec& p) {
  std::array<double, 4> e{}, c{};
  for (int r = 0; r < 4; ++r) e[r] = view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2] + view[12 + r];
  for (int r = 0; r < 4; ++r) c[r] = projection[r] * e[0] + projection[4 + r] * e[1] + projection[8 + r] * e[2] + projection[12 + r] * e[3];
  return {c[0] / c[3], c[1] / c[3], c[2] / c[3], c[3] > 0};
}
bool inside(const Projected& q) {
  return q.in_front && std::abs(q.x) <= 1 && std::abs(q.y) <= 1 && q.z >= -1 && q.z <= 1;
}


// The reported matrices are the camera's: three.js's perspective of fov, aspect, near, far, and
// the inverse of the camera's pose looking from position at target with up
void check_camera(const json& camera, const json& canvas, double scale) {
  const double fov = camera.at("fov").get<double>(), aspect = camera.at("aspect").get<double>();
  const double near = camera.at("near").get<double>(), far = camera.at("far").get<double>();
  demand(canvas.is_array() && canvas.size() == 2 && canvas[0].get<double>() > 0 && canvas[1].get<double>() > 0,
         "the view has no size: " + canvas.dump());
  expect_near(aspect, canvas[0].get<double>() / canvas[1].get<double>(), 0.01, "the camera's aspect against the view's");
  demand(near > 0 && far > near, fmt::format("near {} and far {} are no depth range", near, far));
  const Mat p = mat(camera.at("projection"), "the projection");
  const double top = near * std::tan(fov / 2 * M_PI / 180), right = top * aspect;
  const Mat expected_p = {near / right, 0, 0, 0, 0, near / top, 0, 0, 0, 0, -(far + near) / (far - near), -1,
                          0, 0, -2 * far * near / (far - near), 0};
  for (std::size_t i = 0; i < 16; ++i)
    expect_near(p[i], expected_p[i], 1e-6 * std::max(1.0, std::abs(expected_p[i])), fmt::format("projection[{}]", i));

  const Vec position = vec(camera.at("position"), "the camera's position"), target = vec(camera.at("target"), "its target");
  const Vec up = vec(camera.at("up"), "its up");
  const Vec z = unit(position - target), x = unit(cross(up, z)), y = cross(z, x);
  const Mat v = mat(camera.at("view"), "the view matrix");
  const Mat expected_v = {x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
                          -dot(x, position), -dot(y, position), -dot(z, position), 1};
  for (std::size_t i = 0; i < 16; ++i)
    expect_near(v[i], expected_v[i], 1e-6 * std::max(1.0, i >= 12 ? scale : 1.0), fmt::format("view[{}]", i));
}

// the grid: one plane, normal to the expected normal, lines a cell apart through the origin's
// foot along two perpendicular directions, covering every point of the run
void check_grid(const Scene& scene, const json& grid) {
  demand(grid.is_object(), "there is no grid");
  demand(grid.at("visible").get<bool>(), "the grid is hidden");
  const json& v = grid.at("vertices");
  demand(v.is_array() && v.size() % 6 == 0 && v.size() >= 6 * 4, fmt::format("the grid has {} numbers, not 4 lines or more", v.size()));
  std::vector<Vec> vertices;
  for (std::size_t i = 0; i < v.size(); i += 3) vertices.push_back({v[i].get<double>(), v[i + 1].get<double>(), v[i + 2].get<double>()});
  const json& data = scene.data;
  const bool ground = data.contains("ground") && data["ground"].is_object();
  Vec normal = data.contains("up") && data["up"].is_array() && data["up"].size() == 3 ? vec(data["up"], "up") : Vec{0, 0, 1};
  if (ground) normal = vec(data["ground"].at("normal"), "the ground's normal");
  normal = unit(normal);
  const double tolerance = 1e-5 * scene.scale;
  const Vec origin = vertices.front();
  for (const Vec& p : vertices) expect_near(dot(p - origin, normal), 0, tolerance, "a grid vertex's height over the grid's plane");
  const double height = dot(origin, normal);
  std::string where;
  if (ground) {
    expect_near(height, dot(vec(data["ground"].at("point"), "the ground's point"), normal), tolerance, "the grid's height against the ground's");
    where = "in the ground";
  } else {
    double lowest = 0;
    for (std::size_t i = 0; i < scene.positions.size(); ++i)
      for (std::size_t k = 0; k < scene.positions[i].size() / 3; ++k) lowest = std::min(lowest, dot(scene.sample(i, k), normal));
    demand(height <= lowest + tolerance, fmt::format("the grid at height {:.6g} is above a point at {:.6g}", height, lowest));
    // below the lowest point by no more than what is drawn about it
    demand(height >= lowest - 0.25 * scene.scale - scene.largest_shape,
           fmt::format("the grid at height {:.6g} is far below the lowest point, at {:.6g}", height, lowest));
    where = fmt::format("normal to up {} at height {:.4g} (the lowest point: {:.4g})", str(normal), height, lowest);
  }
  const Vec d1 = unit(vertices[1] - vertices[0]), d2 = cross(normal, d1);
  const double cell = grid.at("cell").get<double>();
  demand(cell > 0, "the grid's cell is not positive");
  const double log_cell = std::log10(cell), mantissa = cell / std::pow(10.0, std::floor(log_cell + 1e-9));
  demand(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6,
         fmt::format("the grid's cell {:.9g} is not 1, 2 or 5 times a power of 10", cell));
  // the origin's foot on the grid's plane, in the grid's directions
  const double foot1 = dot(Vec{0, 0, 0} - origin, d1), foot2 = dot(Vec{0, 0, 0} - origin, d2);
  // the grid's segments lie on lines along d1 or d2, a whole number of cells from the origin's foot
  double lo1 = INFINITY, hi1 = -INFINITY, lo2 = INFINITY, hi2 = -INFINITY;
  std::set<long> lines1, lines2;
  for (std::size_t i = 0; i < vertices.size(); i += 2) {
    const Vec d = vertices[i + 1] - vertices[i];
    demand(norm(d) > 0, "a grid line has no length");
    const bool first = std::abs(dot(unit(d), d1)) > 1 - 1e-6;
    demand(first || std::abs(dot(unit(d), d2)) > 1 - 1e-6, "a grid line is neither along nor across the others");
    const double offset = first ? dot(vertices[i] - origin, d2) - foot2 : dot(vertices[i] - origin, d1) - foot1;
    expect_near(offset / cell, std::round(offset / cell), 1e-4, "a grid line's distance from the origin's foot in cells");
    (first ? lines1 : lines2).insert(std::lround(offset / cell));
    for (const Vec& p : {vertices[i], vertices[i + 1]}) {
      lo1 = std::min(lo1, dot(p - origin, d1)), hi1 = std::max(hi1, dot(p - origin, d1));
      lo2 = std::min(lo2, dot(p - origin, d2)), hi2 = std::max(hi2, dot(p - origin, d2));
    }
  }
  const std::size_t along1 = lines1.size(), along2 = lines2.size();
  demand(along1 >= 2 && along2 >= 2, fmt::format("the grid has {} and {} lines in its two directions", along1, along2));
  demand(along1 <= 80 && along2 <= 80, fmt::format("the grid has {} and {} lines: too fine for its size", along1, along2));
  std::size_t covered = 0;
  for (std::size_t i = 0; i < scene.positions.size(); ++i) {
    for (std::size_t k = 0; k < scene.positions[i].size() / 3; ++k) {
      const Vec p = scene.sample(i, k) - origin;
      const double a = dot(p, d1), b = dot(p, d2);
      demand(a >= lo1 - tolerance && a <= hi1 + tolerance && b >= lo2 - tolerance && b <= hi2 + tolerance,
             fmt::format("point {} at sample {}, {}, is beyond the grid", i, k, str(scene.sample(i, k))));
      ++covered;
    }
  }
  const double side = std::max(hi1 - lo1, hi2 - lo2);
  demand(side <= 3 * (scene.scale + scene.largest_shape) + 10 * cell,
         fmt::format("the grid's side {:.6g} is not sized from the run (its extent {:.6g})", side, scene.scale));
  std::cout << fmt::format("ok: the grid lies {}: {} by {} lines {:.4g} apart ({:.4g} by {:.4g}), covering {} positions\n", where,
                           along1, along2, cell, hi1 - lo1, hi2 - lo2, covered);
}

// the axes a.1, a.2, a.3 at the origin, along the unit vectors, one length, coloured, labelled
// beyond their tips; returns the tips
std::vector<Vec> check_axes(const json& axes, double scale) {
  demand(axes.is_array() && axes.size() == 3, "there are not three axes: " + axes.dump());
  const std::array<const char*, 3> colours = {"d62728", "2ca02c", "1f5fd6"};
  std::vector<Vec> tips;
  double length = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const json& a = axes[k];
    const std::string name = fmt::format("a.{}", k + 1);
    demand(a.is_object(), "there is no axis " + name);
    demand(a.at("name") == name, "axis " + name + " is named " + a.at("name").dump());
    demand(a.at("visible").get<bool>(), "axis " + name + " is hidden");
    expect_near(vec(a.at("start"), name), Vec{0, 0, 0}, 1e-9 * scale, name + "'s start");
    const Vec tip = vec(a.at("tip"), name + "'s tip");
    Vec e{0, 0, 0};
    e[k] = 1;
    if (k == 0) length = norm(tip);
    demand(length > 0, "axis a.1 has no length");
    expect_near(tip, length * e, 1e-6 * length, name + "'s tip");
    demand(a.at("colour") == colours[k], name + " is coloured " + a.at("colour").dump() + ", not " + colours[k]);
    const json& label = a.at("label");
    demand(label.is_object() && label.at("text") == name && label.at("visible").get<bool>(), name + " has no visible label " + label.dump());
    const Vec at = vec(label.at("position"), name + "'s label");
    demand(norm(at - dot(at, e) * e) <= 1e-9 * scale && dot(at, e) >= length, name + "'s label is not beyond its tip: " + str(at));
    tips.push_back(tip);
  }
  std::cout << fmt::format("ok: the axes a.1, a.2, a.3 at the origin, {:.4g} long, red, green, blue, labelled\n", length);
  return tips;
}

// the point a following camera looks at, at time t
Vec followed(const Scene& scene, const std::string& choice, const json& moving, double t) {
  if (choice == "mechanism") {
    demand(moving.is_array() && !moving.empty(), "the page names no moving points");
    Vec sum{0, 0, 0};
    for (const json& i : moving) sum = sum + scene.at(i.get<std::size_t>(), t);
    return (1.0 / static_cast<double>(moving.size())) * sum;
  }
  demand(choice.rfind("body:", 0) == 0, "unknown camera choice " + choice);
  const std::string body = choice.substr(5);
  // the body's shape's point (not a rod's, when it has another), else its particle's
  long point = -1;
  const json& shapes = scene.data.at("shapes");
  for (const json& s : shapes)
    if (point < 0 && scene.drawn(s) && s.at("body") == body && s.at("kind") != "rod") point = s.at("at").get<long>();
  for (const json& s : shapes)
    if (point < 0 && scene.drawn(s) && s.at("body") == body) point = s.at("at").get<long>();
  for (const json& p : scene.data.at("particles"))
    if (point < 0 && p.at("name") == body) point = p.at("point").get<long>();
  demand(point >= 0, "body " + body + " is drawn at no point");
  return scene.at(static_cast<std::size_t>(point), t);
}

// The shapes as drawn at time t: each shape the page can draw (a known kind; a mesh it can
// decode), none other; each but a rod at its point, turned with its frame; a mesh with three
// vertices per triangle
void check_shapes(const Scene& scene, const json& drawn, double t) {
  demand(drawn.is_array(), "the view names no drawn shapes");
  const json shapes = scene.data.value("shapes", json::array());
  std::set<std::size_t> expected, seen;
  for (std::size_t i = 0; i < shapes.size(); ++i)
    if (scene.drawn(shapes[i])) expected.insert(i);
  std::size_t meshes = 0;
  for (const json& d : drawn) {
    const long index = d.at("index").get<long>();
    demand(index >= 0 && static_cast<std::size_t>(index) < shapes.size(), "a drawn shape is none of the scene's: " + d.dump());
    const json& s = shapes[static_cast<std::size_t>(index)];
    const std::string name = s.value("name", "?");
    demand(expected.count(static_cast<std::size_t>(index)) != 0, "shape " + name + " is drawn, but the page cannot draw it");
    demand(seen.insert(static_cast<std::size_t>(index)).second, "shape " + name + " is drawn twice");
    demand(d.at("name") == s.at("name") && d.at("kind") == s.at("kind"), "shape " + name + " is drawn as " + d.dump());
    demand(d.at("visible").get<bool>(), "shape " + name + " is hidden");
    if (s.at("kind") == "rod") continue;
    expect_near(vec(d.at("position"), "a shape's position"), scene.shape_point(s, t), 1e-6 * scene.scale,
                fmt::format("shape {}'s place at t = {}", name, t));
    const json& q = d.at("quaternion");
    demand(q.is_array() && q.size() == 4, "shape " + name + "'s attitude is no quaternion: " + q.dump());
    const double x = q[0].get<double>(), y = q[1].get<double>(), z = q[2].get<double>(), w = q[3].get<double>();
    const Mat3 turned = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                         2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                         2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
    const Mat3 expected_turn = scene.rotation_at(s.contains("frame") ? s["frame"] : json(-1), t);
    for (std::size_t i = 0; i < 9; ++i)
      expect_near(turned[i], expected_turn[i], 0.02, fmt::format("shape {}'s attitude at t = {}, entry {} of its rotation", name, t, i));
    if (const Mesh* m = scene.mesh_of(s); m != nullptr) {
      demand(d.at("vertices").get<std::size_t>() == 3 * m->triangles,
             fmt::format("mesh shape {} is drawn with {} vertices, not 3 x {} triangles", name, d.at("vertices").dump(), m->triangles));
      ++meshes;
    }
  }
  demand(seen == expected, fmt::format("the page draws {} of the scene's {} drawable shapes", seen.size(), expected.size()));
  std::cout << fmt::format("ok: at t = {} the {} shapes ({} meshes) are drawn at their points, turned with their frames\n", t,
                           seen.size(), meshes);
}

int run(int argc, char** argv) {
  std::string follow;
  int first = 1;
  if (argc > 2 && std::string(argv[1]) == "--follow") follow = argv[2], first = 3;
  if (argc - first < 2) {
    std::cerr << "usage: check_view [--follow CHOICE] PAGE.html STATUS.json...\n";
    return 2;
  }
  const Scene scene = load_scene(argv[first]);
  std::vector<json> views;
  std::vector<double> times;
  const std::size_t missing = scene.data.value("missing_meshes", json::array()).size();
  for (int i = first + 1; i < argc; ++i) {
    const json status = status_of(read_file(argv[i]));
    demand(status.contains("view") && status["view"].is_object(), std::string("no view in the status ") + argv[i]);
    views.push_back(status["view"]);
    times.push_back(status.at("t").get<double>());
    // the page says how many meshes it could not draw
    demand(status.value("missingMeshes", -1) == static_cast<long>(missing),
           fmt::format("the page says {} meshes are not drawn, the scene {}", status.value("missingMeshes", -1), missing));
  }
  for (std::size_t i = 0; i < views.size(); ++i) check_shapes(scene, views[i].at("shapes"), times[i]);
  if (missing > 0) std::cout << fmt::format("ok: the page says the scene's {} meshes are not drawn\n", missing);

  // the camera's choices: the whole run first (the default), the mechanism, and every body drawn at a point
  std::vector<std::string> bodies;
  for (const json& s : scene.data.value("shapes", json::array()))
    if (scene.drawn(s) && s.contains("body") && s["body"].is_string()) bodies.push_back(s["body"].get<std::string>());
  for (const json& p : scene.data.value("particles", json::array())) bodies.push_back(p.at("name").get<std::string>());
  for (std::size_t i = 0; i < views.size(); ++i) {
    const json& view = views[i];
    const json& choices = view.at("choices");
    demand(choices.is_array() && choices.size() >= 2 && choices[0] == "" && choices[1] == "mechanism",
           "the camera's choices do not begin with the whole run and the mechanism: " + choices.dump());
    for (const std::string& body : bodies)
      demand(std::find(choices.begin(), choices.end(), json("body:" + body)) != choices.end(),
             "the camera cannot follow body " + body + ": " + choices.dump());
    demand(view.at("follow") == follow && view.at("choice") == follow,
           fmt::format("the camera's choice is {} (the select says {}), not \"{}\"", view.at("follow").dump(), view.at("choice").dump(), follow));
    check_camera(view.at("camera"), view.at("canvas"), scene.scale);
  }
  std::cout << fmt::format("ok: the camera's choice is \"{}\" at t = {}; the reported matrices are the camera's\n", follow,
                           fmt::join(times, ", "));

  check_grid(scene, views.front().at("grid"));
  const std::vector<Vec> tips = check_axes(views.front().at("axes"), scene.scale);

  const json& first_camera = views.front().at("camera");
  const Mat projection = mat(first_camera.at("projection"), "the projection");
  const Mat view = mat(first_camera.at("view"), "the view matrix");
  if (follow.empty()) {
    // a fixed camera: the same at every time, with every point of every sample in the view
    for (std::size_t i = 1; i < views.size(); ++i) {
      const json& c = views[i].at("camera");
      expect_near(vec(c.at("position"), "position"), vec(first_camera.at("position"), "position"), 1e-9 * scene.scale,
                  fmt::format("the camera's position at t = {}, against t = {}", times[i], times[0]));
      expect_near(vec(c.at("target"), "target"), vec(first_camera.at("target"), "target"), 1e-9 * scene.scale,
                  fmt::format("the camera's target at t = {}, against t = {}", times[i], times[0]));
    }
    std::size_t count = 0;
    double reach = 0;
    for (std::size_t p = 0; p < scene.positions.size(); ++p) {
      for (std::size_t k = 0; k < scene.positions[p].size() / 3; ++k) {
        const Projected q = project(projection, view, scene.sample(p, k));
        demand(inside(q), fmt::format("point {} ({}) at t = {} ({}) is outside the initial view: ndc ({:.4f}, {:.4f}, {:.4f})", p,
                                      scene.data["points"][p].value("name", "?"), scene.times[k], str(scene.sample(p, k)), q.x, q.y, q.z));
        reach = std::max({reach, std::abs(q.x), std::abs(q.y)});
        ++count;
      }
    }
    for (const Vec& tip : tips) demand(inside(project(projection, view, tip)), "an axis's tip " + str(tip) + " is outside the view");
    // and every corner of every box and of every mesh's box, at every sample
    std::size_t corners = 0;
    for (const json& s : scene.data.value("shapes", json::array())) {
      const std::vector<Vec> local = scene.corners(s);
      for (std::size_t k = 0; k < scene.samples() && !local.empty(); ++k) {
        const Mat3 r = scene.rotation(s.contains("frame") ? s["frame"] : json(-1), k);
        for (const Vec& c : local) {
          const Vec p = scene.shape_point(s, scene.times[k]) + apply(r, c);
          const Projected q = project(projection, view, p);
          demand(inside(q), fmt::format("a corner of shape {} ({}) at t = {} is outside the initial view: ndc ({:.4f}, {:.4f}, {:.4f})",
                                        s.value("name", "?"), str(p), scene.times[k], q.x, q.y, q.z));
          ++corners;
        }
      }
    }
    // when the points, not the shapes about them, make the run's size, they fill the view
    if (count > 0 && scene.scale >= 2 * scene.largest_shape)
      demand(reach >= 0.35, fmt::format("the run fills only {:.3f} of the view's half-width or half-height", reach));
    std::cout << fmt::format("ok: a fixed camera; all {} positions ({} points x {} samples), {} corners of boxes and meshes' boxes "
                             "and the axes' tips inside the view, reaching {:.3f} of it from its centre\n",
                             count, scene.positions.size(), scene.samples(), corners, reach);
    return 0;
  }

  // a following camera: at each time it looks at the followed point from the same offset, and the
  // moving points at that time are inside the view
  // the moving points the page names: each that moves, none that stays (unless nothing moves)
  std::vector<std::size_t> moving;
  bool anything_moves = false;
  for (std::size_t p = 0; p < scene.positions.size(); ++p) anything_moves = anything_moves || (!scene.positions[p].empty() && scene.travel(p) > 0);
  for (std::size_t p = 0; p < scene.positions.size(); ++p) {
    const double travel = scene.positions[p].empty() ? 0 : scene.travel(p);
    const json& named = views.front().at("moving");
    const bool said = std::find(named.begin(), named.end(), json(p)) != named.end();
    if (travel > 1e-6 * scene.scale) demand(said, fmt::format("point {} moves {:.4g} but is not named moving", p, travel));
    if (travel == 0 && anything_moves) demand(!said, fmt::format("point {} does not move but is named moving", p));
    if (said) moving.push_back(p);
  }
  Vec offset{0, 0, 0};
  for (std::size_t i = 0; i < views.size(); ++i) {
    const json& c = views[i].at("camera");
    const Vec target = vec(c.at("target"), "target"), position = vec(c.at("position"), "position");
    expect_near(target, followed(scene, follow, views[i].at("moving"), times[i]), 1e-6 * scene.scale,
                fmt::format("the camera's target at t = {}", times[i]));
    if (i == 0) offset = position - target;
    expect_near(position - target, offset, 1e-6 * scene.scale, fmt::format("the camera's offset from its target at t = {}", times[i]));
    const Mat p = mat(c.at("projection"), "the projection"), v = mat(c.at("view"), "the view matrix");
    for (const std::size_t m : moving) {
      const Projected q = project(p, v, scene.at(m, times[i]));
      demand(inside(q), fmt::format("moving point {} at t = {} is outside the following view: ndc ({:.4f}, {:.4f})", m, times[i], q.x, q.y));
    }
    std::cout << fmt::format("ok: at t = {} the camera looks at {} from {}; the {} moving points are inside the view\n", times[i],
                             str(target), str(offset), moving.size());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const Failure& e) {
    std::cerr << "FAIL: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "FAIL: " << e.what() << "\n";
  }
  return 1;
}
