// Writes animation pages of synthetic scenes for the browser test (check_page.sh), until
// `eomgen simulate --animate` writes them from simulations:
//
//   write_test_page double_pendulum|pendulum_without_ground|travelling|single_sample|empty|hostile_names OUT.html
//
// double_pendulum: 10 s, 1,000 samples of a double pendulum's kinematics at prescribed angles
// (theta1 = 0.9 cos(1.2 pi t), theta2 = 1.2 sin(1.8 pi t + 0.3)), with a shape of every kind,
// two particles, a constraint force, a ground plane and the coordinates' and energies' series.
// pendulum_without_ground: the same without the ground plane. travelling: 10 s of a cart with a
// pendulum that travels 20 m, without gravity. The others are the edge cases: one sample,
// nothing but times, and names that try to end the page's script elements.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
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
    std::cerr << "usage: write_test_page double_pendulum|pendulum_without_ground|travelling|single_sample|empty|hostile_names OUT.html\n";
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
