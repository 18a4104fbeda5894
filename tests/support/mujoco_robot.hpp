#pragma once
// MuJoCo (Debian's libmujoco 2.2.2) as an independent oracle for a URDF robot's dynamics
// (tests/robots/). The URDF text is first prepared so that MuJoCo compiles the same robot that
// eomgen reads (prepare_urdf_for_mujoco, in memory; models/robots/ is never touched), then
// loaded from a virtual file, and its mass matrix, bias and passive forces, accelerations and
// link poses are read at a state given joint by joint, in an order the caller chooses.
//
// MuJoCo's conventions: qfrc_bias = C(q, qd) qd + g(q) is the left-hand side's velocity and
// gravity terms, qfrc_passive holds the joint damping -c qd, and
// M qacc = qfrc_passive - qfrc_bias + qfrc_applied (+ constraint forces, of which the
// prepared robot has none); xmat of a body maps its components to the world's (v_w = xmat v_b).
#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace eomgen::testing {

/// What a comparison needs of a URDF joint: its kind, limits, damping and mimic.
struct UrdfJointSummary {
  std::string name;
  std::string type;  ///< revolute, continuous, prismatic, fixed, ...
  std::optional<double> lower, upper;
  double damping = 0;
  std::optional<std::string> mimicked;  ///< the joint this one mimics
  double mimic_multiplier = 1, mimic_offset = 0;
  bool moves() const { return type == "revolute" || type == "continuous" || type == "prismatic"; }
};

/// A link's <inertial>: mass, and the inertia about the mass centre in the axes of its origin.
struct UrdfInertialSummary {
  double mass = 0;
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< R(rpy) of <origin>: link <- inertia axes
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();   ///< as written, in those axes
  /// The inertia about the mass centre resolved in the link frame.
  Eigen::Matrix3d inertia_in_link() const { return axes * inertia * axes.transpose(); }
};

struct UrdfSummary {
  std::vector<std::string> links;        ///< in file order
  std::vector<std::optional<UrdfInertialSummary>> inertials;  ///< per link, where it has one
  std::vector<UrdfJointSummary> joints;  ///< in file order, fixed ones included
};

namespace detail {

inline tinyxml2::XMLElement* robot_element(tinyxml2::XMLDocument& doc, const std::string& text) {
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
    throw std::runtime_error(std::string("URDF text: ") + doc.ErrorStr());
  tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::strcmp(robot->Name(), "robot") != 0) throw std::runtime_error("URDF text: no <robot>");
  return robot;
}

inline std::optional<double> number_attribute(const tinyxml2::XMLElement* e, const char* name) {
  if (!e || !e->Attribute(name)) return std::nullopt;
  return std::stod(e->Attribute(name));
}

inline Eigen::Vector3d triple_attribute(const tinyxml2::XMLElement* e, const char* name) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  if (!e || !e->Attribute(name)) return v;
  if (std::sscanf(e->Attribute(name), "%lf %lf %lf", &v[0], &v[1], &v[2]) != 3)
    throw std::runtime_error(std::string("URDF text: cannot read ") + name + "=\"" + e->Attribute(name) + "\"");
  return v;
}

inline std::string exact_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

// the symmetric matrix of an <inertia> element
inline Eigen::Matrix3d inertia_matrix(const tinyxml2::XMLElement* inertia) {
  const auto entry = [&](const char* name) { return number_attribute(inertia, name).value_or(0.0); };
  Eigen::Matrix3d m;
  m << entry("ixx"), entry("ixy"), entry("ixz"), entry("ixy"), entry("iyy"), entry("iyz"), entry("ixz"), entry("iyz"),
      entry("izz");
  return m;
}

inline void remove_children_named(tinyxml2::XMLElement* parent, const char* name) {
  while (tinyxml2::XMLElement* child = parent->FirstChildElement(name)) parent->DeleteChild(child);
}

}  // namespace detail

/// URDF's rotation of roll, pitch, yaw: C = Rz(yaw) Ry(pitch) Rx(roll), taking the rotated
/// frame's components to the parent's.
inline Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// The links (with their inertials) and joints of URDF text. \throws std::runtime_error for text that is no URDF.
inline UrdfSummary read_urdf_summary(const std::string& text) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* robot = detail::robot_element(doc, text);
  UrdfSummary summary;
  for (auto* link = robot->FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    summary.links.push_back(link->Attribute("name"));
    summary.inertials.emplace_back();
    const auto* inertial = link->FirstChildElement("inertial");
    if (!inertial) continue;
    UrdfInertialSummary& i = summary.inertials.back().emplace();
    i.mass = detail::number_attribute(inertial->FirstChildElement("mass"), "value").value_or(0.0);
    i.axes = rotation_from_rpy(detail::triple_attribute(inertial->FirstChildElement("origin"), "rpy"));
    i.inertia = detail::inertia_matrix(inertial->FirstChildElement("inertia"));
  }
  for (auto* joint = robot->FirstChildElement("joint"); joint; joint = joint->NextSiblingElement("joint")) {
    UrdfJointSummary j;
    j.name = joint->Attribute("name");
    j.type = joint->Attribute("type");
    const auto* limit = joint->FirstChildElement("limit");
    j.lower = detail::number_attribute(limit, "lower");
    j.upper = detail::number_attribute(limit, "upper");
    j.damping = detail::number_attribute(joint->FirstChildElement("dynamics"), "damping").value_or(0.0);
    if (const auto* mimic = joint->FirstChildElement("mimic")) {
      j.mimicked = mimic->Attribute("joint");
      j.mimic_multiplier = detail::number_attribute(mimic, "multiplier").value_or(1.0);
      j.mimic_offset = detail::number_attribute(mimic, "offset").value_or(0.0);
    }
    summary.joints.push_back(j);
  }
  return summary;
}

/// Roll, pitch, yaw of a rotation (the inverse of rotation_from_rpy), rebuilding it to
/// rounding also at and near pitch = +-pi/2: roll is taken from what remains after yaw and
/// pitch, so it absorbs the error of a yaw read from the small entries there.
inline Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& c) {
  const double cos_pitch = std::hypot(c(0, 0), c(1, 0));
  const double pitch = std::atan2(-c(2, 0), cos_pitch);
  const double yaw = std::atan2(c(1, 0), c(0, 0));  // any value when cos_pitch is 0
  const Eigen::Matrix3d rest = rotation_from_rpy(Eigen::Vector3d(0, pitch, yaw)).transpose() * c;  // Rx(roll)
  return {std::atan2(rest(2, 1), rest(1, 1)), pitch, yaw};
}

/// The URDF text rewritten so that MuJoCo 2.2.2's compiler builds the robot the file describes,
/// to rounding:
///  - <mujoco><compiler fusestatic="false" .../>: MuJoCo merges the links of fixed joints into
///    their parents by default (fusestatic), and the poses of every link are compared; visuals
///    are discarded, inertia is neither balanced nor taken from geoms;
///  - no <visual> or <collision>: MuJoCo builds geoms (and contacts) from them;
///  - no <limit>: a limited joint can add constraint forces to MuJoCo's accelerations;
///  - no friction attribute in <dynamics>: MuJoCo makes it a frictionloss constraint, and eomgen
///    carries URDF friction as a comment only (the shipped robots write friction="0" at most);
///  - every inertia given on its principal axes, in decreasing order, with the inertial origin's
///    rpy turned onto them: MuJoCo diagonalizes a full inertia by a Jacobi iteration that stops
///    at about 1e-6 relative (mju_eig3), but leaves a diagonal one in decreasing order as it is.
/// <mimic> stays: MuJoCo 2.2.2 ignores it (the caller imposes the mimic itself, if at all).
/// \throws std::runtime_error for text that is no URDF or already has a <mujoco> element.
inline std::string prepare_urdf_for_mujoco(const std::string& text) {
  tinyxml2::XMLDocument doc;
  tinyxml2::XMLElement* robot = detail::robot_element(doc, text);
  if (robot->FirstChildElement("mujoco")) throw std::runtime_error("URDF text: it has a <mujoco> element already");
  tinyxml2::XMLElement* mujoco = doc.NewElement("mujoco");
  tinyxml2::XMLElement* compiler = doc.NewElement("compiler");
  compiler->SetAttribute("fusestatic", "false");
  compiler->SetAttribute("discardvisual", "true");
  compiler->SetAttribute("balanceinertia", "false");
  compiler->SetAttribute("inertiafromgeom", "false");
  mujoco->InsertEndChild(compiler);
  robot->InsertFirstChild(mujoco);

  for (auto* link = robot->FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    detail::remove_children_named(link, "visual");
    detail::remove_children_named(link, "collision");
    tinyxml2::XMLElement* inertial = link->FirstChildElement("inertial");
    tinyxml2::XMLElement* inertia = inertial ? inertial->FirstChildElement("inertia") : nullptr;
    if (!inertia) continue;
    // the inertia as given, resolved in the inertial origin's axes
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(detail::inertia_matrix(inertia));
    // columns: the principal axes in decreasing order of moment, a right-handed triad
    Eigen::Matrix3d axes = eigen.eigenvectors().rowwise().reverse();
    if (axes.determinant() < 0) axes.col(2) *= -1;
    const Eigen::Vector3d moments = eigen.eigenvalues().reverse();

    tinyxml2::XMLElement* origin = inertial->FirstChildElement("origin");
    if (!origin) {
      origin = doc.NewElement("origin");
      inertial->InsertFirstChild(origin);
    }
    const Eigen::Matrix3d principal = rotation_from_rpy(detail::triple_attribute(origin, "rpy")) * axes;
    const Eigen::Vector3d rpy = roll_pitch_yaw(principal);
    if ((rotation_from_rpy(rpy) - principal).cwiseAbs().maxCoeff() > 1e-15)
      throw std::runtime_error(std::string("prepare_urdf_for_mujoco: the principal axes of ") +
                               link->Attribute("name") + " lose precision as roll, pitch, yaw");
    origin->SetAttribute("rpy", (detail::exact_text(rpy[0]) + " " + detail::exact_text(rpy[1]) + " " +
                                 detail::exact_text(rpy[2]))
                                    .c_str());
    inertia->SetAttribute("ixx", detail::exact_text(moments[0]).c_str());
    inertia->SetAttribute("iyy", detail::exact_text(moments[1]).c_str());
    inertia->SetAttribute("izz", detail::exact_text(moments[2]).c_str());
    for (const char* product : {"ixy", "ixz", "iyz"}) inertia->SetAttribute(product, "0");
  }
  for (auto* joint = robot->FirstChildElement("joint"); joint; joint = joint->NextSiblingElement("joint")) {
    detail::remove_children_named(joint, "limit");
    if (auto* dynamics = joint->FirstChildElement("dynamics")) dynamics->DeleteAttribute("friction");
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

/// A URDF robot compiled by MuJoCo from prepare_urdf_for_mujoco(text), with its moving joints
/// in the order `joints` names them: every vector and matrix below is in that order (rows and
/// columns of M), whatever the order of MuJoCo's degrees of freedom.
class MujocoRobot {
 public:
  /// \throws std::runtime_error if MuJoCo refuses the robot, or `joints` does not name each of
  ///   its degrees of freedom exactly once.
  MujocoRobot(const std::string& urdf_text, const std::vector<std::string>& joints) {
    // MuJoCo's default warning handler appends to MUJOCO_LOG.TXT in the working directory;
    // warnings are read from mjData::warning instead (forward())
    mju_user_warning = [](const char*) {};
    const std::string prepared = prepare_urdf_for_mujoco(urdf_text);
    const auto vfs = std::make_unique<mjVFS>();  // 2 MB: not on the stack
    mj_defaultVFS(vfs.get());
    const char* file = "robot.urdf";
    if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(prepared.size())) != 0)
      throw std::runtime_error("MujocoRobot: cannot make the virtual file");
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], prepared.data(), prepared.size());
    char error[1000] = "";
    model_ = mj_loadXML(file, vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (!model_) throw std::runtime_error(std::string("MujocoRobot: MuJoCo refuses the robot: ") + error);
    data_ = mj_makeData(model_);
    if (static_cast<int>(joints.size()) != model_->nv || model_->nq != model_->nv)
      throw std::runtime_error("MujocoRobot: " + std::to_string(joints.size()) + " joints named, MuJoCo has " +
                               std::to_string(model_->nv) + " degrees of freedom");
    for (const std::string& name : joints) {
      const int id = mj_name2id(model_, mjOBJ_JOINT, name.c_str());
      if (id < 0) throw std::runtime_error("MujocoRobot: MuJoCo has no joint '" + name + "'");
      qpos_address_.push_back(model_->jnt_qposadr[id]);
      dof_address_.push_back(model_->jnt_dofadr[id]);
    }
    std::vector<int> sorted = dof_address_;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw std::runtime_error("MujocoRobot: a joint is named twice");
  }
  MujocoRobot(const MujocoRobot&) = delete;
  MujocoRobot& operator=(const MujocoRobot&) = delete;
  ~MujocoRobot() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }

  const mjModel& model() const { return *model_; }
  Eigen::Index size() const { return static_cast<Eigen::Index>(dof_address_.size()); }

  /// Sets the joint angles and displacements q, their rates qd and the generalized forces
  /// `applied` (qfrc_applied: joint torques and forces), all in the order of `joints`, and runs
  /// mj_forward. \throws std::runtime_error if MuJoCo adds constraint rows (nefc > 0: a limit,
  /// contact, equality or friction loss the preparation missed) or warns.
  void forward(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& applied) {
    mj_resetData(model_, data_);
    for (Eigen::Index k = 0; k < size(); ++k) {
      data_->qpos[qpos_address_[k]] = q[k];
      data_->qvel[dof_address_[k]] = qd[k];
      data_->qfrc_applied[dof_address_[k]] = applied[k];
    }
    mj_forward(model_, data_);
    if (data_->nefc != 0) throw std::runtime_error("MujocoRobot: MuJoCo has constraint rows");
    for (int w = 0; w < mjNWARNING; ++w)
      if (data_->warning[w].number != 0) throw std::runtime_error("MujocoRobot: MuJoCo warns (" + std::to_string(w) + ")");
  }

  /// M, from mj_fullM of qM.
  Eigen::MatrixXd mass_matrix() const {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> full(model_->nv, model_->nv);
    mj_fullM(model_, full.data(), data_->qM);
    Eigen::MatrixXd m(size(), size());
    for (Eigen::Index i = 0; i < size(); ++i)
      for (Eigen::Index j = 0; j < size(); ++j) m(i, j) = full(dof_address_[i], dof_address_[j]);
    return m;
  }
  Eigen::VectorXd bias_forces() const { return in_order(data_->qfrc_bias); }        ///< qfrc_bias
  Eigen::VectorXd passive_forces() const { return in_order(data_->qfrc_passive); }  ///< qfrc_passive
  Eigen::VectorXd accelerations() const { return in_order(data_->qacc); }           ///< qacc

  /// The position of the origin of the body (link) `link` in the world, xpos.
  Eigen::Vector3d position(const std::string& link) const {
    return Eigen::Map<const Eigen::Vector3d>(data_->xpos + 3 * body(link));
  }
  /// The body's xmat, which maps its components to the world's: v_world = xmat v_body.
  Eigen::Matrix3d orientation(const std::string& link) const {
    return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data_->xmat + 9 * body(link));
  }
  /// The inertia of a body about its mass centre, resolved in its own (link) frame.
  Eigen::Matrix3d inertia(const std::string& link) const {
    const int b = body(link);
    Eigen::Matrix3d axes;  // body_iquat: the inertia's principal axes in the body frame
    mju_quat2Mat(axes.data(), model_->body_iquat + 4 * b);
    axes.transposeInPlace();  // mju_quat2Mat writes row-major
    const Eigen::Vector3d moments = Eigen::Map<const Eigen::Vector3d>(model_->body_inertia + 3 * b);
    return axes * moments.asDiagonal() * axes.transpose();
  }
  double mass(const std::string& link) const { return model_->body_mass[body(link)]; }

 private:
  int body(const std::string& link) const {
    const int id = mj_name2id(model_, mjOBJ_BODY, link.c_str());
    if (id < 0) throw std::runtime_error("MujocoRobot: MuJoCo has no body '" + link + "'");
    return id;
  }
  Eigen::VectorXd in_order(const mjtNum* by_dof) const {
    Eigen::VectorXd v(size());
    for (Eigen::Index k = 0; k < size(); ++k) v[k] = by_dof[dof_address_[k]];
    return v;
  }

  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<int> qpos_address_, dof_address_;  // per joint of the caller's order
};

}  // namespace eomgen::testing
