// Writes animation pages of synthetic scenes for the browser test (check_page.sh), until
// `eomgen simulate --animate` writes them from simulations:
//
//   write_test_page double_pendulum|pendulum_without_ground|travelling|mesh|broken_meshes|single_sample|empty|hostile_names OUT.html
//
// double_pendulum: 10 s, 1,000 samples of a double pendulum's kinematics at prescribed angles
// (theta1 = 0.9 cos(1.2 pi t), theta2 = 1.2 sin(1.8 pi t + 0.3)), with a shape of every kind but a mesh,
// two particles, a constraint force, a ground plane and the coordinates' and energies' series.
// pendulum_without_ground: the same without the ground plane. travelling: 10 s of a cart with a
// pendulum that travels 20 m, without gravity. mesh: 10 s of an arm and a forearm swinging in
// three dimensions, drawn with STL-like meshes (a bar of 12 triangles both draw, reaching beyond
// their points, and a tetrahedron), with a mesh not drawn. broken_meshes: meshes the page cannot
// draw (not base64, too short, not finite, no such mesh) beside one it can, and hostile names in
// the meshes not drawn. The others are the edge cases: one sample, nothing but times, and names
// that try to end the page's script elements.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "eomgen/report/animation_page.hpp"

namespace {

constexpr double pi = 3.14159265358979323846;

// numbers as the scene writes them: six significant digits are a tenth of a millimetre on a
// 1 m mechanism, well below a pixel
std::string numbers(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += fmt::format("{}{:.6g}", i == 0 ? "" : ",", values[i]);
  return out + "]";
}

struct Kinematics {
  std::vector<double> t, theta1, theta2, rot_b, rot_c, pivot, p1, p2, g2, force, T, V;
};

// frame b along rod 1 (b.1 down the rod at theta = 0), c along rod 2; angles from the downward
// vertical, y up: the columns of the matrix are b.1 = (sin a, -cos a, 0), b.2 = (cos a, sin a, 0), b.3 = z
void append_rotation(std::vector<double>& r, double a) {
  const double s = std::sin(a), c = std::cos(a);
  r.insert(r.end(), {s, c, 0, -c, s, 0, 0, 0, 1});
}

Kinematics double_pendulum(int n, double t_end) {
  const double l1 = 1.0, l2 = 0.8, m1 = 1.0, m2 = 0.7, g = 9.81;
  Kinematics k;
  for (int i = 0; i < n; ++i) {
    const double t = n > 1 ? t_end * i / (n - 1) : 0.0;
    const double a = 0.9 * std::cos(1.2 * pi * t), b = 1.2 * std::sin(1.8 * pi * t + 0.3);
    const double ad = -0.9 * 1.2 * pi * std::sin(1.2 * pi * t), bd = 1.2 * 1.8 * pi * std::cos(1.8 * pi * t + 0.3);
    k.t.push_back(t);
    k.theta1.push_back(a);
    k.theta2.push_back(b);
    append_rotation(k.rot_b, a);
    append_rotation(k.rot_c, a + b);
    const double x1 = l1 * std::sin(a), y1 = -l1 * std::cos(a);
    const double x2 = x1 + l2 * std::sin(a + b), y2 = y1 - l2 * std::cos(a + b);
    k.pivot.insert(k.pivot.end(), {0, 0, 0});
    k.p1.insert(k.p1.end(), {x1, y1, 0});
    k.p2.insert(k.p2.end(), {x2, y2, 0});
    k.g2.insert(k.g2.end(), {0.5 * (x1 + x2), 0.5 * (y1 + y2), 0});
    k.force.insert(k.force.end(), {6 * std::sin(a), (m1 + m2) * g + 4 * std::cos(2 * a), 0});
    // the particles' energies at these velocities
    const double v1x = l1 * std::cos(a) * ad, v1y = l1 * std::sin(a) * ad;
    const double v2x = v1x + l2 * std::cos(a + b) * (ad + bd), v2y = v1y + l2 * std::sin(a + b) * (ad + bd);
    k.T.push_back(0.5 * m1 * (v1x * v1x + v1y * v1y) + 0.5 * m2 * (v2x * v2x + v2y * v2y));
    k.V.push_back(m1 * g * y1 + m2 * g * y2);
  }
  return k;
}

std::string double_pendulum_scene(int n, double t_end, const std::string& model, const std::string& description,
                                  bool ground = true) {
  const Kinematics k = double_pendulum(n, t_end);
  std::vector<double> total(k.T.size());
  for (std::size_t i = 0; i < total.size(); ++i) total[i] = k.T[i] + k.V[i];
  std::string s = "{\"format\": 1";
  s += fmt::format(", \"model\": \"{}\", \"description\": \"{}\", \"source\": \"double_pendulum.eom\"", model, description);
  s += ", \"times\": " + numbers(k.t) + ", \"up\": [0, 1, 0]";
  s += ", \"frames\": [{\"name\": \"b\", \"body\": \"rod1\", \"rotations\": " + numbers(k.rot_b) + "}";
  s += ", {\"name\": \"c\", \"body\": \"rod2\", \"rotations\": " + numbers(k.rot_c) + "}]";
  s += ", \"points\": [{\"name\": \"O\", \"positions\": " + numbers(k.pivot) + "}";
  s += ", {\"name\": \"p1\", \"positions\": " + numbers(k.p1) + "}";
  s += ", {\"name\": \"p2\", \"positions\": " + numbers(k.p2) + "}";
  s += ", {\"name\": \"g2\", \"positions\": " + numbers(k.g2) + "}]";
  s += ", \"links\": [[0, 1], [1, 2]]";
  s += ", \"shapes\": ["
       "{\"name\": \"rod1\", \"kind\": \"rod\", \"body\": \"rod1\", \"frame\": 0, \"at\": 0, \"to\": 1, \"radius\": 0.02, \"inferred\": false}, "
       "{\"name\": \"rod2\", \"kind\": \"rod\", \"body\": \"rod2\", \"frame\": 1, \"at\": 1, \"to\": 2, \"radius\": 0.015, \"inferred\": false}, "
       "{\"name\": \"support\", \"kind\": \"box\", \"body\": null, \"frame\": -1, \"at\": 0, \"size\": [0.4, 0.06, 0.1], \"inferred\": false}, "
       "{\"name\": \"hub\", \"kind\": \"cylinder\", \"body\": \"rod1\", \"frame\": 0, \"at\": 1, \"radius\": 0.04, \"length\": 0.12, \"axis\": [0, 0, 1], \"inferred\": false}, "
       "{\"name\": \"bob2\", \"kind\": \"sphere\", \"body\": \"bob2\", \"frame\": 1, \"at\": 2, \"radius\": 0.07, \"inferred\": false}, "
       "{\"name\": \"vane\", \"kind\": \"disk\", \"body\": \"rod2\", \"frame\": 1, \"at\": 2, \"radius\": 0.12, \"length\": 0.01, \"axis\": [1, 0, 0], \"inferred\": false}, "
       "{\"name\": \"rod2_box\", \"kind\": \"box\", \"body\": \"rod2\", \"frame\": 1, \"at\": 3, \"size\": [0.8, 0.05, 0.05], \"inferred\": true}]";
  s += ", \"particles\": [{\"name\": \"bob1\", \"point\": 1, \"mass\": 1}, {\"name\": \"bob2\", \"point\": 2, \"mass\": 0.7}]";
  s += ", \"trails\": [2]";
  s += ", \"forces\": [{\"name\": \"pivot\", \"point\": 0, \"vectors\": " + numbers(k.force) + "}]";
  s += ground ? ", \"ground\": {\"normal\": [0, 1, 0], \"point\": [0, -2, 0]}" : ", \"ground\": null";
  s += ", \"series\": [{\"name\": \"theta1\", \"group\": \"coordinates\", \"values\": " + numbers(k.theta1) + "}";
  s += ", {\"name\": \"theta2\", \"group\": \"coordinates\", \"values\": " + numbers(k.theta2) + "}";
  s += ", {\"name\": \"T\", \"group\": \"energy\", \"values\": " + numbers(k.T) + "}";
  s += ", {\"name\": \"V\", \"group\": \"energy\", \"values\": " + numbers(k.V) + "}";
  s += ", {\"name\": \"T+V\", \"group\": \"energy\", \"values\": " + numbers(total) + "}]";
  return s + "}\n";
}

// ---- meshes as the scene carries them: 9 little-endian float32 per triangle, in base64 ---------

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = bytes.size() - i;
    const unsigned word = static_cast<unsigned>(bytes[i]) << 16 | (left > 1 ? static_cast<unsigned>(bytes[i + 1]) << 8 : 0u) |
                          (left > 2 ? static_cast<unsigned>(bytes[i + 2]) : 0u);
    out += alphabet[(word >> 18) & 63];
    out += alphabet[(word >> 12) & 63];
    out += left > 1 ? alphabet[(word >> 6) & 63] : '=';
    out += left > 2 ? alphabet[word & 63] : '=';
  }
  return out;
}

// the floats' bytes, least significant first whatever this machine's order
std::string little_endian_base64(const std::vector<float>& values) {
  std::vector<unsigned char> bytes;
  for (const float v : values) {
    std::uint32_t word = 0;
    std::memcpy(&word, &v, sizeof word);
    for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<unsigned char>((word >> (8 * b)) & 0xff));
  }
  return base64(bytes);
}

struct TestMesh {
  std::vector<float> vertices;  // 9 per triangle
  std::string entry(const std::string& file) const {
    return fmt::format("{{\"file\": \"{}\", \"triangles\": {}, \"vertices\": \"{}\"}}", file, vertices.size() / 9,
                       little_endian_base64(vertices));
  }
  // the vertices' box, [xmin, ymin, zmin, xmax, ymax, zmax]
  std::string bounds() const {
    std::vector<double> box{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < vertices.size(); ++i)
      box[i % 3] = std::min(box[i % 3], static_cast<double>(vertices[i])), box[3 + i % 3] = std::max(box[3 + i % 3], static_cast<double>(vertices[i]));
    return numbers(box);
  }
};

// a box from lo to hi in 12 triangles, wound outwards
TestMesh box_mesh(const std::array<float, 3>& lo, const std::array<float, 3>& hi) {
  TestMesh m;
  const auto corner = [&](int k) { return std::array<float, 3>{k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]}; };
  // each face's corners in order about its outward normal
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    for (const int k : {f[0], f[1], f[2], f[0], f[2], f[3]}) {
      const std::array<float, 3> c = corner(k);
      m.vertices.insert(m.vertices.end(), c.begin(), c.end());
    }
  }
  return m;
}

// a tetrahedron with one corner at o and edges e along the axes, its triangles wound either way
// (as STL files often are)
TestMesh tetrahedron(const std::array<float, 3>& o, float e) {
  const std::array<float, 3> a = o, b = {o[0] + e, o[1], o[2]}, c = {o[0], o[1] + e, o[2]}, d = {o[0], o[1], o[2] + e};
  TestMesh m;
  for (const auto& v : {a, c, b, a, b, d, a, d, c, c, b, d}) m.vertices.insert(m.vertices.end(), v.begin(), v.end());
  return m;
}

// An arm yawing about a.3 (angle a) from a fixed pivot, a forearm pitching about the arm's
// second axis (angle b) from the elbow; each drawn with the same bar, which reaches 0.8 m behind
// its point; a tetrahedron hanging 0.6 m below the forearm's tip, another at the pivot
// (scenery): the meshes, not the points, reach lowest and furthest back. The hand's mesh is not
// drawn (not STL), its body the box of its mass and inertia instead
std::string mesh_scene(int n, double t_end) {
  const double l1 = 1.0, l2 = 1.0;
  std::vector<double> t, yaw, pitch, rot_a, rot_b, pivot, elbow, tip;
  for (int i = 0; i < n; ++i) {
    const double s = n > 1 ? t_end * i / (n - 1) : 0.0;
    const double a = 0.8 * std::sin(1.3 * s), b = 0.9 * std::sin(2.1 * s + 0.4);
    const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
    t.push_back(s);
    yaw.push_back(a);
    pitch.push_back(b);
    rot_a.insert(rot_a.end(), {ca, -sa, 0, sa, ca, 0, 0, 0, 1});
    rot_b.insert(rot_b.end(), {ca * cb, -sa, ca * sb, sa * cb, ca, sa * sb, -sb, 0, cb});
    pivot.insert(pivot.end(), {0, 0, 0});
    elbow.insert(elbow.end(), {l1 * ca, l1 * sa, 0});
    tip.insert(tip.end(), {l1 * ca + l2 * ca * cb, l1 * sa + l2 * sa * cb, -l2 * sb});
  }
  const TestMesh bar = box_mesh({-0.8f, -0.06f, -0.06f}, {1.0f, 0.06f, 0.06f});
  const TestMesh claw = tetrahedron({0.0f, -0.15f, -0.6f}, 0.6f);
  std::string s = "{\"format\": 1, \"model\": \"mesh_arm\", \"description\": \"An arm and a forearm drawn with meshes\"";
  s += ", \"source\": \"mesh_arm.eom\", \"times\": " + numbers(t) + ", \"up\": [0, 0, 1]";
  s += ", \"frames\": [{\"name\": \"A\", \"body\": \"arm\", \"rotations\": " + numbers(rot_a) + "}";
  s += ", {\"name\": \"B\", \"body\": \"forearm\", \"rotations\": " + numbers(rot_b) + "}]";
  s += ", \"points\": [{\"name\": \"O\", \"positions\": " + numbers(pivot) + "}";
  s += ", {\"name\": \"elbow\", \"positions\": " + numbers(elbow) + "}";
  s += ", {\"name\": \"tip\", \"positions\": " + numbers(tip) + "}]";
  s += ", \"links\": [[0, 1], [1, 2]]";
  s += ", \"shapes\": [";
  s += "{\"name\": \"arm\", \"kind\": \"mesh\", \"body\": \"arm\", \"frame\": 0, \"at\": 0, \"mesh\": 0, \"bounds\": " + bar.bounds() +
       ", \"inferred\": false}, ";
  s += "{\"name\": \"forearm\", \"kind\": \"mesh\", \"body\": \"forearm\", \"frame\": 1, \"at\": 1, \"mesh\": 0, \"bounds\": " +
       bar.bounds() + ", \"inferred\": false}, ";
  s += "{\"name\": \"claw\", \"kind\": \"mesh\", \"body\": \"forearm\", \"frame\": 1, \"at\": 2, \"mesh\": 1, \"bounds\": " +
       claw.bounds() + ", \"inferred\": false}, ";
  s += "{\"name\": \"base\", \"kind\": \"mesh\", \"body\": null, \"frame\": -1, \"at\": 0, \"mesh\": 1, \"bounds\": " +
       claw.bounds() + ", \"inferred\": false}, ";
  s += "{\"name\": \"hand\", \"kind\": \"box\", \"body\": \"hand\", \"frame\": 1, \"at\": 2, \"size\": [0.12, 0.1, 0.08], \"inferred\": true}]";
  s += ", \"meshes\": [" + bar.entry("meshes/bar.stl") + ", " + claw.entry("package://arm/meshes/claw.stl") + "]";
  s += ", \"missing_meshes\": [{\"shape\": \"hand\", \"file\": \"meshes/hand.dae\", \"reason\": \"not STL (a COLLADA file)\"}]";
  s += ", \"particles\": [], \"trails\": [2], \"forces\": [], \"ground\": null";
  s += ", \"series\": [{\"name\": \"a\", \"group\": \"coordinates\", \"values\": " + numbers(yaw) + "}";
  s += ", {\"name\": \"b\", \"group\": \"coordinates\", \"values\": " + numbers(pitch) + "}]";
  return s + "}\n";
}

// Meshes the page cannot draw, each an error it records (the shape drawn nowhere), beside one it
// draws: vertices that are not base64, fewer bytes than the triangles need, a coordinate that is
// not a number, a mesh that does not exist, a broken mesh shared by a second shape. The meshes
// not drawn have names that would run a script or load an image if they were read as HTML.
std::string broken_meshes_scene(int n, double t_end) {
  std::vector<double> t, origin, cart;
  for (int i = 0; i < n; ++i) {
    const double s = n > 1 ? t_end * i / (n - 1) : 0.0;
    t.push_back(s);
    origin.insert(origin.end(), {0, 0, 0});
    cart.insert(cart.end(), {std::sin(3 * s), 0.5 * s, 0.1});
  }
  const TestMesh good = box_mesh({-0.2f, -0.1f, -0.05f}, {0.2f, 0.1f, 0.05f});
  TestMesh one = tetrahedron({0, 0, 0}, 0.1f), not_finite = one;
  one.vertices.resize(9);
  not_finite.vertices.resize(9);
  not_finite.vertices[4] = std::numeric_limits<float>::quiet_NaN();
  const auto shape = [](const std::string& name, const std::string& body, int mesh) {
    return fmt::format("{{\"name\": \"{}\", \"kind\": \"mesh\", \"body\": {}, \"frame\": -1, \"at\": 1, \"mesh\": {}, "
                       "\"bounds\": [-0.1, -0.1, -0.1, 0.1, 0.1, 0.1], \"inferred\": false}}", name, body, mesh);
  };
  std::string s = "{\"format\": 1, \"model\": \"broken_meshes\", \"description\": \"Meshes the page cannot draw\"";
  s += ", \"times\": " + numbers(t) + ", \"up\": [0, 0, 1], \"frames\": []";
  s += ", \"points\": [{\"name\": \"O\", \"positions\": " + numbers(origin) + "}";
  s += ", {\"name\": \"c\", \"positions\": " + numbers(cart) + "}]";
  s += ", \"links\": [[0, 1]]";
  s += ", \"shapes\": [{\"name\": \"good\", \"kind\": \"mesh\", \"body\": \"cart\", \"frame\": -1, \"at\": 1, \"mesh\": 0, "
       "\"bounds\": " + good.bounds() + ", \"inferred\": false}, ";
  s += shape("bad64", "\"wreck\"", 1) + ", " + shape("short", "\"cart\"", 2) + ", " + shape("nan", "null", 3) + ", " +
       shape("nowhere", "\"cart\"", 9) + ", " + shape("shared_bad", "\"wreck\"", 1) + "]";
  s += ", \"meshes\": [" + good.entry("good.stl") + ", {\"file\": \"bad64.stl\", \"triangles\": 1, \"vertices\": \"@@not base64@@\"}";
  s += ", {\"file\": \"short.stl\", \"triangles\": 2, \"vertices\": \"" + little_endian_base64(one.vertices) + "\"}";
  s += ", " + not_finite.entry("nan.stl") + "]";
  s += ", \"missing_meshes\": [{\"shape\": \"</script><img src=x onerror=\\\"document.title='injected'\\\">\", "
       "\"file\": \"<img src=y>.stl\", \"reason\": \"not found (searched: <b>here</b>, & there)\"}, null, "
       "{\"shape\": 7, \"file\": [\"x\"]}]";
  s += ", \"particles\": [], \"trails\": [], \"forces\": [], \"ground\": null, \"series\": []";
  return s + "}\n";
}

// a cart travelling 20 m along a.1 in 10 s, weaving along a.2, with a pendulum swinging about
// a.2 below it, without gravity (up is a.3) and without a ground
std::string travelling_scene(int n, double t_end) {
  std::vector<double> t, swing, rotation, origin, cart, tip;
  for (int i = 0; i < n; ++i) {
    const double s = n > 1 ? t_end * i / (n - 1) : 0.0;
    const double a = 0.8 * std::sin(3 * s), x = 2 * s, y = 0.3 * std::sin(s);
    t.push_back(s);
    swing.push_back(a);
    // the pole's frame turns by a about a.2: its columns are its unit vectors
    rotation.insert(rotation.end(), {std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)});
    origin.insert(origin.end(), {0, 0, 0});
    cart.insert(cart.end(), {x, y, 0.2});
    tip.insert(tip.end(), {x + 0.5 * std::sin(a), y, 0.2 - 0.5 * std::cos(a)});
  }
  std::string s = "{\"format\": 1, \"model\": \"travelling\", \"description\": \"A cart with a pendulum, travelling\"";
  s += ", \"times\": " + numbers(t) + ", \"up\": [0, 0, 1]";
  s += ", \"frames\": [{\"name\": \"p\", \"body\": \"pole\", \"rotations\": " + numbers(rotation) + "}]";
  s += ", \"points\": [{\"name\": \"w\", \"positions\": " + numbers(origin) + "}";
  s += ", {\"name\": \"c\", \"positions\": " + numbers(cart) + "}";
  s += ", {\"name\": \"tip\", \"positions\": " + numbers(tip) + "}]";
  s += ", \"links\": [[1, 2]]";
  s += ", \"shapes\": ["
       "{\"name\": \"body\", \"kind\": \"box\", \"body\": \"cart\", \"frame\": -1, \"at\": 1, \"size\": [0.4, 0.2, 0.1], \"inferred\": false}, "
       "{\"name\": \"pole\", \"kind\": \"rod\", \"body\": \"pole\", \"frame\": 0, \"at\": 1, \"to\": 2, \"radius\": 0.02, \"inferred\": false}]";
  s += ", \"particles\": [{\"name\": \"bob\", \"point\": 2, \"mass\": 1}]";
  s += ", \"trails\": [2], \"forces\": [], \"ground\": null";
  s += ", \"series\": [{\"name\": \"swing\", \"group\": \"coordinates\", \"values\": " + numbers(swing) + "}]";
  return s + "}\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: write_test_page double_pendulum|pendulum_without_ground|travelling|mesh|broken_meshes|single_sample|empty|"
                 "hostile_names OUT.html\n";
    return 2;
  }
  const std::string kind = argv[1];
  std::string title, scene;
  if (kind == "double_pendulum") {
    title = "double_pendulum";
    scene = double_pendulum_scene(1000, 10.0, "double_pendulum", "Planar double pendulum at prescribed angles");
  } else if (kind == "pendulum_without_ground") {
    title = "pendulum_without_ground";
    scene = double_pendulum_scene(1000, 10.0, "pendulum_without_ground", "The double pendulum without a ground", false);
  } else if (kind == "travelling") {
    title = "travelling";
    scene = travelling_scene(1000, 10.0);
  } else if (kind == "mesh") {
    title = "mesh";
    scene = mesh_scene(1000, 10.0);
  } else if (kind == "broken_meshes") {
    title = "broken meshes";
    scene = broken_meshes_scene(50, 1.0);
  } else if (kind == "single_sample") {
    title = "one sample";
    scene = double_pendulum_scene(1, 0.0, "single_sample", "The double pendulum at one instant");
  } else if (kind == "empty") {
    title = "empty";
    scene = "{\"format\": 1, \"model\": \"empty\", \"times\": [0, 1], \"up\": [0, 0, 1], \"frames\": [], \"points\": [], "
            "\"links\": [], \"shapes\": [], \"particles\": [], \"trails\": [], \"forces\": [], \"ground\": null, "
            "\"series\": []}\n";
  } else if (kind == "hostile_names") {
    // a script that ran would set the title; the page must show these as text
    const std::string name = "</script><script>document.title='injected'</script><!--";
    title = name + " & <b>";
    scene = double_pendulum_scene(50, 1.0, name, "<!-- </script> \\\" '");
  } else {
    std::cerr << "write_test_page: unknown scene " << kind << "\n";
    return 2;
  }
  std::ofstream out(argv[2], std::ios::binary);
  out << eomgen::animation_page(title, scene);
  out.close();
  if (!out) {
    std::cerr << "write_test_page: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
