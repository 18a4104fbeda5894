// A Robot written as model text (urdf_import.hpp).
//
// URDF's conventions against ours (docs/conventions.md, docs/robots.md):
// - `<origin rpy="r p y">` gives R = Rz(y) Ry(p) Rx(r), the rotation taking the child's
//   components to the parent's. The DCM of the child relative to the parent is its transpose,
//   C = C1(r) C2(p) C3(y), which is `euler(PARENT, 321, y, p, r)` (C = Ck(T3) Cj(T2) Ci(T1)).
// - A revolute joint turns the child by +q about the axis (an active rotation), so the DCM of
//   the child relative to the joint frame is the passive C_axis(q): `rotate(J, 3, q)` for the
//   axis 0 0 1, `rotate(J, 3, -q)` for 0 0 -1, `axis_angle(J, AXIS, q)` otherwise.
// - An inertia is given about the mass centre in the axes of `<inertial><origin rpy>`; the body
//   is given that frame as its own, so the inertia is written as the file gives it and is
//   rotated exactly by the derivation.
#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "eomgen/base/bounded_read.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "joint_space_inertia.hpp"

namespace eomgen::urdf {
namespace {

// every word the language gives a meaning of its own: a name equal to one gets a `_` appended
const std::set<std::string>& reserved_words() {
  static const std::set<std::string> words{
      "model", "description", "const", "parameter", "coordinate", "input", "frame", "point", "particle", "body",
      "gravity", "force", "moment", "spring", "damper", "torsion", "potential", "generalized_force", "constraint",
      "roll", "wheel", "shape", "independent", "output", "for", "in", "end", "a", "w", "t", "pi", "sin", "cos",
      "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "sqrt", "exp", "log", "abs", "dot", "cross",
      "norm", "unit", "position", "velocity", "angular_velocity", "diag", "transpose", "dcm", "rotate", "euler",
      "axis_angle", "quaternion", "rodrigues", "mrp", "sphere", "box", "cylinder", "disk", "rod", "T", "g"};
  return words;
}

// A URDF name as an identifier of the language: every character other than a letter, a digit
// or `_` becomes `_`, a name that does not begin with a letter or `_` gets `_` in front, and a
// reserved word gets `_` behind.
std::string identifier(const std::string& name) {
  std::string id;
  for (char c : name) id += std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0])) != 0) id = "_" + id;
  if (reserved_words().count(id) != 0) id += "_";
  return id;
}

// text for a comment or a description: one line, printable ASCII, no quote
std::string printable(const std::string& s) {
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    out += u >= 0x20 && u < 0x7f && c != '"' ? c : '?';
  }
  return out;
}

// whether a model file can hold \p s in double quotes: no quote, no control character, UTF-8
bool quotable(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto u = static_cast<unsigned char>(s[i]);
    if (u == '"' || u < 0x20 || u == 0x7f) return false;
    if (u < 0x80) {
      ++i;
      continue;
    }
    // a UTF-8 sequence: its length from the lead byte, then continuation bytes (no overlong
    // two-byte forms; the lexer says the rest)
    const std::size_t length = u >= 0xc2 && u <= 0xdf ? 2 : u >= 0xe0 && u <= 0xef ? 3 : u >= 0xf0 && u <= 0xf4 ? 4 : 0;
    if (length == 0 || i + length > s.size()) return false;
    for (std::size_t k = 1; k < length; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return false;
    i += length;
  }
  return true;
}

// whether the animation can draw a geometry: a box, cylinder or sphere, or an STL mesh
bool drawable(const Visual& v) {
  switch (v.kind) {
    case Visual::Kind::box:
    case Visual::Kind::cylinder:
    case Visual::Kind::sphere: return true;
    case Visual::Kind::mesh: {
      std::string extension = std::filesystem::path(v.mesh).extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return extension == ".stl";
    }
    case Visual::Kind::unsupported: return false;
  }
  EOMGEN_UNREACHABLE("a Visual::Kind outside its enumerators");
}

// What draws a link: its visuals, or its collision geometry where it has visuals, all of them
// meshes that are not STL (a robot's COLLADA visuals beside STL collision meshes), and some
// collision geometry can be drawn.
struct DrawnGeometry {
  const std::vector<Visual>& shapes;
  const char* label;  // the shapes' names: <link>_visual<k> or <link>_collision<k>
};
DrawnGeometry drawn_geometry(const Link& l) {
  const bool meshes_not_stl = !l.visuals.empty() && std::all_of(l.visuals.begin(), l.visuals.end(), [](const Visual& v) {
    return v.kind == Visual::Kind::mesh && !drawable(v);
  });
  if (meshes_not_stl && std::any_of(l.collisions.begin(), l.collisions.end(), drawable)) return {l.collisions, "collision"};
  return {l.visuals, "visual"};
}

// a number as a factor or a list entry: a negative one in parentheses where it follows an operator
std::string factor(const Number& n) { return n.value < 0 ? "(" + n.text + ")" : n.text; }

std::string column(const Triple& v) { return fmt::format("[{}, {}, {}]", v[0].text, v[1].text, v[2].text); }

// the principal axis a unit vector lies along: +-1..3, or 0
int principal_axis(const Triple& axis) {
  int found = 0;
  for (int i = 0; i < 3; ++i) {
    if (axis[static_cast<std::size_t>(i)].is_zero()) continue;
    if (found != 0) return 0;
    found = axis[static_cast<std::size_t>(i)].value > 0 ? i + 1 : -(i + 1);
  }
  return found;
}

// an axis of unit length as written, or normalized (and then written in full precision)
Triple unit_axis(const Triple& axis) {
  const double length = std::hypot(axis[0].value, axis[1].value, axis[2].value);
  if (std::abs(length - 1) <= 1e-12) return axis;
  Triple out;
  for (std::size_t i = 0; i < 3; ++i) {
    const double v = axis[i].value / length;
    out[i] = Number{fmt::format("{}", v), v};
  }
  return out;
}

// An angle as the model writes it: the double nearest to a multiple of pi/4 (what a program
// prints for pi/2) as that multiple of `pi`, so that its sine and cosine are exact (a 0 stays
// 0 in the equations, instead of 6e-17 that costs operations in every call); any other number
// as written (1.57079632679, 4.9e-12 short of pi/2, stays itself).
std::string angle(const Number& a) {
  const double quarters = std::round(a.value / (M_PI / 4));
  if (quarters == 0 || std::abs(quarters) > 64) return a.text;
  const double exact = quarters * (M_PI / 4);
  if (std::abs(a.value - exact) > 4 * std::numeric_limits<double>::epsilon() * std::abs(exact)) return a.text;
  const long q = std::lround(quarters);
  const long g = std::gcd(std::labs(q), 4L);
  const long numerator = q / g, denominator = 4 / g;
  const std::string times = numerator == 1 ? "" : numerator == -1 ? "-" : fmt::format("{}*", numerator);
  return denominator == 1 ? times + "pi" : fmt::format("{}pi/{}", times, denominator);
}

// DCM of a frame turned by `rpy` relative to `parent`: the parent itself, one principal
// rotation, or the 3-2-1 sequence
std::string turned(const std::string& parent, const Triple& rpy) {
  const bool r = !rpy[0].is_zero(), p = !rpy[1].is_zero(), y = !rpy[2].is_zero();
  if (!r && !p && !y) return parent;
  if (r && !p && !y) return fmt::format("rotate({}, 1, {})", parent, angle(rpy[0]));
  if (!r && p && !y) return fmt::format("rotate({}, 2, {})", parent, angle(rpy[1]));
  if (!r && !p && y) return fmt::format("rotate({}, 3, {})", parent, angle(rpy[2]));
  return fmt::format("euler({}, 321, {}, {}, {})", parent, angle(rpy[2]), angle(rpy[1]), angle(rpy[0]));
}

class Writer {
 public:
  Writer(const Robot& robot, const ImportOptions& options) : robot_(robot), options_(options) {
    for (const Link& l : robot.links) links_[l.name] = &l;
    for (const Joint& j : robot.joints) {
      children_[j.parent].push_back(&j);
      parent_joint_[j.child] = &j;
    }
    for (const Link& l : robot.links)
      if (parent_joint_.count(l.name) == 0) root_ = &l;
    // the joints depth first, each before the joints below it, children in file order
    std::vector<const Joint*> stack;
    const auto push_children = [&](const std::string& link) {
      const auto c = children_.find(link);
      if (c != children_.end()) stack.insert(stack.end(), c->second.rbegin(), c->second.rend());
    };
    push_children(root_->name);
    while (!stack.empty()) {
      const Joint* j = stack.back();
      stack.pop_back();
      order_.push_back(j);
      push_children(j->child);
    }
    // links welded to the root do not move: their masses do not enter the equations (none, where
    // the root flies free)
    base_.name = root_->name;
    base_.type = Joint::Type::floating;
    base_.child = root_->name;
    base_.location = base_.axis_location = root_->location;
    if (options_.floating_base) return;
    grounded_.insert(root_->name);
    for (const Joint* j : order_)
      if (j->type == Joint::Type::fixed && grounded_.count(j->parent) != 0) grounded_.insert(j->child);
  }

  ImportResult run() {
    check_masses();
    name_everything();
    header();
    line("parameter g = 9.81  # gravitational acceleration [m/s^2], along -z of the root link");
    line("gravity = -g*a.3");
    root();
    for (const Joint* j : order_) {
      joint(*j);
      child_link(*links_.at(j->child));
    }
    outputs();
    return {out_, repairs_, {}};
  }

 private:
  // ---- names

  // Reserves an identifier for what a part of the file becomes; two parts that meet in one
  // identifier are an error at the second.
  std::string claim(const std::string& id, const std::string& what, const SourceLocation& where) {
    const auto [it, fresh] = claimed_.emplace(id, std::make_pair(what, where));
    if (!fresh)
      throw SourceError(where, fmt::format("{} becomes the name '{}' in the model, which {} (line {}) already has: "
                                           "expected names that stay different once every character other than a "
                                           "letter, a digit or '_' is made '_'",
                                           what, id, it->second.first, it->second.second.line));
    return id;
  }

  void name_everything() {
    // links first: a joint named like a link (URDF keeps them apart) names its coordinate `_q`
    for (const Link& l : robot_.links) {
      const std::string what = fmt::format("link '{}'", printable(l.name));
      const std::string id = claim(identifier(l.name), what, l.location);
      link_id_[l.name] = id;
      claim(id + "_origin", what, l.location);
      if (has_body(l)) {
        claim(id + "_body", what, l.location);
        claim(id + "_com", what, l.location);
        for (const char* p : {"_mass", "_com_x", "_com_y", "_com_z", "_ixx", "_ixy", "_ixz", "_iyy", "_iyz", "_izz"})
          claim(id + p, what, l.location);
        if (l.inertial->origin.turns()) claim(id + "_inertia", what, l.location);
      }
      const DrawnGeometry drawn = drawn_geometry(l);
      for (std::size_t k = 0; k < drawn.shapes.size(); ++k) {
        const std::string v = fmt::format("{}_{}{}", id, drawn.label, k + 1);
        claim(v, what, drawn.shapes[k].location);
        claim(v + "_at", what, drawn.shapes[k].location);
        if (drawn.shapes[k].origin.turns()) claim(v + "_frame", what, drawn.shapes[k].location);
      }
    }
    if (options_.floating_base) {
      const std::string what = fmt::format("the floating base of link '{}'", printable(root_->name));
      for (const char* c : {"_x", "_y", "_z", "_yaw", "_pitch", "_roll"})
        for (const char* d : {"", "_dot", "_ddot"}) claim(link_id_[root_->name] + c + d, what, root_->location);
    }
    std::set<std::string> link_names;
    for (const Link& l : robot_.links) link_names.insert(l.name);
    for (const Joint& j : robot_.joints) {
      const std::string what = fmt::format("joint '{}'", printable(j.name));
      std::string id = identifier(j.name);
      if (link_names.count(j.name) != 0) id += "_q";
      joint_id_[j.name] = id;
      if (j.origin.turns() && j.type != Joint::Type::fixed && j.type != Joint::Type::prismatic)
        claim(id + "_frame", what, j.location);
      for (const std::string& c : coordinate_names(j, id)) {
        claim(c, what, j.location);
        claim(c + "_dot", what, j.location);
        claim(c + "_ddot", what, j.location);
      }
      if (actuated(j)) {
        claim(input_name(j, id), what, j.location);
        claim(id + "_actuator", what, j.location);
      }
      if (damped(j)) {
        claim(id + "_damping", what, j.location);
        claim(id + "_damper", what, j.location);
      }
      if (follows(j)) claim(id + "_mimic", what, j.location);
    }
    for (const Link& l : robot_.links)
      if (children_.count(l.name) == 0)
        for (const char* o : {"_position", "_axis_1", "_axis_2", "_axis_3", "_angular_velocity"})
          claim(link_id_[l.name] + o, fmt::format("the outputs of link '{}'", printable(l.name)), l.location);
  }

  static std::vector<std::string> coordinate_names(const Joint& j, const std::string& id) {
    switch (j.type) {
      case Joint::Type::revolute:
      case Joint::Type::continuous:
      case Joint::Type::prismatic: return {id};
      case Joint::Type::fixed: return {};
      case Joint::Type::planar: return {id + "_x", id + "_y", id + "_theta"};
      case Joint::Type::floating: return {id + "_x", id + "_y", id + "_z", id + "_yaw", id + "_pitch", id + "_roll"};
    }
    return {};
  }
  static bool one_coordinate(const Joint& j) {
    return j.type == Joint::Type::revolute || j.type == Joint::Type::continuous || j.type == Joint::Type::prismatic;
  }
  static bool actuated(const Joint& j) { return one_coordinate(j) && !follows(j); }
  static bool damped(const Joint& j) { return one_coordinate(j) && j.damping && !j.damping->is_zero(); }
  static std::string input_name(const Joint& j, const std::string& id) {
    return id + (j.type == Joint::Type::prismatic ? "_force" : "_torque");
  }
  // a body of the model: a link with mass that moves
  bool has_body(const Link& l) const {
    return l.inertial && l.inertial->mass.value > 0 && grounded_.count(l.name) == 0;
  }
  static bool follows(const Joint& j) { return j.mimic.has_value() && j.type != Joint::Type::fixed; }

  // ---- checks the language would make too late (in the written text) or not at all

  void check_masses() {
    if (!options_.floating_base &&
        std::none_of(robot_.joints.begin(), robot_.joints.end(), [](const Joint& j) { return j.type != Joint::Type::fixed; }))
      throw SourceError(robot_.location,
                        fmt::format("robot '{}' has no joint that moves: its root link is fixed to the ground, and "
                                    "with it every link: expected a joint that is not fixed (a free-flying robot "
                                    "needs --floating-base, or a floating joint from a world link to its base)", printable(robot_.name)));
    for (const Link& l : robot_.links) {
      if (!l.inertial || grounded_.count(l.name) != 0) continue;  // a grounded link's inertia is never used
      const Inertial& in = *l.inertial;
      const Eigen::Matrix3d J = inertia(in);
      if (in.mass.value == 0) {
        if (J.cwiseAbs().maxCoeff() == 0) continue;
        if (!options_.repair_inertia)
          throw SourceError(in.mass_location,
                            fmt::format("link '{}': the mass is 0 but the inertia is not: expected a positive mass, or "
                                        "both zero for a link that only carries a frame; --repair-inertia sets the "
                                        "inertia to zero", printable(l.name)));
        repairs_.push_back(fmt::format("link '{}': mass 0 with an inertia: the inertia is set to zero (the link only "
                                       "carries a frame)", printable(l.name)));
        continue;
      }
      check_inertia(l, J);
    }
    // a joint that moves no mass has a zero row of the mass matrix (a follower of a mimic is
    // moved by its constraint instead)
    std::set<std::string> moves_mass;  // links with mass at or below them, among the moving ones
    for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
      const Link& child = *links_.at((*it)->child);
      if (has_body(child) || moves_mass.count(child.name) != 0) moves_mass.insert((*it)->parent);
      if (has_body(child)) moves_mass.insert(child.name);
    }
    for (const Joint* j : order_) {
      if (j->type == Joint::Type::fixed || follows(*j) || moves_mass.count(j->child) != 0) continue;
      throw SourceError(j->location, fmt::format("joint '{}' ({}) moves only links without mass ('{}' and what hangs "
                                                 "from it), so its row of the mass matrix is zero: expected a mass "
                                                 "beyond the joint, or a fixed joint (--fix-massless-joints makes "
                                                 "such joints fixed)",
                                                 printable(j->name), type_name(j->type), printable(j->child)));
    }
    // and what moves must resist: a point mass on a joint's own axis, or a motion the joints
    // before it already make, leaves the mass matrix singular at every state
    const auto body = [&](const Link& l) -> std::optional<BodyData> {
      if (!has_body(l)) return std::nullopt;
      const auto repaired = repaired_.find(l.name);
      return BodyData{l.inertial->mass.value, repaired != repaired_.end() ? repaired->second : inertia(*l.inertial)};
    };
    std::vector<const Joint*> joints = order_;
    if (options_.floating_base) joints.insert(joints.begin(), &base_);
    if (const Joint* j = first_singular_joint(robot_, joints, body))
      throw SourceError(j->location,
                        fmt::format("joint '{}' ({}): the mass matrix would be singular at every state: the motion of "
                                    "this joint meets no inertia that the joints before it do not already move (a "
                                    "point mass on its own axis, say): expected an inertia about the joint beyond it, "
                                    "or a fixed joint", printable(j->name), type_name(j->type)));
  }

  static Eigen::Matrix3d inertia(const Inertial& in) {
    Eigen::Matrix3d J;
    J << in.ixx.value, in.ixy.value, in.ixz.value, in.ixy.value, in.iyy.value, in.iyz.value, in.ixz.value,
        in.iyz.value, in.izz.value;
    return J;
  }

  // Principal moments not below zero and each at most the sum of the other two, as the
  // language asks (mechanical_system.cpp, the same tolerance); --repair-inertia raises what
  // falls short instead: negative moments to zero, then the two smaller moments by half the
  // excess of the largest each, so the largest is their sum; the principal axes are kept.
  void check_inertia(const Link& l, const Eigen::Matrix3d& J) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(J);
    Eigen::Vector3d m = eigen.eigenvalues();
    const double tolerance = 1e-12 * std::max(1.0, m.cwiseAbs().maxCoeff());
    const bool negative = m(0) < -tolerance;
    const bool triangle = m(2) > m(0) + m(1) + tolerance;
    if (!negative && !triangle) return;
    const std::string moments = fmt::format("{:.6g}, {:.6g}, {:.6g}", m(0), m(1), m(2));
    const std::string broken = negative ? "a principal moment is negative"
                                        : fmt::format("{:.6g} exceeds the sum of the other two", m(2));
    if (!options_.repair_inertia)
      throw SourceError(l.inertial->inertia_location,
                        fmt::format("link '{}': the inertia has the principal moments {}, and {}: no mass distribution "
                                    "has it (expected each principal moment at least 0 and at most the sum of the "
                                    "other two); --repair-inertia replaces it by the nearest one that is",
                                    printable(l.name), moments, broken));
    for (int i = 0; i < 3; ++i) m(i) = std::max(m(i), 0.0);
    std::sort(m.data(), m.data() + 3);
    const double excess = m(2) - m(0) - m(1);
    if (excess > 0) m(0) += excess / 2, m(1) += excess / 2;
    Eigen::Matrix3d R = eigen.eigenvectors();
    Eigen::Matrix3d repaired = R * m.asDiagonal() * R.transpose();
    repaired = (repaired + repaired.transpose()) / 2;
    repaired_[l.name] = repaired;
    repairs_.push_back(fmt::format("link '{}': inertia with principal moments {} ({}) replaced by one with {:.6g}, "
                                   "{:.6g}, {:.6g} about the same axes",
                                   printable(l.name), moments, broken, m(0), m(1), m(2)));
  }

  // ---- text

  void line(const std::string& s) { out_ += s + "\n"; }

  void header() {
    const std::string base = std::filesystem::path(robot_.file).filename().string();
    line(fmt::format("# Robot '{}', imported by `eomgen import` from {}.", printable(robot_.name), printable(base)));
    line("#");
    line("# Every link is a frame of its name (the root link's is the inertial frame a, z up) with a point");
    line("# <link>_origin at its origin; every joint degree of freedom a coordinate of the joint's name; each");
    line("# link's mass, mass centre and inertia are parameters (<link>_mass, <link>_com_x, <link>_ixx, ...);");
    line("# each actuated joint has an input and a generalized force on its coordinate. Joint limits, efforts,");
    line("# velocities and friction are carried as comments only: the equations do not enforce them.");
    line("# docs/robots.md gives the mapping joint by joint.");
    for (const std::string& r : repairs_) line("# --repair-inertia: " + r);
    line("");
    line(fmt::format("model {} \"{} (imported from {})\"", identifier(robot_.name), printable(robot_.name),
                     printable(base)));
    line("");
  }

  void root() {
    const Link& l = *root_;
    if (options_.floating_base) {
      const std::string& id = link_id_[l.name];
      line(fmt::format("# link '{}' (the root, flying free: --floating-base): moved by x, y, z along a's axes and "
                       "turned by the", printable(l.name)));
      line("# 3-2-1 (yaw, pitch, roll) Euler angles, singular at pitch = +-pi/2 (docs/robots.md)");
      line(fmt::format("coordinate {0}_x, {0}_y, {0}_z, {0}_yaw, {0}_pitch, {0}_roll", id));
      line(fmt::format("frame {0} = euler(a, 321, {0}_yaw, {0}_pitch, {0}_roll)", id));
      line(fmt::format("point {0}_origin = w + {0}_x*a.1 + {0}_y*a.2 + {0}_z*a.3", id));
      child_link(l, /*heading=*/false);
      return;
    }
    line(fmt::format("# link '{}' (the root: fixed to the inertial frame a)", printable(l.name)));
    line(fmt::format("frame {} = a", link_id_[l.name]));
    line(fmt::format("point {}_origin = w", link_id_[l.name]));
    grounded_mass(l);
    shapes(l);
    line("");
  }

  void grounded_mass(const Link& l) {
    if (l.inertial && l.inertial->mass.value > 0)
      line(fmt::format("# its mass ({}) is fixed to the ground: it does not enter the equations", l.inertial->mass.text));
  }

  void joint(const Joint& j) {
    const std::string& id = joint_id_[j.name];
    const std::string& parent = link_id_[j.parent];
    const std::string& child = link_id_[j.child];
    line(fmt::format("# joint '{}' ({}): {} -> {}", printable(j.name), type_name(j.type), parent, child));
    if (j.locked) line("#   moves only links without mass: made fixed at its zero position (--fix-massless-joints)");
    std::string limits;
    if (j.lower) limits += " lower " + j.lower->text;
    if (j.upper) limits += " upper " + j.upper->text;
    if (j.effort) limits += " effort " + j.effort->text;
    if (j.velocity) limits += " velocity " + j.velocity->text;
    if (!limits.empty()) line("#   limit:" + limits + " (not enforced)");
    if (j.friction && !j.friction->is_zero()) line("#   friction " + j.friction->text + " (not modelled)");
    // the joint frame: the child's frame at zero motion (the child's own where the joint does
    // not turn it)
    std::string joint_frame = parent;
    const bool turns_child = j.type != Joint::Type::fixed && j.type != Joint::Type::prismatic;
    if (j.origin.turns() && !turns_child) joint_frame = turned(parent, j.origin.rpy);
    if (j.origin.turns() && turns_child) {
      joint_frame = id + "_frame";
      line(fmt::format("frame {} = {}", joint_frame, turned(parent, j.origin.rpy)));
    }
    const std::string offset = j.origin.translates() ? fmt::format(" + {} in {}", column(j.origin.xyz), parent) : "";
    const Triple axis = unit_axis(j.axis);
    const int principal = principal_axis(axis);
    switch (j.type) {
      case Joint::Type::revolute:
      case Joint::Type::continuous: {
        line(fmt::format("coordinate {}", id));
        if (principal != 0)
          line(fmt::format("frame {} = rotate({}, {}, {}{})", child, joint_frame, std::abs(principal),
                           principal < 0 ? "-" : "", id));
        else
          line(fmt::format("frame {} = axis_angle({}, {}, {})", child, joint_frame, column(axis), id));
        line(fmt::format("point {}_origin = {}_origin{}", child, parent, offset));
        break;
      }
      case Joint::Type::prismatic: {
        line(fmt::format("coordinate {}", id));
        line(fmt::format("frame {} = {}", child, joint_frame));
        const std::string along = principal != 0 ? fmt::format("{} {}*{}.{}", principal < 0 ? "-" : "+", id, child,
                                                               std::abs(principal))
                                                 : fmt::format("+ {}*{} in {}", id, column(axis), child);
        line(fmt::format("point {}_origin = {}_origin{} {}", child, parent, offset, along));
        break;
      }
      case Joint::Type::fixed:
        line(fmt::format("frame {} = {}", child, joint_frame));
        line(fmt::format("point {}_origin = {}_origin{}", child, parent, offset));
        break;
      case Joint::Type::planar: {
        if (principal == 0)
          throw SourceError(j.axis_location, fmt::format("joint '{}' (planar): the axis {} is not along x, y or z of "
                                                         "the joint frame: expected a principal axis (turn the joint's "
                                                         "origin instead)", printable(j.name), column(j.axis)));
        const int k = std::abs(principal);
        const int u = k % 3 + 1, v = (k + 1) % 3 + 1;  // the plane's axes, in cyclic order
        line(fmt::format("#   moves in the plane of {}.{} and {}.{} (coordinates _x, _y) and turns about {}.{} (_theta)",
                         joint_frame, u, joint_frame, v, joint_frame, k));
        line(fmt::format("coordinate {}_x, {}_y, {}_theta", id, id, id));
        line(fmt::format("frame {} = rotate({}, {}, {}{}_theta)", child, joint_frame, k, principal < 0 ? "-" : "", id));
        line(fmt::format("point {}_origin = {}_origin{} + {}_x*{}.{} + {}_y*{}.{}", child, parent, offset, id,
                         joint_frame, u, id, joint_frame, v));
        break;
      }
      case Joint::Type::floating:
        line("#   a free body: translations along the joint frame's axes, then the 3-2-1 (yaw, pitch, roll)");
        line("#   Euler angles, singular at pitch = +-pi/2 (docs/robots.md)");
        line(fmt::format("coordinate {0}_x, {0}_y, {0}_z, {0}_yaw, {0}_pitch, {0}_roll", id));
        line(fmt::format("frame {0} = euler({1}, 321, {2}_yaw, {2}_pitch, {2}_roll)", child, joint_frame, id));
        line(fmt::format("point {0}_origin = {1}_origin{2} + {3}_x*{4}.1 + {3}_y*{4}.2 + {3}_z*{4}.3", child, parent,
                         offset, id, joint_frame));
        break;
    }
    if (actuated(j)) {
      const std::string input = input_name(j, id);
      line(fmt::format("input {}", input));
      line(fmt::format("generalized_force {}_actuator(on = {}, value = {})", id, id, input));
    }
    if (damped(j)) {
      line(fmt::format("parameter {}_damping = {}", id, j.damping->text));
      line(fmt::format("damper {}_damper(on = {}, damping = {}_damping)", id, id, id));
    }
    if (j.mimic && !follows(j))
      line(fmt::format("#   mimics '{}' (multiplier {}, offset {}): a fixed joint moves nothing, so the mimic is not "
                       "modelled", printable(j.mimic->joint), j.mimic->multiplier.text, j.mimic->offset.text));
    if (follows(j)) {
      const std::string& leader = joint_id_.at(j.mimic->joint);
      std::string right = j.mimic->multiplier.value == 1 ? leader : factor(j.mimic->multiplier) + "*" + leader;
      if (!j.mimic->offset.is_zero())
        right += j.mimic->offset.value < 0 ? " - " + j.mimic->offset.text.substr(1) : " + " + j.mimic->offset.text;
      line(fmt::format("constraint {}_mimic: {} = {}", id, id, right));
    }
  }

  void child_link(const Link& l, bool heading = true) {
    const std::string& id = link_id_[l.name];
    if (heading) line(fmt::format("# link '{}'", printable(l.name)));
    if (has_body(l)) {
      const Inertial& in = *l.inertial;
      line(fmt::format("parameter {}_mass = {}", id, in.mass.text));
      // the mass centre and the inertia as parameters, but for the entries the file gives as 0:
      // those stay 0 in the equations, where a parameter would cost operations in every call
      std::vector<std::string> zeros;
      const auto value = [&](const std::string& name, const std::string& text, double v) {
        if (v == 0) {
          zeros.push_back(name);
          return std::string("0");
        }
        line(fmt::format("parameter {}_{} = {}", id, name, text));
        return fmt::format("{}_{}", id, name);
      };
      const char* axes[] = {"x", "y", "z"};
      std::array<std::string, 3> com;
      for (std::size_t i = 0; i < 3; ++i)
        com[i] = value(std::string("com_") + axes[i], in.origin.xyz[i].text, in.origin.xyz[i].value);
      const auto repaired = repaired_.find(l.name);
      const auto entry = [&](const char* name, const Number& n, int r, int c) {
        if (repaired == repaired_.end()) return value(name, n.text, n.value);
        const double v = repaired->second(r, c);
        return value(name, fmt::format("{:.17g}", v), v);
      };
      const std::string ixx = entry("ixx", in.ixx, 0, 0), ixy = entry("ixy", in.ixy, 0, 1),
                        ixz = entry("ixz", in.ixz, 0, 2), iyy = entry("iyy", in.iyy, 1, 1),
                        iyz = entry("iyz", in.iyz, 1, 2), izz = entry("izz", in.izz, 2, 2);
      if (!zeros.empty()) {
        std::string list;
        for (const std::string& z : zeros) list += (list.empty() ? "" : ", ") + z;
        line(fmt::format("# 0 in the file, and written 0: {} (make one a parameter to vary it)", list));
      }
      std::string body_frame = id;
      if (in.origin.turns()) {
        body_frame = id + "_inertia";
        line(fmt::format("frame {} = {}  # the axes of the inertia", body_frame, turned(id, in.origin.rpy)));
      }
      const bool centred = com[0] == "0" && com[1] == "0" && com[2] == "0";
      line(centred ? fmt::format("point {0}_com = {0}_origin", id)
                   : fmt::format("point {0}_com = {0}_origin + [{1}, {2}, {3}] in {0}", id, com[0], com[1], com[2]));
      line(fmt::format("body {0}_body(mass = {0}_mass, centre = {0}_com, frame = {1},", id, body_frame));
      line(fmt::format("  inertia = [[{}, {}, {}],", ixx, ixy, ixz));
      line(fmt::format("             [{}, {}, {}],", ixy, iyy, iyz));
      line(fmt::format("             [{}, {}, {}]])", ixz, iyz, izz));
    } else if (grounded_.count(l.name) != 0) {
      grounded_mass(l);
    } else {
      line("# no mass: it only carries a frame");
    }
    shapes(l);
    line("");
  }

  void shapes(const Link& l) {
    const std::string& id = link_id_[l.name];
    const DrawnGeometry drawn = drawn_geometry(l);
    if (&drawn.shapes == &l.collisions)
      for (std::size_t k = 0; k < l.visuals.size(); ++k)
        line(fmt::format("# visual {}: mesh '{}' (not STL, which is all the animation draws: the link is drawn by its "
                         "collision geometry instead)", k + 1, printable(l.visuals[k].mesh)));
    for (std::size_t k = 0; k < drawn.shapes.size(); ++k) {
      const Visual& v = drawn.shapes[k];
      const std::string name = fmt::format("{}_{}{}", id, drawn.label, k + 1);
      if (v.kind == Visual::Kind::mesh && !quotable(v.mesh)) {
        line(fmt::format("# {} {}: mesh '{}' (not drawn: its name has a quote, a control character or a byte that "
                         "is not UTF-8, which a model file cannot quote)", drawn.label, k + 1, printable(v.mesh)));
        continue;
      }
      if (v.kind == Visual::Kind::mesh && std::any_of(v.scale.begin(), v.scale.end(), [](const Number& n) { return n.is_zero(); })) {
        line(fmt::format("# {} {}: mesh '{}' (not drawn: a scale of 0 flattens it)", drawn.label, k + 1, printable(v.mesh)));
        continue;
      }
      if (v.kind == Visual::Kind::unsupported) {
        line(fmt::format("# {} {}: <{}> (not drawn: expected box, cylinder, sphere or mesh)", drawn.label, k + 1, printable(v.mesh)));
        continue;
      }
      std::string frame = id;
      if (v.origin.turns()) {
        frame = name + "_frame";
        line(fmt::format("frame {} = {}", frame, turned(id, v.origin.rpy)));
      }
      std::string at = id + "_origin";
      if (v.origin.translates()) {
        at = name + "_at";
        line(fmt::format("point {} = {}_origin + {} in {}", at, id, column(v.origin.xyz), id));
      }
      const std::string body = has_body(l) ? fmt::format("body = {}_body, ", id) : "";
      const std::string place = fmt::format("at = {}, frame = {}", at, frame);
      switch (v.kind) {
        case Visual::Kind::box:
          line(fmt::format("shape {} = box({}size = {}, {})", name, body, column(v.size), place));
          break;
        case Visual::Kind::cylinder:
          line(fmt::format("shape {} = cylinder({}radius = {}, length = {}, axis = {}.3, {})", name, body, v.radius.text,
                           v.length.text, frame, place));
          break;
        case Visual::Kind::sphere:
          line(fmt::format("shape {} = sphere({}radius = {}, {})", name, body, v.radius.text, place));
          break;
        case Visual::Kind::mesh: {
          const bool unscaled = std::all_of(v.scale.begin(), v.scale.end(), [](const Number& n) { return n.value == 1; });
          line(fmt::format("shape {} = mesh({}file = \"{}\", {}{})", name, body, mesh_path(v.mesh),
                           unscaled ? "" : fmt::format("scale = {}, ", column(v.scale)), place));
          break;
        }
        case Visual::Kind::unsupported:
          break;
      }
    }
  }

  // A mesh's file as the written model names it: a path relative to the URDF becomes one
  // relative to where the model is written (options_.model_directory); package:// and file://
  // names, and absolute paths, stay as written (docs/robots.md, "Meshes").
  std::string mesh_path(const std::string& file) const {
    namespace fs = std::filesystem;
    if (options_.model_directory.empty() || file.find("://") != std::string::npos || fs::path(file).is_absolute())
      return file;
    const fs::path absolute = (fs::absolute(fs::path(robot_.file)).parent_path() / file).lexically_normal();
    const fs::path relative = absolute.lexically_relative(fs::absolute(options_.model_directory).lexically_normal());
    const std::string text = (relative.empty() ? absolute : relative).generic_string();
    return quotable(text) ? text : file;
  }

  void outputs() {
    line("# the pose of every leaf link (the tool frames): its origin, its axes in a, and its angular");
    line("# velocity in a (the header's output_jacobian_* of these are the tool's task-space Jacobians)");
    for (const Link& l : robot_.links) {
      if (children_.count(l.name) != 0 || &l == root_) continue;
      const std::string& id = link_id_[l.name];
      line(fmt::format("output {0}_position = position({0}_origin)", id));
      for (int i = 1; i <= 3; ++i) line(fmt::format("output {0}_axis_{1} = {0}.{1}", id, i));
      line(fmt::format("output {0}_angular_velocity = angular_velocity({0})", id));
    }
  }

  const Robot& robot_;
  const ImportOptions& options_;
  const Link* root_ = nullptr;
  std::map<std::string, const Link*> links_;
  std::map<std::string, std::vector<const Joint*>> children_;
  std::map<std::string, const Joint*> parent_joint_;
  std::map<std::string, std::string> link_id_, joint_id_;
  std::map<std::string, std::pair<std::string, SourceLocation>> claimed_;
  std::map<std::string, Eigen::Matrix3d> repaired_;
  std::vector<std::string> repairs_;
  std::vector<const Joint*> order_;  // depth first
  Joint base_;                       // the root's floating joint (floating_base), parent ""
  std::set<std::string> grounded_;   // links welded to the root
  std::string out_;
};

}  // namespace

// The robot with the moving joints that move no mass made fixed, each said in `notes`.
Robot with_massless_joints_locked(Robot robot, std::vector<std::string>& notes) {
  std::map<std::string, std::vector<Joint*>> children;
  for (Joint& j : robot.joints) children[j.parent].push_back(&j);
  std::map<std::string, bool> massive;  // a link with mass at or below it
  for (const Link& l : robot.links) massive[l.name] = l.inertial && l.inertial->mass.value > 0;
  // the joints below a link before the link's own (read_robot refused cycles), so one sweep
  // carries every mass up to the root
  std::vector<const Joint*> postorder;
  {
    std::set<std::string> children_of_joints;
    for (const Joint& j : robot.joints) children_of_joints.insert(j.child);
    std::vector<std::pair<std::string, bool>> stack;
    for (const Link& l : robot.links)
      if (children_of_joints.count(l.name) == 0) stack.emplace_back(l.name, false);
    std::map<std::string, const Joint*> parent_joint;
    for (const Joint& j : robot.joints) parent_joint[j.child] = &j;
    while (!stack.empty()) {
      auto [link, expanded] = stack.back();
      stack.pop_back();
      if (expanded) {
        const auto p = parent_joint.find(link);
        if (p != parent_joint.end()) postorder.push_back(p->second);
        continue;
      }
      stack.emplace_back(link, true);
      for (const Joint* j : children[link]) stack.emplace_back(j->child, false);
    }
  }
  for (const Joint* j : postorder)
    if (massive[j->child]) massive[j->parent] = true;
  std::set<std::string> locked;
  for (Joint& j : robot.joints) {
    if (j.type == Joint::Type::fixed || massive[j.child]) continue;
    notes.push_back(fmt::format("joint '{}' ({}) moves only links without mass: made fixed at its zero position",
                                printable(j.name), type_name(j.type)));
    j.type = Joint::Type::fixed;
    j.locked = true;
    locked.insert(j.name);
  }
  for (const Joint& j : robot.joints)
    if (j.mimic && j.type != Joint::Type::fixed && locked.count(j.mimic->joint) != 0)
      throw SourceError(j.mimic->location, fmt::format("joint '{}' mimics '{}', which moves no mass and is made fixed: "
                                                       "expected the joint it follows to move a mass, or no mimic",
                                                       printable(j.name), printable(j.mimic->joint)));
  return robot;
}

ImportResult write_model(const Robot& robot, const ImportOptions& options) {
  if (!options.fix_massless_joints) return Writer(robot, options).run();
  std::vector<std::string> notes;
  const Robot locked = with_massless_joints_locked(robot, notes);
  ImportResult result = Writer(locked, options).run();
  result.locked = std::move(notes);
  return result;
}

bool is_urdf_path(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".urdf";
}

ImportResult import_urdf(const std::string& path, const ImportOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: error: cannot read the URDF file", path));
  const std::string text = read_at_most(in, max_urdf_bytes);
  if (in.bad()) throw Error(fmt::format("{}: error: cannot read the URDF file", path));
  return write_model(read_robot(text, path), options);
}

}  // namespace eomgen::urdf
