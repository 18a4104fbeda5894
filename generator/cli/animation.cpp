#include "animation.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <variant>
#include <sstream>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/report/stl_mesh.hpp"
#include "eomgen/symbolic/double_evaluator.hpp"
#include "mesh_files.hpp"

namespace eomgen::tools {

namespace {

using Rows = std::vector<std::vector<double>>;

/// The samples a page keeps of \p n: all, or at most max_animation_samples spread evenly, the
/// last kept.
std::vector<std::size_t> kept_samples(std::size_t n) {
  std::vector<std::size_t> kept;
  if (n <= max_animation_samples) {
    for (std::size_t i = 0; i < n; ++i) kept.push_back(i);
    return kept;
  }
  for (std::size_t k = 0; k < max_animation_samples; ++k)
    kept.push_back(k * (n - 1) / (max_animation_samples - 1));
  return kept;
}

/// The kept lines of the scene file, every one of \p width numbers. Read twice, counting and
/// then parsing the kept lines only, so a run of millions of samples needs no more memory than
/// its page.
Rows read_samples(const std::string& path, std::size_t width) {
  std::size_t lines = 0;
  {
    std::ifstream in(path, std::ios::binary);
    for (std::string line; std::getline(in, line);) ++lines;
  }
  if (lines == 0) throw Error("the simulation wrote no sample for the animation (a bug in eomgen)");
  const std::vector<std::size_t> kept = kept_samples(lines);
  Rows rows;
  std::ifstream in(path, std::ios::binary);
  std::size_t index = 0, next = 0;
  for (std::string line; next < kept.size() && std::getline(in, line); ++index) {
    if (index != kept[next]) continue;
    ++next;
    std::vector<double> row;
    const char* p = line.c_str();
    while (*p != '\0') {
      char* end = nullptr;
      row.push_back(std::strtod(p, &end));
      if (end == p || (*end != ',' && *end != '\0'))
        throw Error(fmt::format("the animation's samples are malformed at line {} (a bug in eomgen)", index + 1));
      p = *end == ',' ? end + 1 : end;
    }
    if (row.size() != width)
      throw Error(fmt::format("the animation's samples have {} values at line {}, expected {} (a bug in eomgen)",
                              row.size(), index + 1, width));
    rows.push_back(std::move(row));
  }
  if (rows.size() != kept.size()) throw Error("the animation's samples ended early (a bug in eomgen)");
  return rows;
}

/// JSON text, written by hand for the numbers: six significant digits (a micrometre in a metre)
/// keep a page of thousands of samples small, and fmt prints them the same in every process.
class JsonText {
 public:
  JsonText& raw(const std::string& s) {
    out_ += s;
    return *this;
  }
  JsonText& string(const std::string& s) {
    out_ += nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return *this;
  }
  /// \throws Error for a value JSON cannot hold (inf, NaN): a multiplier or an energy that
  /// overflowed, a dimension that --set made infinite
  JsonText& number(double v) {
    if (!std::isfinite(v))
      throw Error(fmt::format("the animation's scene would hold the value {}, which is no number: a multiplier, an "
                              "energy or a dimension is not finite in this run",
                              v));
    out_ += fmt::format("{:.6g}", v == 0 ? 0.0 : v);  // no "-0"
    return *this;
  }
  template <class Range>
  JsonText& numbers(const Range& values) {
    out_ += '[';
    bool first = true;
    for (const double v : values) {
      if (!first) out_ += ',';
      first = false;
      number(v);
    }
    out_ += ']';
    return *this;
  }
  const std::string& text() const { return out_; }

 private:
  std::string out_;
};

/// The run's parameter values: the defaults, overridden by --set, and the derived parameters
/// computed from them.
DoubleEvaluator parameter_values(const Model& model, const std::map<std::string, double>& set) {
  DoubleEvaluator values;
  for (const Parameter& p : model.system.variables().parameters()) {
    const auto given = set.find(p.name);
    values.set(p.symbol, given == set.end() ? p.default_value : given->second);
  }
  model.system.variables().evaluate_derived_parameters(values);
  return values;
}

/// A shape's dimension at the run's parameters: finite and positive (zero where \p may_be_zero).
/// The language checked it at the defaults; --set can still make it zero or negative.
double dimension(const DoubleEvaluator& values, const GiNaC::ex& e, const VisualShape& shape, const char* what,
                 bool may_be_zero = false) {
  double v = 0;
  try {
    v = values.value(e, what);
  } catch (const Error&) {
    v = std::nan("");
  }
  if (!std::isfinite(v) || v < 0 || (v == 0 && !may_be_zero))
    throw SourceError(shape.location, fmt::format("shape '{}': its {} is {} at the parameters of this run: expected a "
                                                  "finite positive length; check the --set values",
                                                  shape.name, what, v));
  return v;
}

/// A cylinder's or disk's unit axis at the run's parameters (its components hold no state).
Eigen::Vector3d shape_axis(const DoubleEvaluator& values, const VisualShape& shape) {
  Eigen::Vector3d axis;
  try {
    for (int i = 0; i < 3; ++i) axis(i) = values.value(shape.axis[static_cast<std::size_t>(i)], "its axis");
  } catch (const Error&) {
    axis.setConstant(std::nan(""));
  }
  if (!axis.allFinite() || !(axis.norm() > 0))
    throw SourceError(shape.location, fmt::format("shape '{}': its axis is not a direction at the parameters of this "
                                                  "run (zero or not finite); check the --set values",
                                                  shape.name));
  return axis.normalized();
}

/// Every dimension of \p shape at the run's parameters, checked (a rod's radius may be 0).
std::vector<double> shape_dimensions(const DoubleEvaluator& values, const VisualShape& shape) {
  switch (shape.kind) {
    case VisualShape::Kind::sphere: return {dimension(values, shape.radius, shape, "radius")};
    case VisualShape::Kind::box:
      return {dimension(values, shape.size[0], shape, "length along axis 1"),
              dimension(values, shape.size[1], shape, "length along axis 2"),
              dimension(values, shape.size[2], shape, "length along axis 3")};
    case VisualShape::Kind::cylinder:
      return {dimension(values, shape.radius, shape, "radius"), dimension(values, shape.length, shape, "length")};
    case VisualShape::Kind::disk:
      return {dimension(values, shape.radius, shape, "radius"), dimension(values, shape.length, shape, "thickness")};
    case VisualShape::Kind::rod: return {dimension(values, shape.radius, shape, "radius", true)};
    case VisualShape::Kind::mesh: {
      std::vector<double> scale;
      for (std::size_t k = 0; k < 3; ++k) {
        double v = std::nan("");
        try {
          v = values.value(shape.scale[k], "its scale");
        } catch (const Error&) {
        }
        if (!std::isfinite(v) || v == 0)
          throw SourceError(shape.location, fmt::format("shape '{}': factor {} of its scale is {} at the parameters of "
                                                        "this run: expected a finite number that is not zero; check "
                                                        "the --set values", shape.name, k + 1, v));
        scale.push_back(v);
      }
      return scale;
    }
  }
  EOMGEN_UNREACHABLE("a VisualShape::Kind without dimensions");
}

const char* kind_name(VisualShape::Kind kind) {
  switch (kind) {
    case VisualShape::Kind::sphere: return "sphere";
    case VisualShape::Kind::box: return "box";
    case VisualShape::Kind::cylinder: return "cylinder";
    case VisualShape::Kind::disk: return "disk";
    case VisualShape::Kind::rod: return "rod";
    case VisualShape::Kind::mesh: return "mesh";
  }
  EOMGEN_UNREACHABLE("a VisualShape::Kind without a name");
}

/// Where the recorded values of one sample lie in its line of the scene file.
struct SampleLayout {
  std::size_t nq, nc, recording;  // offsets of q, lambda, T, the recording
  std::size_t width;
};

/// An extra frame of the page: a body's principal axes, turned from its frame by the constant R
/// (columns: the axes in the body frame's components), for the box of a body with no shape whose
/// inertia is not diagonal in its frame.
struct PrincipalFrame {
  std::size_t recorded_frame;  // index into recording.frames, or no_frame for the inertial frame
  std::string body;
  Eigen::Matrix3d axes;
};
inline constexpr std::size_t no_frame = static_cast<std::size_t>(-1);

}  // namespace

namespace {

class SceneWriter {
 public:
  SceneWriter(const Model& model, const SceneRecording& recording, const std::map<std::string, double>& parameters,
              const std::string& samples, const MeshPlaces& places)
      : places_(places),
        model_(model),
        system_(model.system),
        recording_(recording),
        values_(parameter_values(model, parameters)),
        nq_(system_.variables().coordinates().size()),
        nc_(system_.constraints().size()),
        rows_(read_samples(samples, 3 + nq_ + nc_ + recording.components.size())),
        kept_(kept_samples(rows_.size())) {}

  std::string write(const std::string& source_name) {
    json_.raw("{\"format\":1,\"model\":").string(model_.name);
    json_.raw(",\n\"description\":").string(model_.description);
    json_.raw(",\n\"source\":").string(source_name);
    json_.raw(",\n\"times\":").numbers(column(0));
    json_.raw(",\n\"up\":").numbers(up());
    std::vector<PrincipalFrame> principal;
    const std::string shapes = shapes_text(principal);
    frames(principal);
    points();
    json_.raw(",\n\"links\":[");
    for (std::size_t k = 0; k < recording_.links.size(); ++k)
      json_.raw(fmt::format("{}[{},{}]", k ? "," : "", recording_.links[k].first, recording_.links[k].second));
    json_.raw("]");
    json_.raw(",\n\"shapes\":[").raw(shapes).raw("]");
    meshes();
    particles();
    json_.raw(",\n\"trails\":[");
    for (std::size_t k = 0; k < recording_.trails.size(); ++k) json_.raw(fmt::format("{}{}", k ? "," : "", recording_.trails[k]));
    json_.raw("]");
    forces();
    ground();
    series();
    json_.raw("}\n");
    return json_.text();
  }

  const std::vector<MissingMesh>& missing_meshes() const { return missing_; }

 private:
  std::size_t recording_offset() const { return 3 + nq_ + nc_; }
  std::size_t frame_count() const { return recording_.frames.size(); }

  /// Column c of the kept samples.
  std::vector<double> column(std::size_t c) const {
    std::vector<double> v;
    for (const std::size_t i : kept_) v.push_back(rows_[i][c]);
    return v;
  }
  /// C_af of recorded frame k at sample i.
  Eigen::Matrix3d rotation(std::size_t k, std::size_t i) const {
    Eigen::Matrix3d c;
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) c(r, s) = rows_[i][recording_offset() + 9 * k + 3 * r + s];
    return c;
  }
  Eigen::Vector3d position(std::size_t point, std::size_t i) const {
    const std::size_t at = recording_offset() + 9 * frame_count() + 3 * point;
    return {rows_[i][at], rows_[i][at + 1], rows_[i][at + 2]};
  }
  /// A constant vector of expressions at the run's parameters (coordinates and time at 0, for
  /// a gravity given in a moving frame).
  Eigen::Vector3d constant(const std::array<GiNaC::ex, 3>& e, const std::string& what) const {
    DoubleEvaluator at_zero = values_;
    at_zero.set(system_.variables().time(), 0);
    for (const Coordinate& c : system_.variables().coordinates()) at_zero.set(c.q, 0), at_zero.set(c.qd, 0);
    return {at_zero.finite(e[0], what), at_zero.finite(e[1], what), at_zero.finite(e[2], what)};
  }

  /// The camera's up: against gravity, else the inertial frame's axis 3.
  std::vector<double> up() const {
    if (!system_.gravity().is_zero()) {
      const GiNaC::matrix g = resolve(system_, system_.gravity(), system_.inertial_frame());
      const Variables& vars = system_.variables();
      bool fixed = true;  // a gravity that turns with the state or time has no one up: the default
      for (unsigned i = 0; i < 3; ++i)
        for (const SymbolKind kind : {SymbolKind::time, SymbolKind::coordinate, SymbolKind::rate, SymbolKind::input})
          fixed = fixed && !vars.contains(g(i, 0), kind);
      if (fixed) {
        const Eigen::Vector3d v = constant({g(0, 0), g(1, 0), g(2, 0)}, "gravity");
        if (v.norm() > 0) return {-v.x() / v.norm(), -v.y() / v.norm(), -v.z() / v.norm()};
      }
    }
    return {0, 0, 1};
  }

  /// The size of the scene: the diagonal of the box around every point over the run.
  double scene_size() const {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (const std::size_t i : kept_)
      for (std::size_t p = 0; p < recording_.points.size(); ++p)
        lo = lo.cwiseMin(position(p, i)), hi = hi.cwiseMax(position(p, i));
    const double d = (hi - lo).norm();
    return std::isfinite(d) && d > 0 ? d : 1.0;
  }

  std::ptrdiff_t frame_index(std::optional<FrameId> frame) const {
    if (!frame || *frame == system_.inertial_frame()) return -1;
    for (std::size_t k = 0; k < frame_count(); ++k)
      if (recording_.frames[k].first == *frame) return static_cast<std::ptrdiff_t>(k);
    EOMGEN_UNREACHABLE("a shape's frame is not recorded (scene_recording records every shape's frame)");
  }

  std::string shapes_text(std::vector<PrincipalFrame>& principal) {
    JsonText s;
    bool first = true;
    const auto begin = [&](const std::string& name, const char* kind, const std::string& body) {
      s.raw(first ? "\n" : ",\n");
      first = false;
      s.raw("{\"name\":").string(name).raw(fmt::format(",\"kind\":\"{}\",\"body\":", kind));
      if (body.empty())
        s.raw("null");
      else
        s.string(body);
    };
    std::set<std::string> drawn_bodies;  // bodies with a shape drawn (other than a rod)
    for (const VisualShape& shape : model_.shapes) {
      std::optional<std::size_t> mesh;
      if (shape.kind == VisualShape::Kind::mesh) {
        mesh = mesh_of(shape);
        if (!mesh) continue;  // in missing_: its body is drawn as if it had no shape
      }
      if (shape.kind != VisualShape::Kind::rod && !shape.body.empty()) drawn_bodies.insert(shape.body);
      begin(shape.name, kind_name(shape.kind), shape.body);
      s.raw(fmt::format(",\"frame\":{},\"at\":{}", frame_index(shape.frame), shape.at.index));
      const std::vector<double> d = shape_dimensions(values_, shape);
      switch (shape.kind) {
        case VisualShape::Kind::sphere: s.raw(",\"radius\":").number(d[0]); break;
        case VisualShape::Kind::box: s.raw(",\"size\":").numbers(d); break;
        case VisualShape::Kind::cylinder:
        case VisualShape::Kind::disk: {
          s.raw(",\"radius\":").number(d[0]).raw(",\"length\":").number(d[1]);
          const Eigen::Vector3d axis = shape_axis(values_, shape);
          s.raw(",\"axis\":").numbers(std::vector<double>{axis.x(), axis.y(), axis.z()});
          break;
        }
        case VisualShape::Kind::rod:
          s.raw(fmt::format(",\"to\":{},\"radius\":", shape.to.index)).number(d[0]);
          break;
        case VisualShape::Kind::mesh:
          s.raw(fmt::format(",\"mesh\":{},\"bounds\":", *mesh)).numbers(meshes_[*mesh].bounds);
          break;
      }
      s.raw(",\"inferred\":false}");
    }
    const double fallback = 0.03 * scene_size();
    for (const RigidBody& body : system_.rigid_bodies()) {
      // a rod only takes its body's colour (docs/model-language.md): the body keeps its box, as
      // it does when its mesh cannot be drawn (the stand-in)
      if (drawn_bodies.count(body.name) != 0) continue;
      // the box of the body's mass and inertia: x^2 = 6 (trace J - 2 J_x) / m for its edges
      const std::string what = fmt::format("the inertia of body '{}'", body.name);
      Eigen::Matrix3d j;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) j(r, c) = values_.finite(body.inertia(r, c), what);
      const double m = values_.finite(body.mass, "the mass of body '" + body.name + "'");
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(j);
      const bool diagonal = (j - Eigen::Matrix3d(j.diagonal().asDiagonal())).cwiseAbs().maxCoeff() <=
                            1e-12 * j.cwiseAbs().maxCoeff();
      const Eigen::Vector3d moments = diagonal ? Eigen::Vector3d(j.diagonal()) : eigen.eigenvalues();
      Eigen::Vector3d edges;
      // (a mass --set to zero or less has no box: the fallback's cube)
      for (int k = 0; k < 3; ++k)
        edges(k) = m > 0 ? std::sqrt(std::max(0.0, 6 * (moments.sum() - 2 * moments(k)) / m)) : 0.0;
      if (!edges.allFinite()) edges.setZero();
      const double thinnest = edges.maxCoeff() > 0 ? 0.05 * edges.maxCoeff() : fallback;
      edges = edges.cwiseMax(thinnest);
      std::ptrdiff_t frame = frame_index(body.frame);
      if (!diagonal) {
        Eigen::Matrix3d axes = eigen.eigenvectors();
        if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
        // the body's recorded frame, or none for a body whose frame is the inertial one
        principal.push_back({frame < 0 ? no_frame : static_cast<std::size_t>(frame), body.name, axes});
        frame = static_cast<std::ptrdiff_t>(frame_count() + principal.size() - 1);
      }
      begin(body.name, "box", body.name);
      s.raw(fmt::format(",\"frame\":{},\"at\":{},\"size\":", frame, body.mass_centre.index))
          .numbers(std::vector<double>{edges.x(), edges.y(), edges.z()})
          .raw(",\"inferred\":true}");
    }
    return s.text() + (first ? "" : "\n");
  }

  /// The index in meshes_ of \p shape's triangles at this run's scale, read on first use; none
  /// (and an entry in missing_) when its file is not found, not STL, cannot be read, or would
  /// take the page over max_animation_triangles.
  std::optional<std::size_t> mesh_of(const VisualShape& shape) {
    const MeshFileLookup found = find_mesh_file(shape.file, places_.model_directory, places_.ros_package_path);
    if (!found.path) {
      missing_.push_back({shape.name, shape.file, found.reason});
      return std::nullopt;
    }
    const std::vector<double> scale = shape_dimensions(values_, shape);
    const std::string file = found.path->string();
    for (std::size_t k = 0; k < meshes_.size(); ++k)
      if (meshes_[k].path == file && meshes_[k].scale == scale) return k;
    auto read = read_.find(file);
    if (read == read_.end()) {
      std::variant<TriangleMesh, std::string> result;
      try {
        result = read_stl(file, max_animation_triangles, max_mesh_file_bytes);
      } catch (const MeshError& e) {
        result = std::string(e.what());
      }
      read = read_.emplace(file, std::move(result)).first;
    }
    if (const std::string* why = std::get_if<std::string>(&read->second)) {
      missing_.push_back({shape.name, shape.file, fmt::format("{} cannot be drawn: {}", file, *why)});
      return std::nullopt;
    }
    const TriangleMesh& triangles = std::get<TriangleMesh>(read->second);
    if (triangles_ + triangles.triangles() > max_animation_triangles) {
      missing_.push_back({shape.name, shape.file,
                          fmt::format("{} has {} triangles, which would take the page over its {} (make the mesh "
                                      "coarser)", file, triangles.triangles(), max_animation_triangles)});
      return std::nullopt;
    }
    triangles_ += triangles.triangles();
    PageMesh m{file, scale, shape.file, {}, triangles.triangles(), {}};
    m.vertices.reserve(triangles.vertices.size());
    std::array<float, 6> box{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < triangles.vertices.size(); ++i) {
      const float v = static_cast<float>(scale[i % 3] * static_cast<double>(triangles.vertices[i]));
      m.vertices.push_back(v);
      box[i % 3] = std::min(box[i % 3], v), box[3 + i % 3] = std::max(box[3 + i % 3], v);
    }
    m.bounds.assign(box.begin(), box.end());
    meshes_.push_back(std::move(m));
    return meshes_.size() - 1;
  }

  void meshes() {
    json_.raw(",\n\"meshes\":[");
    for (std::size_t k = 0; k < meshes_.size(); ++k) {
      json_.raw(k ? ",\n" : "\n").raw("{\"file\":").string(meshes_[k].written);
      json_.raw(fmt::format(",\"triangles\":{},\"vertices\":\"", meshes_[k].triangles));
      json_.raw(little_endian_base64(meshes_[k].vertices)).raw("\"}");
    }
    json_.raw("]");
    json_.raw(",\n\"missing_meshes\":[");
    for (std::size_t k = 0; k < missing_.size(); ++k) {
      json_.raw(k ? ",\n" : "\n").raw("{\"shape\":").string(missing_[k].shape);
      json_.raw(",\"file\":").string(missing_[k].file).raw(",\"reason\":").string(missing_[k].reason).raw("}");
    }
    json_.raw("]");
  }

  void frames(const std::vector<PrincipalFrame>& principal) {
    json_.raw(",\n\"frames\":[");
    const auto frame = [&](bool first, const std::string& name, const std::string& body, auto&& matrix) {
      json_.raw(first ? "\n" : ",\n").raw("{\"name\":").string(name).raw(",\"body\":");
      if (body.empty())
        json_.raw("null");
      else
        json_.string(body);
      std::vector<double> entries;
      for (const std::size_t i : kept_) {
        const Eigen::Matrix3d c = matrix(i);
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s) entries.push_back(c(r, s));
      }
      json_.raw(",\"rotations\":").numbers(entries).raw("}");
    };
    for (std::size_t k = 0; k < frame_count(); ++k)
      frame(k == 0, system_.frame(recording_.frames[k].first).name, recording_.frames[k].second,
            [&](std::size_t i) { return rotation(k, i); });
    for (const PrincipalFrame& p : principal) {
      const bool inertial = p.recorded_frame == no_frame;
      const std::string parent = system_.frame(inertial ? system_.inertial_frame() : recording_.frames[p.recorded_frame].first).name;
      frame(frame_count() == 0 && &p == &principal.front(), fmt::format("{} (principal axes of {})", parent, p.body), "",
            [&](std::size_t i) {
              return Eigen::Matrix3d(inertial ? p.axes : Eigen::Matrix3d(rotation(p.recorded_frame, i) * p.axes));
            });
    }
    json_.raw("]");
  }

  void points() {
    json_.raw(",\n\"points\":[");
    for (std::size_t p = 0; p < recording_.points.size(); ++p) {
      std::vector<double> xyz;
      for (const std::size_t i : kept_) {
        const Eigen::Vector3d x = position(p, i);
        xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
      }
      json_.raw(p ? ",\n" : "\n").raw("{\"name\":").string(system_.point(recording_.points[p]).name);
      json_.raw(",\"positions\":").numbers(xyz).raw("}");
    }
    json_.raw("]");
  }

  void particles() {
    json_.raw(",\n\"particles\":[");
    bool first = true;
    for (const Particle& particle : system_.particles()) {
      json_.raw(first ? "" : ",").raw("{\"name\":").string(particle.name);
      json_.raw(fmt::format(",\"point\":{},\"mass\":", particle.point.index))
          .number(values_.finite(particle.mass, "the mass of particle '" + particle.name + "'"))
          .raw("}");
      first = false;
    }
    json_.raw("]");
  }

  void forces() {
    json_.raw(",\n\"forces\":[");
    for (std::size_t c = 0; c < model_.contacts.size(); ++c) {
      const ContactForce& contact = model_.contacts[c];
      std::vector<Eigen::Vector3d> directions;
      for (const ContactForce::Row& row : contact.rows) directions.push_back(constant(row.direction, "a contact's direction"));
      std::vector<double> xyz;
      for (const std::size_t i : kept_) {
        Eigen::Vector3d f = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < contact.rows.size(); ++k) f += rows_[i][1 + nq_ + contact.rows[k].constraint] * directions[k];
        xyz.insert(xyz.end(), {f.x(), f.y(), f.z()});
      }
      json_.raw(c ? ",\n" : "\n").raw("{\"name\":").string(contact.name);
      json_.raw(fmt::format(",\"point\":{},\"vectors\":", contact.point.index)).numbers(xyz).raw("}");
    }
    json_.raw("]");
  }

  void ground() {
    json_.raw(",\n\"ground\":");
    for (const ContactForce& contact : model_.contacts) {
      if (!contact.plane_normal) continue;
      const Eigen::Vector3d normal = constant(*contact.plane_normal, "a contact's normal");
      if (!(normal.norm() > 0)) continue;
      const Eigen::Vector3d n = normal.normalized();
      const Eigen::Vector3d p = position(contact.plane_point.index, kept_.front());
      json_.raw("{\"normal\":").numbers(std::vector<double>{n.x(), n.y(), n.z()});
      json_.raw(",\"point\":").numbers(std::vector<double>{p.x(), p.y(), p.z()}).raw("}");
      return;
    }
    json_.raw("null");
  }

  void series() {
    json_.raw(",\n\"series\":[");
    const auto one = [&](bool first, const std::string& name, const char* group, std::size_t col) {
      json_.raw(first ? "\n" : ",\n").raw("{\"name\":").string(name).raw(fmt::format(",\"group\":\"{}\",\"values\":", group));
      json_.numbers(column(col)).raw("}");
    };
    const std::vector<Coordinate>& q = system_.variables().coordinates();
    for (std::size_t k = 0; k < q.size(); ++k) one(k == 0, q[k].name, "coordinates", 1 + k);
    const std::size_t t_col = 1 + nq_ + nc_;
    one(q.empty(), "T", "energy", t_col);
    one(false, "V", "energy", t_col + 1);
    json_.raw(",\n{\"name\":\"T+V\",\"group\":\"energy\",\"values\":");
    std::vector<double> total;
    for (const std::size_t i : kept_) total.push_back(rows_[i][t_col] + rows_[i][t_col + 1]);
    json_.numbers(total).raw("}]");
  }

  /// A mesh as the page holds it: its triangles scaled, in float (what the page draws).
  struct PageMesh {
    std::string path;            // the file read
    std::vector<double> scale;   // at this run's parameters
    std::string written;         // the file as the model writes it
    std::vector<float> vertices;
    std::size_t triangles;
    std::vector<double> bounds;  // min x, y, z, then max x, y, z
  };

  const MeshPlaces& places_;
  std::map<std::string, std::variant<TriangleMesh, std::string>> read_;  // by path: the triangles, or why not
  std::vector<PageMesh> meshes_;
  std::vector<MissingMesh> missing_;
  std::size_t triangles_ = 0;  // in meshes_
  const Model& model_;
  const MechanicalSystem& system_;
  const SceneRecording& recording_;
  DoubleEvaluator values_;
  std::size_t nq_, nc_;
  Rows rows_;
  std::vector<std::size_t> kept_;
  JsonText json_;
};

}  // namespace

void check_animation_parameters(const Model& model, const std::map<std::string, double>& parameters) {
  const DoubleEvaluator values = parameter_values(model, parameters);
  for (const VisualShape& shape : model.shapes) {
    shape_dimensions(values, shape);
    if (shape.kind == VisualShape::Kind::cylinder || shape.kind == VisualShape::Kind::disk) shape_axis(values, shape);
  }
}

AnimationScene animation_scene(const Model& model, const SceneRecording& recording,
                               const std::map<std::string, double>& parameters, const std::string& samples,
                               const std::string& source_name, const MeshPlaces& places) {
  SceneWriter writer(model, recording, parameters, samples, places);
  AnimationScene scene;
  scene.json = writer.write(source_name);
  scene.missing_meshes = writer.missing_meshes();
  return scene;
}

}  // namespace eomgen::tools
