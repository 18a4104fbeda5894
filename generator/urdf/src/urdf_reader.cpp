// Reading a URDF file into a Robot (urdf_robot.hpp), with tinyxml2.
#include <tinyxml2.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/urdf/urdf_robot.hpp"

namespace eomgen::urdf {
namespace {

using tinyxml2::XMLElement;

// Places in the text. tinyxml2 gives an element's line only; the offset of every element's
// start tag is found in one pass over the text, which holds the start tags in the order of the
// elements (comments, CDATA sections and processing instructions are skipped; markup cannot
// stand in attribute values or text), and an attribute's place by reading its start tag.
class Places {
 public:
  Places(const std::string& text, std::string file) : text_(text), file_(std::move(file)) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts_.push_back(i + 1);
  }

  /// Finds every element's start tag; after a successful parse of the same text.
  void index(const tinyxml2::XMLDocument& document) {
    std::size_t cursor = 0;
    std::vector<const XMLElement*> stack;
    for (const XMLElement* e = document.FirstChildElement(); e != nullptr; e = e->NextSiblingElement())
      stack.push_back(e);
    std::reverse(stack.begin(), stack.end());
    while (!stack.empty()) {  // pre-order, without recursion
      const XMLElement* e = stack.back();
      stack.pop_back();
      const std::size_t at = next_start_tag(cursor);
      if (at == std::string::npos) break;
      offsets_[e] = at;
      cursor = at + 1;
      std::vector<const XMLElement*> children;
      for (const XMLElement* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) children.push_back(c);
      stack.insert(stack.end(), children.rbegin(), children.rend());
    }
  }

  SourceLocation at_offset(std::size_t offset) const {
    const auto after = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
    const std::size_t line = static_cast<std::size_t>(after - line_starts_.begin()) - 1;
    return {file_, static_cast<int>(line + 1), static_cast<int>(offset - line_starts_[line] + 1)};
  }
  /// The first character of a line that is not blank.
  SourceLocation at_line(int line) const {
    if (line < 1 || static_cast<std::size_t>(line) > line_starts_.size()) return {file_, std::max(line, 1), 1};
    std::size_t i = line_starts_[static_cast<std::size_t>(line) - 1];
    while (i < text_.size() && (text_[i] == ' ' || text_[i] == '\t')) ++i;
    return at_offset(i);
  }

  SourceLocation of(const XMLElement& e, const char* attribute = nullptr) const {
    const auto found = offsets_.find(&e);
    if (found == offsets_.end()) return at_line(e.GetLineNum());
    const std::size_t start = found->second;
    if (attribute != nullptr)
      if (const std::size_t at = attribute_offset(start, attribute); at != std::string::npos) return at_offset(at);
    return at_offset(start);
  }

 private:
  // the next start tag from `from`: a '<' that opens no comment, CDATA section, processing
  // instruction, declaration or end tag
  std::size_t next_start_tag(std::size_t from) const {
    for (std::size_t i = text_.find('<', from); i != std::string::npos; i = text_.find('<', i + 1)) {
      const auto skip_to = [&](const char* end) {
        const std::size_t e = text_.find(end, i);
        return e == std::string::npos ? text_.size() : e;
      };
      if (text_.compare(i, 4, "<!--") == 0) {
        i = skip_to("-->");
      } else if (text_.compare(i, 9, "<![CDATA[") == 0) {
        i = skip_to("]]>");
      } else if (text_.compare(i, 2, "<?") == 0) {
        i = skip_to("?>");
      } else if (text_.compare(i, 2, "<!") == 0 || text_.compare(i, 2, "</") == 0) {
        i = skip_to(">");
      } else {
        return i;
      }
      if (i >= text_.size()) break;
    }
    return std::string::npos;
  }

  // the offset of `name` among the attributes of the start tag at `start`, read as XML writes
  // them (name = "value" or 'value', a '>' inside a value ends nothing), or npos
  std::size_t attribute_offset(std::size_t start, const std::string& name) const {
    std::size_t i = start + 1;
    const auto blank = [&](std::size_t k) { return k < text_.size() && std::isspace(static_cast<unsigned char>(text_[k])) != 0; };
    while (i < text_.size() && !blank(i) && text_[i] != '>' && text_[i] != '/') ++i;  // the element's name
    while (i < text_.size()) {
      while (blank(i)) ++i;
      if (i >= text_.size() || text_[i] == '>' || text_[i] == '/') return std::string::npos;
      const std::size_t name_at = i;
      while (i < text_.size() && !blank(i) && text_[i] != '=' && text_[i] != '>') ++i;
      const bool match = text_.compare(name_at, i - name_at, name) == 0 && i - name_at == name.size();
      while (blank(i)) ++i;
      if (i >= text_.size() || text_[i] != '=') return std::string::npos;
      ++i;
      while (blank(i)) ++i;
      if (i >= text_.size() || (text_[i] != '"' && text_[i] != '\'')) return std::string::npos;
      const std::size_t close = text_.find(text_[i], i + 1);
      if (match) return name_at;
      if (close == std::string::npos) return std::string::npos;
      i = close + 1;
    }
    return std::string::npos;
  }

  const std::string& text_;
  std::string file_;
  std::vector<std::size_t> line_starts_;
  std::unordered_map<const XMLElement*, std::size_t> offsets_;
};

// What a tinyxml2 error means, for a reader who wrote the file by hand.
std::string xml_error(tinyxml2::XMLError error) {
  switch (error) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return "an end tag does not match the element it closes: expected every <element> closed by its own "
             "</element> or written <element .../>";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "an element is not closed or its tag is malformed: expected <name attribute=\"value\" ...> closed "
             "by </name>, or <name .../>";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "an attribute is malformed: expected name=\"value\"";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: return "the file holds no XML element: expected a <robot> element";
    case tinyxml2::XML_ERROR_PARSING_COMMENT: return "a comment is not closed: expected <!-- ... -->";
    case tinyxml2::XML_ERROR_PARSING_CDATA: return "a CDATA section is not closed: expected <![CDATA[ ... ]]>";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED: return "elements are nested too deep for a robot description";
    default: return fmt::format("expected well-formed XML ({})", tinyxml2::XMLDocument::ErrorIDToName(error));
  }
}

class Reader {
 public:
  Reader(const std::string& text, const std::string& file) : text_(text), places_(text, file) {
    robot_.file = file;
  }

  Robot run() {
    refuse_declarations();
    tinyxml2::XMLDocument document(true, tinyxml2::COLLAPSE_WHITESPACE);
    if (const tinyxml2::XMLError error = document.Parse(text_.data(), text_.size()); error != tinyxml2::XML_SUCCESS)
    {
      // tinyxml2 names the element it was reading at the end of its message: "... name=link"
      const std::string detail = document.ErrorStr() == nullptr ? "" : document.ErrorStr();
      const std::size_t name = detail.rfind("name=");
      const std::string at = name == std::string::npos ? "" : " in <" + detail.substr(name + 5) + ">";
      throw SourceError(places_.at_line(document.ErrorLineNum()), "malformed XML" + at + ": " + xml_error(error));
    }
    places_.index(document);
    const XMLElement* root = document.RootElement();
    if (root == nullptr) throw SourceError(places_.at_line(1), "no XML element: expected a <robot> element");
    if (std::string(root->Name()) != "robot")
      throw SourceError(places_.of(*root), fmt::format("the document's element is <{}>: expected <robot>", root->Name()));
    if (const XMLElement* second = root->NextSiblingElement())
      throw SourceError(places_.of(*second), fmt::format("<{}> after the end of <robot>: expected one <robot> element, "
                                                         "the whole file", second->Name()));
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
    const std::size_t first = text.find_first_not_of(" \t\r\n"), last = text.find_last_not_of(" \t\r\n");
    text = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
    if (!text.empty() && text[0] == '+') text.erase(0, 1);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    const bool plain = !text.empty() && end == text.c_str() + text.size() && text.find_first_of("xXnNiI") == std::string::npos;
    if (!plain) throw SourceError(where, fmt::format("{}: '{}' is not a number", what, word));
    if (!std::isfinite(value)) throw SourceError(where, fmt::format("{}: '{}' is not finite", what, word));
    if (value != 0 && std::abs(value) < std::numeric_limits<double>::min())
      throw SourceError(where, fmt::format("{}: '{}' is too small to compute with (below {:g}): expected 0 or a "
                                           "number of normal size", what, word, std::numeric_limits<double>::min()));
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
    // a collision geometry only stands in for visuals: one this reader would refuse as a visual
    // is left out, not an error in a file whose dynamics are sound
    for (const XMLElement* c = e.FirstChildElement("collision"); c != nullptr; c = c->NextSiblingElement("collision")) {
      try {
        if (auto collision = this->visual(*c, what)) l.collisions.push_back(*collision);
      } catch (const SourceError&) {
      }
    }
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
      v.scale = triple(*shape, "scale", what + ": mesh scale", {Number{"1", 1}, Number{"1", 1}, Number{"1", 1}});
    } else {
      // a visual draws, it weighs nothing: one eomgen cannot draw is kept as a comment
      v.kind = Visual::Kind::unsupported;
      v.mesh = kind;
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
    if (roots.empty()) refuse_cycle(robot_.links.front().name, parent_joint);
    if (roots.size() > 1)
      throw SourceError(roots[1]->location,
                        fmt::format("links '{}' and '{}' are both roots (the child of no joint): expected one tree, "
                                    "joined to '{}' by a joint", roots[0]->name, roots[1]->name, roots[0]->name));
    // every link reached from the root, breadth first: the rest hang from a cycle
    std::map<std::string, std::vector<const Joint*>> children;
    for (const Joint& j : robot_.joints) children[j.parent].push_back(&j);
    std::set<std::string> reached{roots[0]->name};
    for (std::vector<std::string> next{roots[0]->name}; !next.empty();) {
      std::vector<std::string> after;
      for (const std::string& link : next)
        for (const Joint* j : children[link])
          if (reached.insert(j->child).second) after.push_back(j->child);
      next.swap(after);
    }
    for (const Joint& j : robot_.joints)
      if (reached.count(j.child) == 0) refuse_cycle(j.child, parent_joint);
    const auto one_coordinate = [](Joint::Type t) {
      return t == Joint::Type::revolute || t == Joint::Type::continuous || t == Joint::Type::prismatic;
    };
    for (const Joint& j : robot_.joints) {
      if (!j.mimic) continue;
      const auto m = joints.find(j.mimic->joint);
      if (m == joints.end())
        throw SourceError(j.mimic->location, fmt::format("joint '{}' mimics '{}', which is no joint of the robot",
                                                         j.name, j.mimic->joint));
      if (m->second == &j) throw SourceError(j.mimic->location, fmt::format("joint '{}' mimics itself", j.name));
      // a fixed joint that mimics moves nothing: its <mimic> is kept as a comment (write_model)
      if (j.type == Joint::Type::fixed) continue;
      if (!one_coordinate(j.type) || !one_coordinate(m->second->type))
        throw SourceError(j.mimic->location,
                          fmt::format("joint '{}' ({}) mimics '{}' ({}): expected both revolute, continuous or "
                                      "prismatic (one coordinate each)", j.name, type_name(j.type), j.mimic->joint,
                                      type_name(m->second->type)));
      if (m->second->mimic && m->second->type != Joint::Type::fixed)
        throw SourceError(j.mimic->location,
                          fmt::format("joint '{}' mimics '{}', which mimics '{}' in turn: expected a joint that moves "
                                      "on its own (mimic '{}' directly, with the multipliers and offsets composed)",
                                      j.name, j.mimic->joint, m->second->mimic->joint, m->second->mimic->joint));
    }
  }

  // Refuses the cycle that the parents of `link` lead into: walking up from it, the first link
  // met twice closes the cycle; the joints around it are named, and the error stands at the one
  // written first.
  [[noreturn]] void refuse_cycle(const std::string& link, const std::map<std::string, const Joint*>& parent_joint) const {
    std::map<std::string, std::size_t> seen;  // link -> its place on the walk
    std::vector<const Joint*> walk;
    std::string at = link;
    while (seen.emplace(at, walk.size()).second) {
      const Joint* j = parent_joint.at(at);
      walk.push_back(j);
      at = j->parent;
    }
    const std::vector<const Joint*> cycle(walk.begin() + static_cast<long>(seen.at(at)), walk.end());
    const Joint* first = *std::min_element(cycle.begin(), cycle.end(), [](const Joint* a, const Joint* b) {
      return a->location.line != b->location.line ? a->location.line < b->location.line
                                                  : a->location.column < b->location.column;
    });
    // parent to child, from the one written first round to it again
    std::vector<const Joint*> loop(cycle.rbegin(), cycle.rend());
    std::rotate(loop.begin(), std::find(loop.begin(), loop.end(), first), loop.end());
    std::string names;
    for (const Joint* j : loop) names += fmt::format("'{}' -> ", j->name);
    names += fmt::format("'{}'", first->name);
    throw SourceError(first->location, fmt::format("the joints {} make a cycle (each the parent of the next's "
                                                   "parent link): expected a tree, every link but one the child of "
                                                   "one joint", names));
  }

  const std::string& text_;
  Places places_;
  Robot robot_;
};

}  // namespace

std::string type_name(Joint::Type t) {
  switch (t) {
    case Joint::Type::revolute: return "revolute";
    case Joint::Type::continuous: return "continuous";
    case Joint::Type::prismatic: return "prismatic";
    case Joint::Type::fixed: return "fixed";
    case Joint::Type::floating: return "floating";
    case Joint::Type::planar: return "planar";
  }
  EOMGEN_UNREACHABLE("type_name: a Joint::Type outside its enumerators");
}

Robot read_robot(const std::string& text, const std::string& file) {
  if (text.size() > max_urdf_bytes)
    throw SourceError({file, 1, 1}, fmt::format("the file has more than {} MiB: expected a robot description "
                                                "(meshes belong in files of their own)", max_urdf_bytes >> 20));
  return Reader(text, file).run();
}

}  // namespace eomgen::urdf
