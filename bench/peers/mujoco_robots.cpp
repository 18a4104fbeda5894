// Peer benchmark: one shipped robot (models/robots/NAME.urdf) as eomgen generates it, against
// MuJoCo 2.2.2 reading the same URDF, prepared as tests/robots/ prepares it
// (tests/support/mujoco_robot.hpp: links kept apart, no geoms, limits or friction loss,
// inertias on exact principal axes) and with its joints mapped to our coordinates by name.
//
// Build (mujoco_robots.sh does this for every robot), on one line:
//   g++ -std=c++17 -O2 -DEOM_HEADER='"ur5.hpp"' -DEOM_NS=ur5 -DEOM_TOOL=tool0 -I<dir of header>
//       -I<repo>/runtime/include -I<repo>/tests -I/usr/include/eigen3
//       mujoco_robots.cpp -lmujoco -ltinyxml2 -o bench_ur5
// EOM_TOOL names the leaf link whose output_jacobian_<EOM_TOOL>_position is timed (the MuJoCo
// body of the same name: the preparation keeps fixed-joint links apart).
// Run:  bench_ur5 ROBOT.urdf [rounds]
//
// 1. cross-check at 8 random states (fixed seed; q inside the joint limits, continuous joints in
//    [-pi, pi], rates up to 2 rad/s or 0.2 m/s, inputs up to 10 N m or 10 N; a mimic joint
//    follows its leader): M against mj_fullM(qM), F against qfrc_applied + qfrc_passive -
//    qfrc_bias (our F holds the dampers and the inputs), and for a robot without constraints
//    qdd against qacc (max-abs error / max-abs value, worst state);
// 2. ns per call, interleaved rounds over a pool of 64 such states at zero input (medians and
//    minima): our M and F, and for a robot without constraints our forward dynamics, against
//    MuJoCo's stages for M and the bias forces, its hand-assembled forward dynamics and
//    mj_forward. A robot with constraints (the Panda's mimic) is timed for M and F only: MuJoCo
//    ignores <mimic>, so its accelerations are those of another system;
// 3. the functions a controller calls, cross-checked at 8 states and timed as in 2 (the pool's
//    states with accelerations up to 5 rad/s^2 or 0.5 m/s^2, drawn from a second seed): our
//    inverse_dynamics (with the Panda's lambda) against mj_inverse, which runs its position and
//    velocity stages itself (qfrc_inverse = M qacc + qfrc_bias - qfrc_passive = our M qdd - F at
//    zero input, for the Panda tau + Xi^T lambda: MuJoCo's tree has no mimic), and against
//    mj_inverseSkip(mjSTAGE_POS) after a position stage done once, untimed (its velocity and
//    acceleration stages alone: what is left when mj_forward ran at that q already); our
//    output_jacobian_<EOM_TOOL>_position against mj_kinematics + mj_comPos + mj_jac (jacp only,
//    at the body's origin), the stages mj_jac needs at a new q (it reads cdof and subtree_com).
// Machine-readable lines start with "RESULT key value".
#include EOM_HEADER

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <eomrt/dynamics_unconstrained.hpp>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "interleaved_timing.hpp"
#include "support/mujoco_robot.hpp"

#ifndef EOM_TOOL
#error "EOM_TOOL: the leaf link whose position Jacobian is timed (-DEOM_TOOL=tool0)"
#endif
#define EOM_PASTE(a, b, c) a##b##c
#define EOM_NAME(a, b, c) EOM_PASTE(a, b, c)
#define EOM_STRING2(x) #x
#define EOM_STRING(x) EOM_STRING2(x)

namespace {

using Model = eomgen_models::EOM_NS::Model;
constexpr int nq = Model::nq;
using Vec = Model::Vector<double>;
using Inputs = Model::Inputs<double>;
using Mat = Model::MassMatrix<double>;
using eomgen::testing::UrdfJointSummary;

volatile double g_sink = 0;

std::string read_text(const char* path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(std::string("cannot read ") + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A URDF name as the import makes it an identifier: every character outside [A-Za-z0-9_]
/// replaced by '_' (tests/robots/mujoco_cross_check_test.cpp).
std::string identifier(std::string name) {
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  return name;
}

/// The URDF joint of each of our coordinates, in coordinate order.
std::vector<UrdfJointSummary> joints_of_coordinates(const eomgen::testing::UrdfSummary& urdf) {
  std::vector<UrdfJointSummary> joints;
  for (const char* coordinate : Model::coordinate_names) {
    const auto it = std::find_if(urdf.joints.begin(), urdf.joints.end(), [&](const UrdfJointSummary& j) {
      return j.moves() && identifier(j.name) == coordinate;
    });
    if (it == urdf.joints.end()) throw std::runtime_error(std::string("no URDF joint for the coordinate ") + coordinate);
    joints.push_back(*it);
  }
  return joints;
}

/// The coordinate each input drives: input <coordinate>_torque or <coordinate>_force.
std::vector<int> coordinates_of_inputs() {
  std::vector<int> out;
  for (const char* input : Model::input_names) {
    int found = -1;
    for (int i = 0; i < nq; ++i)
      for (const char* suffix : {"_torque", "_force"})
        if (std::string(Model::coordinate_names[i]) + suffix == input) found = i;
    if (found < 0) throw std::runtime_error(std::string("no coordinate for the input ") + input);
    out.push_back(found);
  }
  return out;
}

struct State {
  Vec q, qd;
  Inputs u;
  Vec qdd = Vec::Zero();  ///< for the inverse dynamics (random_accelerations)
};

/// A random state: the sampling of tests/robots/mujoco_cross_check_test.cpp.
State random_state(const std::vector<UrdfJointSummary>& joints, std::mt19937_64& rng) {
  const auto uniform = [&](double low, double high) { return std::uniform_real_distribution<double>(low, high)(rng); };
  State s{Vec::Zero(), Vec::Zero(), Inputs::Zero()};
  for (int k = 0; k < nq; ++k) {
    const UrdfJointSummary& j = joints[k];
    s.q[k] = j.lower && j.upper ? uniform(*j.lower, *j.upper) : uniform(-M_PI, M_PI);
    s.qd[k] = j.type == "prismatic" ? uniform(-0.2, 0.2) : uniform(-2, 2);
  }
  for (int k = 0; k < Model::nu; ++k) s.u[k] = uniform(-10, 10);
  for (int k = 0; k < nq; ++k) {  // a mimic joint follows its leader
    const UrdfJointSummary& j = joints[k];
    if (!j.mimicked) continue;
    const auto leader = std::find_if(joints.begin(), joints.end(),
                                     [&](const UrdfJointSummary& other) { return other.name == *j.mimicked; });
    if (leader == joints.end()) throw std::runtime_error("no leader for the mimic joint " + j.name);
    s.q[k] = j.mimic_multiplier * s.q[leader - joints.begin()] + j.mimic_offset;
    s.qd[k] = j.mimic_multiplier * s.qd[leader - joints.begin()];
  }
  return s;
}

/// Accelerations up to 5 rad/s^2 or 0.5 m/s^2 for the states, from a generator of their own (the
/// states of the earlier timings stay as they were); a mimic joint follows its leader.
void random_accelerations(const std::vector<UrdfJointSummary>& joints, std::vector<State>& states, std::mt19937_64& rng) {
  for (State& s : states) {
    for (int k = 0; k < nq; ++k)
      s.qdd[k] = (joints[k].type == "prismatic" ? 0.1 : 1) * std::uniform_real_distribution<double>(-5, 5)(rng);
    for (int k = 0; k < nq; ++k) {
      const UrdfJointSummary& j = joints[k];
      if (!j.mimicked) continue;
      const auto leader = std::find_if(joints.begin(), joints.end(),
                                       [&](const UrdfJointSummary& other) { return other.name == *j.mimicked; });
      s.qdd[k] = j.mimic_multiplier * s.qdd[leader - joints.begin()];
    }
  }
}

/// Our inverse dynamics at zero input into tau; with constraints, tau + Xi^T lambda (= M qdd - F)
/// into `total` when asked (a template, so that `if constexpr` picks the overload the header has).
template <class M, class C>
void our_inverse_dynamics(const C& c, const State& s, const Inputs& u, Vec& tau,
                          Eigen::Matrix<double, M::nc, 1>& lambda, Vec* total = nullptr) {
  if constexpr (M::nc == 0) {
    M::inverse_dynamics(0.0, s.q, s.qd, s.qdd, u, c, tau);
    if (total) *total = tau;
  } else {
    M::inverse_dynamics(0.0, s.q, s.qd, s.qdd, u, c, tau, lambda);
    if (total) {
      Eigen::Matrix<double, M::nc, nq> xi;
      M::constraint_jacobian(0.0, s.q, c, xi);
      *total = tau + xi.transpose() * lambda;
    }
  }
}

/// The generalized forces of the inputs, per coordinate.
Vec applied_forces(const Inputs& u, const std::vector<int>& driven) {
  Vec applied = Vec::Zero();
  for (int k = 0; k < Model::nu; ++k) applied[driven[k]] += u[k];
  return applied;
}

/// Our accelerations into ws.qdd by the runtime: the model's forward_dynamics() where it prefers
/// it, or (by_mass_matrix) M, F and the runtime's Cholesky path. A model with constraints has
/// neither here (a template, so that `if constexpr` drops the calls the runtime refuses).
template <class M, class ParametersOrConstants>
eomrt::DynamicsStatus our_accelerations(bool by_mass_matrix, const ParametersOrConstants& p,
                                        eomrt::DynamicsWorkspace<M, double>& ws, const State& s, const Inputs& u) {
  if constexpr (M::nc == 0) {
    return by_mass_matrix ? eomrt::detail::forward_dynamics_by_mass_matrix<M, double>(p, ws, 0.0, s.q, s.qd, u)
                          : eomrt::forward_dynamics_unconstrained<M, double>(p, ws, 0.0, s.q, s.qd, u);
  } else {
    throw std::logic_error("our_accelerations: the model has constraints");
  }
}

/// Cross-check at the first 8 states: M against mj_fullM, F against MuJoCo's applied + passive -
/// bias forces, and without constraints qdd against qacc (max-abs error / max-abs value).
void cross_check(eomgen::testing::MujocoRobot& robot, const std::vector<State>& states, const std::vector<int>& driven) {
  const Model::Parameters<double> p;
  double eM = 0, eF = 0, eA = 0;
  Mat M;
  Vec F;
  eomrt::DynamicsWorkspace<Model, double> ws;
  for (int k = 0; k < 8; ++k) {
    const State& s = states[k];
    const Vec applied = applied_forces(s.u, driven);
    robot.forward(s.q, s.qd, applied);
    Model::mass_matrix_and_forcing(0.0, s.q, s.qd, s.u, p, M, F);
    eM = std::max(eM, peers::relative_error(M.data(), robot.mass_matrix().data(), nq * nq));
    const Eigen::VectorXd theirs = applied + robot.passive_forces() - robot.bias_forces();
    eF = std::max(eF, peers::relative_error(F.data(), theirs.data(), nq));
    if (Model::nc == 0) {
      if (our_accelerations<Model>(false, p, ws, s, s.u) != eomrt::DynamicsStatus::ok)
        throw std::runtime_error("our forward dynamics failed");
      eA = std::max(eA, peers::relative_error(ws.qdd.data(), robot.accelerations().data(), nq));
    }
  }
  std::printf("cross-check (8 random states; max-abs error / max-abs value):\n");
  std::printf("  M vs mj_fullM(qM): %.3g   F vs applied + passive - bias: %.3g\n", eM, eF);
  std::printf("RESULT err_M %.3g\nRESULT err_F %.3g\n", eM, eF);
  if (Model::nc == 0) std::printf("  qdd vs qacc: %.3g\nRESULT err_qdd %.3g\n", eA, eA);
}

/// ns per call of our functions and MuJoCo's stages over the pool of states, at zero inputs.
/// MuJoCo's ops copy q, qd into an mjData of their own (2 nq doubles, in its order of degrees of
/// freedom); ours read the pool directly.
void time_calls(const mjModel* m, const std::vector<UrdfJointSummary>& joints, const std::vector<State>& states,
                int rounds) {
  const int pool = static_cast<int>(states.size());
  const std::unique_ptr<mjData, void (*)(mjData*)> data(mj_makeData(m), mj_deleteData);
  mjData* d = data.get();
  std::vector<Eigen::VectorXd> qpos(pool, Eigen::VectorXd(m->nq)), qvel(pool, Eigen::VectorXd(m->nv)),
      qacc(pool, Eigen::VectorXd(m->nv));
  std::vector<int> dof(nq);  // MuJoCo's degree of freedom of each of our coordinates
  for (int i = 0; i < nq; ++i) {
    const int id = mj_name2id(m, mjOBJ_JOINT, joints[i].name.c_str());
    dof[i] = m->jnt_dofadr[id];
    for (int k = 0; k < pool; ++k) {
      qpos[k][m->jnt_qposadr[id]] = states[k].q[i];
      qvel[k][m->jnt_dofadr[id]] = states[k].qd[i];
      qacc[k][m->jnt_dofadr[id]] = states[k].qdd[i];
    }
  }
  const auto set_state = [&](int k) {
    mju_copy(d->qpos, qpos[k].data(), m->nq);
    mju_copy(d->qvel, qvel[k].data(), m->nv);
  };
  // the parameter-only values, computed once as a controller would (every timed call takes them)
  const Model::Constants<double> c{Model::Parameters<double>{}};
  const Inputs u = Inputs::Zero();
  eomrt::DynamicsWorkspace<Model, double> ws;
  Mat M;
  Vec F;
  std::vector<double> x(m->nv);
  std::vector<peers::TimedOp> ops;
  ops.push_back({"ours_MF", "ours: mass_matrix_and_forcing (M, F)", [&](int k) {
                   Model::mass_matrix_and_forcing(0.0, states[k].q, states[k].qd, u, c, M, F);
                   g_sink = g_sink + M(nq - 1, 0) + F(0);
                 }});
  if (Model::nc == 0) {
    ops.push_back({"ours_fd", "ours: eomrt::forward_dynamics_unconstrained (the model's forward_dynamics() where it prefers it)",
                   [&](int k) {
                     our_accelerations<Model>(false, c, ws, states[k], u);
                     g_sink = g_sink + ws.qdd(0);
                   }});
    ops.push_back({"ours_fd_chol", "ours: M, F and the runtime's Cholesky path (pivot-ratio and finiteness tests)",
                   [&](int k) {
                     our_accelerations<Model>(true, c, ws, states[k], u);
                     g_sink = g_sink + ws.qdd(0);
                   }});
  }
  ops.push_back({"mj_MF", "MuJoCo: kinematics + comPos + crb + comVel + rne (qM, qfrc_bias)", [&](int k) {
                   set_state(k);
                   mj_kinematics(m, d);
                   mj_comPos(m, d);
                   mj_crb(m, d);
                   mj_comVel(m, d);
                   mj_rne(m, d, 0, d->qfrc_bias);
                   g_sink = g_sink + d->qM[0] + d->qfrc_bias[0];
                 }});
  if (Model::nc == 0) {
    // the robots' dampers are MuJoCo's passive forces: mj_passive joins the bias here
    ops.push_back({"mj_fd", "MuJoCo: mj_MF + factorM + passive + solveM (qacc = M^-1 (passive - bias))", [&](int k) {
                     set_state(k);
                     mj_kinematics(m, d);
                     mj_comPos(m, d);
                     mj_crb(m, d);
                     mj_factorM(m, d);
                     mj_comVel(m, d);
                     mj_passive(m, d);
                     mj_rne(m, d, 0, d->qfrc_bias);
                     for (int i = 0; i < m->nv; ++i) x[i] = d->qfrc_passive[i] - d->qfrc_bias[i];
                     mj_solveM(m, d, d->qacc, x.data(), 1);
                     g_sink = g_sink + d->qacc[0];
                   }});
    ops.push_back({"mj_forward", "MuJoCo: mj_forward (no geoms, so no collisions)", [&](int k) {
                     set_state(k);
                     mj_forward(m, d);
                     g_sink = g_sink + d->qacc[0];
                   }});
    // the hand-assembled forward dynamics against mj_forward, once
    ops[ops.size() - 2].f(3);
    const std::vector<double> a(d->qacc, d->qacc + m->nv);
    ops.back().f(3);
    std::printf("  mj_fd pipeline vs mj_forward qacc: %.3g (nefc %d)\n",
                peers::relative_error(a.data(), d->qacc, m->nv), d->nefc);
  }

  // 3. the controller functions: inverse dynamics and the tool's position Jacobian
  const int tool = mj_name2id(m, mjOBJ_BODY, EOM_STRING(EOM_TOOL));
  if (tool < 0) throw std::runtime_error("MuJoCo has no body " EOM_STRING(EOM_TOOL));
  Vec tau, total;
  Eigen::Matrix<double, Model::nc, 1> lambda;
  Eigen::Matrix<double, 3, nq> J;
  std::vector<double> jacp(3 * m->nv);
  {  // cross-check at the first 8 states (max-abs error / max-abs value)
    double e_id = 0, e_jac = 0;
    for (int k = 0; k < 8; ++k) {
      set_state(k);
      mju_copy(d->qacc, qacc[k].data(), m->nv);
      mj_inverse(m, d);
      if (d->nefc != 0) throw std::runtime_error("mj_inverse: MuJoCo has constraint rows");
      our_inverse_dynamics<Model>(c, states[k], u, tau, lambda, &total);
      Vec theirs;
      for (int i = 0; i < nq; ++i) theirs[i] = d->qfrc_inverse[dof[i]];
      e_id = std::max(e_id, peers::relative_error(total.data(), theirs.data(), nq));
      // mj_inverse ran mj_kinematics and mj_comPos at this q
      mj_jac(m, d, jacp.data(), nullptr, d->xpos + 3 * tool, tool);
      Model::EOM_NAME(output_jacobian_, EOM_TOOL, _position)(0.0, states[k].q, c, J);
      Eigen::Matrix<double, 3, nq> theirs_J;  // jacp is row-major, nv columns in MuJoCo's order
      for (int r = 0; r < 3; ++r)
        for (int i = 0; i < nq; ++i) theirs_J(r, i) = jacp[r * m->nv + dof[i]];
      e_jac = std::max(e_jac, peers::relative_error(J.data(), theirs_J.data(), 3 * nq));
    }
    std::printf("controller functions (8 random states with accelerations):\n");
    std::printf("  inverse dynamics vs qfrc_inverse: %.3g   %s position Jacobian vs mj_jac jacp: %.3g\n", e_id,
                EOM_STRING(EOM_TOOL), e_jac);
    std::printf("RESULT err_id %.3g\nRESULT err_jac %.3g\n", e_id, e_jac);
  }
  // a second mjData whose position stage is done once (at state 0) before the timing
  const std::unique_ptr<mjData, void (*)(mjData*)> positioned(mj_makeData(m), mj_deleteData);
  mjData* dp = positioned.get();
  mju_copy(dp->qpos, qpos[0].data(), m->nq);
  mj_invPosition(m, dp);
  ops.push_back({"ours_id", Model::nc == 0 ? "ours: inverse_dynamics (tau)" : "ours: inverse_dynamics (tau, lambda)",
                 [&](int k) {
                   our_inverse_dynamics<Model>(c, states[k], u, tau, lambda);
                   g_sink = g_sink + tau(0);
                 }});
  ops.push_back({"mj_inverse", "MuJoCo: mj_inverse (its position, velocity and acceleration stages)", [&](int k) {
                   set_state(k);
                   mju_copy(d->qacc, qacc[k].data(), m->nv);
                   mj_inverse(m, d);
                   g_sink = g_sink + d->qfrc_inverse[0];
                 }});
  ops.push_back({"mj_inv_vel", "MuJoCo: mj_inverseSkip(mjSTAGE_POS), the position stage done beforehand (untimed)",
                 [&](int k) {
                   mju_copy(dp->qvel, qvel[k].data(), m->nv);
                   mju_copy(dp->qacc, qacc[k].data(), m->nv);
                   mj_inverseSkip(m, dp, mjSTAGE_POS, 1);
                   g_sink = g_sink + dp->qfrc_inverse[0];
                 }});
  ops.push_back({"ours_jac", "ours: output_jacobian_" EOM_STRING(EOM_TOOL) "_position", [&](int k) {
                   Model::EOM_NAME(output_jacobian_, EOM_TOOL, _position)(0.0, states[k].q, c, J);
                   g_sink = g_sink + J(0, 0);
                 }});
  ops.push_back({"mj_jac", "MuJoCo: kinematics + comPos + jac (jacp of " EOM_STRING(EOM_TOOL) "'s origin)", [&](int k) {
                   mju_copy(d->qpos, qpos[k].data(), m->nq);
                   mj_kinematics(m, d);
                   mj_comPos(m, d);
                   mj_jac(m, d, jacp.data(), nullptr, d->xpos + 3 * tool, tool);
                   g_sink = g_sink + jacp[0];
                 }});
  peers::print_timings(ops, peers::time_interleaved(ops, rounds, pool), rounds);
}

int run(const char* urdf_path, int rounds) {
  const std::string urdf_text = read_text(urdf_path);
  const std::vector<UrdfJointSummary> joints = joints_of_coordinates(eomgen::testing::read_urdf_summary(urdf_text));
  std::vector<std::string> names;
  for (const auto& j : joints) names.push_back(j.name);
  eomgen::testing::MujocoRobot robot(urdf_text, names);
  const mjModel& m = robot.model();
  std::printf("MuJoCo %s, robot %s: nq = %d, nu = %d, nc = %d; MuJoCo nv = %d, nbody = %d, nM = %d\n",
              mj_versionString(), Model::name, nq, Model::nu, Model::nc, m.nv, m.nbody, m.nM);
  std::printf("RESULT nq %d\nRESULT nc %d\n", nq, Model::nc);
  std::printf("tool: %s\n", EOM_STRING(EOM_TOOL));
  std::mt19937_64 rng(20261205);
  std::vector<State> states;
  for (int k = 0; k < 64; ++k) states.push_back(random_state(joints, rng));
  std::mt19937_64 rng_accelerations(20261206);
  random_accelerations(joints, states, rng_accelerations);
  cross_check(robot, states, coordinates_of_inputs());
  time_calls(&m, joints, states, rounds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s ROBOT.urdf [rounds]\n", argv[0]);
    return 2;
  }
  try {
    return run(argv[1], argc > 2 ? std::atoi(argv[2]) : 21);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
}
