#include "link_tree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "eomgen/mechanics/kinematics.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;
using Coordinates = std::set<std::size_t>;

bool contains(const Coordinates& outer, const Coordinates& inner) {
  return std::includes(outer.begin(), outer.end(), inner.begin(), inner.end());
}

// Which coordinates every frame, point and link depends on (its deps), and the checks on them.
class TreeBuilder {
 public:
  explicit TreeBuilder(const MechanicalSystem& s) : s_(s), vars_(s.variables()) {
    for (const Frame& f : s.frames())
      frame_deps_.push_back(f.parent ? joined(frame_deps_[f.parent->index], of(f.rotation.dcm())) : Coordinates{});
    for (const Point& p : s.points()) {
      Coordinates deps = p.parent ? point_deps_[p.parent->index] : Coordinates{};
      for (const auto& [frame, components] : p.offset.terms())
        deps = joined(joined(deps, of(components)), frame_deps_[frame.index]);
      point_deps_.push_back(deps);
    }
  }

  std::variant<LinkTree, std::string> build() {
    std::vector<Link> links = collect_links();
    // a strictly smaller set of coordinates comes first, so parents precede their children
    std::stable_sort(links.begin(), links.end(),
                     [&](const Link& a, const Link& b) { return deps(a).size() < deps(b).size(); });
    for (std::size_t i = 0; i < links.size(); ++i)
      if (auto reason = attach(links, i)) return *reason;
    if (auto reason = check_partition(links)) return *reason;
    for (const Link& link : links)
      if (auto reason = check_joint(links, link)) return *reason;
    return LinkTree{std::move(links)};
  }

 private:
  Coordinates of(const matrix& m) const {
    Coordinates out;
    for (unsigned i = 0; i < m.rows(); ++i)
      for (unsigned j = 0; j < m.cols(); ++j)
        for (const ex& symbol : symbols_of(m(i, j)))
          if (vars_.kind_of(symbol) == SymbolKind::coordinate) out.insert(*vars_.coordinate_index(symbol));
    return out;
  }

  static Coordinates joined(Coordinates a, const Coordinates& b) {
    a.insert(b.begin(), b.end());
    return a;
  }

  Coordinates deps(const Link& link) const {
    return joined(frame_deps_[link.frame.index], point_deps_[link.centre.index]);
  }

  // a particle turns with the frame of the last term of the offset it hangs from
  FrameId particle_frame(PointId p) const {
    for (;;) {
      const Point& point = s_.point(p);
      if (!point.offset.is_zero()) return point.offset.terms().back().first;
      if (!point.parent) return s_.inertial_frame();
      p = *point.parent;
    }
  }

  // true if m depends on parameters only: no coordinate, rate, input or time
  bool constant(const matrix& m) const {
    for (unsigned i = 0; i < m.rows(); ++i)
      for (unsigned j = 0; j < m.cols(); ++j)
        for (const ex& symbol : symbols_of(m(i, j)))
          if (const auto kind = vars_.kind_of(symbol); !kind || !is_parameter_kind(*kind)) return false;
    return true;
  }

  // every term of the offset a constant in a frame that turns with `frame` rigidly
  bool fixed_in(const Vector& offset, FrameId frame) const {
    for (const auto& [f, components] : offset.terms()) {
      if (!constant(components)) return false;
      for (FrameId step : frame_path(f, frame))
        if (!constant(s_.frame(step).rotation.dcm())) return false;
    }
    return true;
  }

  // up the point tree from the centre while each step is fixed in the link's frame
  PointId fixed_origin(PointId centre, FrameId frame) const {
    PointId p = centre;
    while (s_.point(p).parent && fixed_in(s_.point(p).offset, frame)) p = *s_.point(p).parent;
    return p;
  }

  // particles, then rigid bodies (the derivation's order); links that never move carry no
  // dynamics and are left out
  std::vector<Link> collect_links() const {
    std::vector<Link> links;
    for (const Particle& p : s_.particles())
      links.push_back(Link{p.name, p.mass, matrix(3, 3), particle_frame(p.point), p.point, {}, std::nullopt, {}});
    for (const RigidBody& b : s_.rigid_bodies()) {
      // the recursions refer a body to the frame its own frame is a constant turn of (a URDF
      // link's, whose inertia axes are turned from it): its joint is then a plain turn, and the
      // constant turn goes into the inertia, which is constant
      FrameId f = b.frame;
      while (s_.frame(f).parent && constant(s_.frame(f).rotation.dcm())) f = *s_.frame(f).parent;
      matrix inertia = b.inertia;
      if (f != b.frame) {
        const matrix C = dcm(s_, b.frame, f);
        inertia = C.transpose().mul(b.inertia).mul(C);
      }
      links.push_back(Link{b.name, b.mass, inertia, f, b.mass_centre, {}, std::nullopt, {}});
    }
    for (Link& link : links) link.origin = fixed_origin(link.centre, link.frame);
    links.erase(std::remove_if(links.begin(), links.end(), [&](const Link& l) { return deps(l).empty(); }),
                links.end());
    return links;
  }

  // the parent of links[i]: an earlier link with the same deps (then rigidly attached), or the
  // one with the largest deps strictly inside its own, which must hold every other such link's
  std::optional<std::string> attach(std::vector<Link>& links, std::size_t i) const {
    const Coordinates own = deps(links[i]);
    std::optional<std::size_t> parent;
    for (std::size_t j = 0; j < i; ++j) {
      const Coordinates other = deps(links[j]);
      if (other == own) {
        links[i].parent = j;
        return std::nullopt;
      }
      if (contains(own, other) && (!parent || other.size() > deps(links[*parent]).size())) parent = j;
    }
    const Coordinates inherited = parent ? deps(links[*parent]) : Coordinates{};
    for (std::size_t j = 0; j < i; ++j)
      if (contains(own, deps(links[j])) && !contains(inherited, deps(links[j])))
        return fmt::format("'{}' and '{}' both move '{}' but not one with the other: not a tree", links[j].name,
                           links[*parent].name, links[i].name);
    links[i].parent = parent;
    std::set_difference(own.begin(), own.end(), inherited.begin(), inherited.end(),
                        std::back_inserter(links[i].joint));
    return std::nullopt;
  }

  // the joints' coordinates partition the model's
  std::optional<std::string> check_partition(const std::vector<Link>& links) const {
    std::vector<const Link*> moved_by(vars_.coordinate_count(), nullptr);
    for (const Link& link : links)
      for (std::size_t k : link.joint) {
        if (moved_by[k])
          return fmt::format("coordinate '{}' moves '{}' and '{}' through separate joints: not a tree",
                             vars_.coordinates()[k].name, moved_by[k]->name, link.name);
        moved_by[k] = &link;
      }
    for (std::size_t k = 0; k < moved_by.size(); ++k)
      if (!moved_by[k]) return fmt::format("coordinate '{}' moves no mass", vars_.coordinates()[k].name);
    return std::nullopt;
  }

  // frames on the tree path between a and b, the common ancestor excluded
  std::vector<FrameId> frame_path(FrameId a, FrameId b) const {
    std::vector<FrameId> path;
    while (a != b) {
      FrameId& deeper = s_.frame(a).depth >= s_.frame(b).depth ? a : b;
      path.push_back(deeper);
      deeper = *s_.frame(deeper).parent;
    }
    return path;
  }

  std::vector<PointId> point_path(PointId a, PointId b) const {
    std::vector<PointId> path;
    while (a != b) {
      PointId& deeper = s_.point(a).depth >= s_.point(b).depth ? a : b;
      path.push_back(deeper);
      deeper = *s_.point(deeper).parent;
    }
    return path;
  }

  bool turns_only_with(FrameId a, FrameId b, const Coordinates& joint) const {
    for (FrameId f : frame_path(a, b))
      if (!contains(joint, of(s_.frame(f).rotation.dcm()))) return false;
    return true;
  }

  // the motion of a link relative to its parent depends on the joint's coordinates only
  std::optional<std::string> check_joint(const std::vector<Link>& links, const Link& link) const {
    const Coordinates joint(link.joint.begin(), link.joint.end());
    const FrameId fp = link.parent ? links[*link.parent].frame : s_.inertial_frame();
    const PointId cp = link.parent ? links[*link.parent].centre : s_.origin();
    bool local = turns_only_with(link.frame, fp, joint);
    for (PointId p : point_path(link.centre, cp))
      for (const auto& [frame, components] : s_.point(p).offset.terms())
        local = local && contains(joint, of(components)) && turns_only_with(frame, fp, joint);
    if (local) return std::nullopt;
    return fmt::format("'{}' moves relative to {} through more than its joint's coordinates", link.name,
                       link.parent ? "'" + links[*link.parent].name + "'" : std::string("the ground"));
  }

  const MechanicalSystem& s_;
  const Variables& vars_;
  std::vector<Coordinates> frame_deps_;
  std::vector<Coordinates> point_deps_;
};

}  // namespace

std::variant<LinkTree, std::string> link_tree(const MechanicalSystem& system) {
  if (!system.constraints().empty()) return std::string("the model has constraints");
  return TreeBuilder(system).build();
}

std::variant<LinkTree, std::string> link_tree_of_bodies(const MechanicalSystem& system) {
  return TreeBuilder(system).build();
}

}  // namespace eomgen
