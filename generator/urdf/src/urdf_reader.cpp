// Reading a URDF file into a Robot (urdf_robot.hpp), with tinyxml2.
#include <tinyxml2.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "eomgen/base/error.hpp"
#include "eomgen/urdf/urdf_robot.hpp"

namespace eomgen::urdf {
namespace {

using tinyxml2::XMLElement;

// Places in the text. tinyxml2 gives an element's line; the column is that of its `<name` on
// the line, and an attribute's that of its name inside the element's start tag.
class Places {
 public:
  Places(const std::string& text, std::string file) : text_(text), file_(std::move(file)) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts_.push_back(i + 1);
  }

  SourceLocation at_offset(std::size_t offset) const {
    std::size_t line = 0;
    while (line + 1 < line_starts_.size() && line_starts_[line + 1] <= offset) ++line;
    return {file_, static_cast<int>(line + 1), static_cast<int>(offset - line_starts_[line] + 1)};
  }
  SourceLocation at_line(int line) const { return {file_, line, 1}; }

  SourceLocation of(const XMLElement& e, const char* attribute = nullptr) const {
    const std::size_t start = element_offset(e);
    if (attribute == nullptr || start == std::string::npos) return start == std::string::npos ? at_line(e.GetLineNum()) : at_offset(start);
    const std::size_t end = text_.find('>', start);
    const std::string name = attribute;
    for (std::size_t i = text_.find(name, start); i != std::string::npos && i < end; i = text_.find(name, i + 1)) {
      const bool starts = std::isspace(static_cast<unsigned char>(text_[i - 1])) != 0;
      std::size_t j = i + name.size();
      while (j < text_.size() && std::isspace(static_cast<unsigned char>(text_[j])) != 0) ++j;
      if (starts && j < text_.size() && text_[j] == '=') return at_offset(i);
    }
    return at_offset(start);
  }

 private:
  std::size_t element_offset(const XMLElement& e) const {
    const int line = e.GetLineNum();
    if (line < 1 || static_cast<std::size_t>(line) > line_starts_.size()) return std::string::npos;
    const std::string open = std::string("<") + e.Name();
    // the element starts on its line; several elements of one name may share it
    const std::size_t from = line_starts_[static_cast<std::size_t>(line) - 1];
    std::size_t at = text_.find(open, from);
    for (const XMLElement* s = e.PreviousSiblingElement(e.Name()); s != nullptr && s->GetLineNum() == line;
         s = s->PreviousSiblingElement(e.Name()))
      at = text_.find(open, at + 1);
    return at;
  }

  const std::string& text_;
  std::string file_;
  std::vector<std::size_t> line_starts_;
};

class Reader {
 public:
  Reader(const std::string& text, const std::string& file) : text_(text), places_(text, file) {
    robot_.file = file;
  }

  Robot run() {
    refuse_declarations();
    tinyxml2::XMLDocument document(true, tinyxml2::COLLAPSE_WHITESPACE);
    if (document.Parse(text_.data(), text_.size()) != tinyxml2::XML_SUCCESS)
      throw SourceError(places_.at_line(document.ErrorLineNum()),
                        fmt::format("malformed XML: {}", document.ErrorStr()));
    const XMLElement* root = document.RootElement();
    if (root == nullptr) throw SourceError(places_.at_line(1), "no XML element: expected a <robot> element");
    if (std::string(root->Name()) != "robot")
      throw SourceError(places_.of(*root), fmt::format("the document's element is <{}>: expected <robot>", root->Name()));
    robot_.location = places_.of(*root);
    robot_.name = required(*root, "name");
    for (const XMLElement* e = root->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "link") robot_.links.push_back(link(*e));
      if (tag == "joint") robot_.joints.push_back(joint(*e));
      // <material>, <transmission>, <gazebo> and others say nothing about the dynamics
    }
    check_tree();
    return std::move(robot_);
  }

 private:
  // tinyxml2 expands no entity beyond XML's five and character references, and fetches
  // nothing; a declaration is refused outright so that no reader of the same file does either
  void refuse_declarations() const {
    for (const char* word : {"<!DOCTYPE", "<!ENTITY"}) {
      const std::size_t at = text_.find(word);
      if (at != std::string::npos)
        throw SourceError(places_.at_offset(at),
                          fmt::format("'{}': document type declarations and entities are not read (they could "
                                      "expand without bound or fetch other files): expected a URDF without them",
                                      word + 2));
    }
  }

  std::string required(const XMLElement& e, const char* attribute) const {
    const char* value = e.Attribute(attribute);
    if (value == nullptr)
      throw SourceError(places_.of(e), fmt::format("<{}> has no '{}' attribute", e.Name(), attribute));
    if (*value == '\0')
      throw SourceError(places_.of(e, attribute), fmt::format("<{}>: '{}' is empty", e.Name(), attribute));
    return value;
  }

  Number number(const std::string& word, const SourceLocation& where, const std::string& what) const {
    std::string text = word;
    if (!text.empty() && text[0] == '+') text.erase(0, 1);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    const bool plain = !text.empty() && end == text.c_str() + text.size() && text.find_first_of("xXnNiI") == std::string::npos;
    if (!plain) throw SourceError(where, fmt::format("{}: '{}' is not a number", what, word));
    if (!std::isfinite(value)) throw SourceError(where, fmt::format("{}: '{}' is not finite", what, word));
    // the model language writes the number as given; a form it reads otherwise gets a canonical text
    const bool language_reads_it =
        text.find_first_not_of("0123456789.eE-") == std::string::npos && text.back() != '.' && text.back() != 'e' &&
        text.back() != 'E' && text.find("-.") == std::string::npos && text.find(".e") == std::string::npos &&
        text.find(".E") == std::string::npos;
    return Number{language_reads_it ? text : fmt::format("{}", value), value == 0 ? 0.0 : value};
  }

  Number scalar(const XMLElement& e, const char* attribute, const std::string& what) const {
    return number(required(e, attribute), places_.of(e, attribute), what);
  }
  std::optional<Number> optional_scalar(const XMLElement& e, const char* attribute, const std::string& what) const {
    if (e.Attribute(attribute) == nullptr) return std::nullopt;
    return scalar(e, attribute, what);
  }

  Triple triple(const XMLElement& e, const char* attribute, const std::string& what, Triple fallback) const {
    const char* value = e.Attribute(attribute);
    if (value == nullptr) return fallback;
    std::vector<std::string> words;
    std::string word;
    for (const char* c = value;; ++c) {
      if (*c == '\0' || std::isspace(static_cast<unsigned char>(*c)) != 0) {
        if (!word.empty()) words.push_back(word);
        word.clear();
        if (*c == '\0') break;
      } else {
        word += *c;
      }
    }
    const SourceLocation where = places_.of(e, attribute);
    if (words.size() != 3)
      throw SourceError(where, fmt::format("{}: '{}' has {} numbers: expected three", what, value, words.size()));
    return {number(words[0], where, what), number(words[1], where, what), number(words[2], where, what)};
  }

  Origin origin(const XMLElement& parent, const std::string& what) const {
    Origin o;
    o.location = places_.of(parent);
    if (const XMLElement* e = parent.FirstChildElement("origin")) {
      o.location = places_.of(*e);
      o.xyz = triple(*e, "xyz", what + " origin xyz", o.xyz);
      o.rpy = triple(*e, "rpy", what + " origin rpy", o.rpy);
    }
    return o;
  }

  Link link(const XMLElement& e) {
    Link l;
    l.location = places_.of(e);
    l.name = required(e, "name");
    const std::string what = fmt::format("link '{}'", l.name);
    if (const XMLElement* in = e.FirstChildElement("inertial")) {
      Inertial inertial;
      inertial.location = places_.of(*in);
      inertial.origin = origin(*in, what + ": inertial");
      const XMLElement* mass = in->FirstChildElement("mass");
      if (mass == nullptr) throw SourceError(places_.of(*in), what + ": <inertial> has no <mass>");
      inertial.mass_location = places_.of(*mass, "value");
      inertial.mass = scalar(*mass, "value", what + ": mass");
      if (inertial.mass.value < 0)
        throw SourceError(inertial.mass_location,
                          fmt::format("{}: the mass {} is negative: expected a mass of zero or more", what, inertial.mass.text));
      const XMLElement* inertia = in->FirstChildElement("inertia");
      if (inertia == nullptr) throw SourceError(places_.of(*in), what + ": <inertial> has no <inertia>");
      inertial.inertia_location = places_.of(*inertia);
      inertial.ixx = scalar(*inertia, "ixx", what + ": ixx");
      inertial.ixy = scalar(*inertia, "ixy", what + ": ixy");
      inertial.ixz = scalar(*inertia, "ixz", what + ": ixz");
      inertial.iyy = scalar(*inertia, "iyy", what + ": iyy");
      inertial.iyz = scalar(*inertia, "iyz", what + ": iyz");
      inertial.izz = scalar(*inertia, "izz", what + ": izz");
      l.inertial = inertial;
    }
    for (const XMLElement* v = e.FirstChildElement("visual"); v != nullptr; v = v->NextSiblingElement("visual"))
      if (auto visual = this->visual(*v, what)) l.visuals.push_back(*visual);
    return l;
  }

  std::optional<Visual> visual(const XMLElement& e, const std::string& what) const {
    Visual v;
    v.location = places_.of(e);
    v.origin = origin(e, what + ": visual");
    const XMLElement* geometry = e.FirstChildElement("geometry");
    if (geometry == nullptr) throw SourceError(places_.of(e), what + ": <visual> has no <geometry>");
    const XMLElement* shape = geometry->FirstChildElement();
    if (shape == nullptr) throw SourceError(places_.of(*geometry), what + ": <geometry> is empty");
    const std::string kind = shape->Name();
    const auto positive = [&](const Number& n, const char* attribute) {
      if (n.value <= 0)
        throw SourceError(places_.of(*shape, attribute),
                          fmt::format("{}: the {}'s {} {} is not positive", what, kind, attribute, n.text));
    };
    if (kind == "box") {
      v.kind = Visual::Kind::box;
      v.size = triple(*shape, "size", what + ": box size", {});
      if (shape->Attribute("size") == nullptr) required(*shape, "size");
      for (const Number& n : v.size) positive(n, "size");
    } else if (kind == "cylinder") {
      v.kind = Visual::Kind::cylinder;
      v.radius = scalar(*shape, "radius", what + ": cylinder radius");
      v.length = scalar(*shape, "length", what + ": cylinder length");
      positive(v.radius, "radius");
      positive(v.length, "length");
    } else if (kind == "sphere") {
      v.kind = Visual::Kind::sphere;
      v.radius = scalar(*shape, "radius", what + ": sphere radius");
      positive(v.radius, "radius");
    } else if (kind == "mesh") {
      v.kind = Visual::Kind::mesh;
      v.mesh = required(*shape, "filename");
    } else {
      throw SourceError(places_.of(*shape), fmt::format("{}: unknown geometry <{}>: expected box, cylinder, sphere "
                                                        "or mesh", what, kind));
    }
    return v;
  }

  Joint joint(const XMLElement& e) {
    Joint j;
    j.location = places_.of(e);
    j.name = required(e, "name");
    const std::string what = fmt::format("joint '{}'", j.name);
    static const std::map<std::string, Joint::Type> types{
        {"revolute", Joint::Type::revolute}, {"continuous", Joint::Type::continuous},
        {"prismatic", Joint::Type::prismatic}, {"fixed", Joint::Type::fixed},
        {"floating", Joint::Type::floating}, {"planar", Joint::Type::planar}};
    const std::string type = required(e, "type");
    const auto found = types.find(type);
    if (found == types.end())
      throw SourceError(places_.of(e, "type"), fmt::format("{}: unknown type '{}': expected revolute, continuous, "
                                                           "prismatic, fixed, floating or planar", what, type));
    j.type = found->second;
    const XMLElement* parent = e.FirstChildElement("parent");
    if (parent == nullptr) throw SourceError(j.location, what + " has no <parent>");
    const XMLElement* child = e.FirstChildElement("child");
    if (child == nullptr) throw SourceError(j.location, what + " has no <child>");
    j.parent = required(*parent, "link");
    j.parent_location = places_.of(*parent, "link");
    j.child = required(*child, "link");
    j.child_location = places_.of(*child, "link");
    j.origin = origin(e, what);
    j.axis_location = j.location;
    if (const XMLElement* axis = e.FirstChildElement("axis")) {
      j.axis_location = places_.of(*axis, "xyz");
      j.axis = triple(*axis, "xyz", what + ": axis", j.axis);
    }
    const bool moves_along_axis = j.type == Joint::Type::revolute || j.type == Joint::Type::continuous ||
                                  j.type == Joint::Type::prismatic || j.type == Joint::Type::planar;
    const double length = std::hypot(j.axis[0].value, j.axis[1].value, j.axis[2].value);
    if (moves_along_axis && !(length > 1e-12))
      throw SourceError(j.axis_location, fmt::format("{}: the axis has zero length: expected the direction the {} "
                                                     "joint moves about or along", what, type));
    if (const XMLElement* limit = e.FirstChildElement("limit")) {
      j.lower = optional_scalar(*limit, "lower", what + ": limit lower");
      j.upper = optional_scalar(*limit, "upper", what + ": limit upper");
      j.effort = optional_scalar(*limit, "effort", what + ": limit effort");
      j.velocity = optional_scalar(*limit, "velocity", what + ": limit velocity");
    }
    if (const XMLElement* dynamics = e.FirstChildElement("dynamics")) {
      j.damping = optional_scalar(*dynamics, "damping", what + ": damping");
      j.damping_location = places_.of(*dynamics, "damping");
      j.friction = optional_scalar(*dynamics, "friction", what + ": friction");
      if (j.damping && j.damping->value < 0)
        throw SourceError(j.damping_location, fmt::format("{}: the damping {} is negative: expected zero or more", what,
                                                          j.damping->text));
    }
    if (const XMLElement* mimic = e.FirstChildElement("mimic")) {
      Joint::Mimic m;
      m.location = places_.of(*mimic);
      m.joint = required(*mimic, "joint");
      if (auto k = optional_scalar(*mimic, "multiplier", what + ": mimic multiplier")) m.multiplier = *k;
      if (auto k = optional_scalar(*mimic, "offset", what + ": mimic offset")) m.offset = *k;
      j.mimic = m;
    }
    return j;
  }

  void check_tree() const {
    if (robot_.links.empty()) throw SourceError(robot_.location, "the robot has no <link>");
    std::map<std::string, const Link*> links;
    for (const Link& l : robot_.links) {
      const auto [it, fresh] = links.emplace(l.name, &l);
      if (!fresh)
        throw SourceError(l.location, fmt::format("link '{}' is declared twice (first at line {})", l.name,
                                                  it->second->location.line));
    }
    std::map<std::string, const Joint*> joints, parent_joint;
    for (const Joint& j : robot_.joints) {
      const auto [it, fresh] = joints.emplace(j.name, &j);
      if (!fresh)
        throw SourceError(j.location, fmt::format("joint '{}' is declared twice (first at line {})", j.name,
                                                  it->second->location.line));
      if (links.count(j.parent) == 0)
        throw SourceError(j.parent_location, fmt::format("joint '{}': parent '{}' is no link of the robot", j.name, j.parent));
      if (links.count(j.child) == 0)
        throw SourceError(j.child_location, fmt::format("joint '{}': child '{}' is no link of the robot", j.name, j.child));
      if (j.parent == j.child)
        throw SourceError(j.child_location, fmt::format("joint '{}' joins link '{}' to itself", j.name, j.child));
      const auto [p, first] = parent_joint.emplace(j.child, &j);
      if (!first)
        throw SourceError(j.child_location,
                          fmt::format("link '{}' is the child of two joints, '{}' (line {}) and '{}': a URDF is a tree, "
                                      "expected one parent per link (close a loop with a constraint in the model)",
                                      j.child, p->second->name, p->second->location.line, j.name));
    }
    std::vector<const Link*> roots;
    for (const Link& l : robot_.links)
      if (parent_joint.count(l.name) == 0) roots.push_back(&l);
    if (roots.empty()) {
      const Joint& j = robot_.joints.front();
      throw SourceError(j.location, fmt::format("every link is the child of a joint, so the joints make a cycle "
                                                "(through joint '{}'): expected one root link", j.name));
    }
    if (roots.size() > 1)
      throw SourceError(roots[1]->location,
                        fmt::format("links '{}' and '{}' are both roots (the child of no joint): expected one tree, "
                                    "joined to '{}' by a joint", roots[0]->name, roots[1]->name, roots[0]->name));
    // every link reached from the root: the rest hang in a cycle
    std::set<std::string> reached{roots[0]->name};
    for (bool grew = true; grew;) {
      grew = false;
      for (const Joint& j : robot_.joints)
        if (reached.count(j.parent) != 0 && reached.insert(j.child).second) grew = true;
    }
    for (const Joint& j : robot_.joints)
      if (reached.count(j.child) == 0)
        throw SourceError(j.location, fmt::format("joint '{}' is on a cycle of joints that the root '{}' does not "
                                                  "reach: expected a tree", j.name, roots[0]->name));
    for (const Joint& j : robot_.joints) {
      if (!j.mimic) continue;
      const auto m = joints.find(j.mimic->joint);
      if (m == joints.end())
        throw SourceError(j.mimic->location, fmt::format("joint '{}' mimics '{}', which is no joint of the robot",
                                                         j.name, j.mimic->joint));
      if (m->second == &j) throw SourceError(j.mimic->location, fmt::format("joint '{}' mimics itself", j.name));
      const auto one_coordinate = [](Joint::Type t) {
        return t == Joint::Type::revolute || t == Joint::Type::continuous || t == Joint::Type::prismatic;
      };
      if (!one_coordinate(j.type) || !one_coordinate(m->second->type))
        throw SourceError(j.mimic->location,
                          fmt::format("joint '{}' mimics '{}': expected both revolute, continuous or prismatic (one "
                                      "coordinate each)", j.name, j.mimic->joint));
    }
  }

  const std::string& text_;
  Places places_;
  Robot robot_;
};

}  // namespace

Robot read_robot(const std::string& text, const std::string& file) {
  if (text.size() > max_urdf_bytes)
    throw SourceError({file, 1, 1}, fmt::format("the file has more than {} MiB: expected a robot description "
                                                "(meshes belong in files of their own)", max_urdf_bytes >> 20));
  return Reader(text, file).run();
}

}  // namespace eomgen::urdf
