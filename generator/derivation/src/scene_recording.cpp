#include "eomgen/derivation/scene_recording.hpp"

#include <algorithm>
#include <set>

#include "eomgen/mechanics/kinematics.hpp"

namespace eomgen {

namespace {

/// Whether the offset from a point's parent is fixed in a moving frame: one term, in a frame
/// other than the inertial one, whose components hold neither state nor time. Such a pair is a
/// link of the mechanism; an offset that holds coordinates (a cart's travel, a coin's position
/// on the plane) is a joint's freedom, not a piece of material.
bool is_link(const MechanicalSystem& system, const Point& point) {
  const std::vector<Vector::Term>& terms = point.offset.terms();
  if (terms.size() != 1 || terms.front().first == system.inertial_frame()) return false;
  const Variables& vars = system.variables();
  for (unsigned i = 0; i < 3; ++i) {
    const GiNaC::ex& c = terms.front().second(i, 0);
    for (const SymbolKind kind : {SymbolKind::time, SymbolKind::coordinate, SymbolKind::rate, SymbolKind::input})
      if (vars.contains(c, kind)) return false;
  }
  return true;
}

std::vector<std::size_t> default_trails(const Model& model) {
  const MechanicalSystem& system = model.system;
  std::set<std::size_t> trails;
  for (const ContactForce& contact : model.contacts) trails.insert(contact.point.index);
  if (!trails.empty()) return {trails.begin(), trails.end()};
  std::vector<bool> has_child(system.points().size(), false);
  for (const Point& p : system.points())
    if (p.parent) has_child[p.parent->index] = true;
  const auto leaf = [&](PointId p) { return p != system.origin() && !has_child[p.index]; };
  for (const Particle& p : system.particles())
    if (leaf(p.point)) trails.insert(p.point.index);
  for (const RigidBody& b : system.rigid_bodies())
    if (leaf(b.mass_centre)) trails.insert(b.mass_centre.index);
  if (!trails.empty()) return {trails.begin(), trails.end()};
  for (std::size_t i = 0; i < system.points().size(); ++i)
    if (leaf(PointId{i})) trails.insert(i);
  return {trails.begin(), trails.end()};
}

}  // namespace

SceneRecording scene_recording(const Model& model) {
  const MechanicalSystem& system = model.system;
  SceneRecording r;
  std::vector<std::string> body_of(system.frames().size());
  std::vector<bool> recorded(system.frames().size(), false);
  for (const RigidBody& b : system.rigid_bodies()) {
    recorded[b.frame.index] = true;
    if (body_of[b.frame.index].empty()) body_of[b.frame.index] = b.name;
  }
  for (const VisualShape& s : model.shapes)
    if (s.frame) recorded[s.frame->index] = true;
  recorded[system.inertial_frame().index] = false;
  for (std::size_t f = 0; f < recorded.size(); ++f)
    if (recorded[f]) r.frames.emplace_back(FrameId{f}, body_of[f]);

  for (std::size_t i = 0; i < system.points().size(); ++i) {
    r.points.push_back(PointId{i});
    const Point& p = system.point(PointId{i});
    if (p.parent && is_link(system, p)) r.links.emplace_back(p.parent->index, i);
  }
  r.trails = default_trails(model);

  for (const auto& [frame, body] : r.frames) {
    const GiNaC::matrix c = dcm(system, system.inertial_frame(), frame);
    for (unsigned i = 0; i < 3; ++i)
      for (unsigned j = 0; j < 3; ++j) r.components.push_back(c(i, j));
  }
  for (const PointId p : r.points) {
    const GiNaC::matrix x = resolve(system, position(system, p, system.origin()), system.inertial_frame());
    for (unsigned i = 0; i < 3; ++i) r.components.push_back(x(i, 0));
  }
  return r;
}

Model with_scene_output(const Model& model, const SceneRecording& recording) {
  Model scene = model;
  Output out;
  // a name that begins no output's name or label: the header declares one name per output and
  // per label, and the labels are the name with _0, _1, ...
  out.name = "scene";
  const auto taken = [&](const std::string& prefix) {
    const auto begins = [&](const std::string& s) { return s.compare(0, prefix.size(), prefix) == 0; };
    for (const Output& o : model.outputs)
      if (begins(o.name) || std::any_of(o.labels.begin(), o.labels.end(), begins)) return true;
    return false;
  };
  while (taken(out.name)) out.name += "_";
  out.components = recording.components;
  for (std::size_t k = 0; k < recording.components.size(); ++k) out.labels.push_back(out.name + "_" + std::to_string(k));
  scene.outputs.push_back(std::move(out));
  return scene;
}

}  // namespace eomgen
