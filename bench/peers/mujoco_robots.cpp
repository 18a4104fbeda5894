// Peer benchmark: one shipped robot (models/robots/NAME.urdf) as eomgen generates it, against
// MuJoCo 2.2.2 reading the same URDF, prepared as tests/robots/ prepares it
// (tests/support/mujoco_robot.hpp: links kept apart, no geoms, limits or friction loss,
// inertias on exact principal axes) and with its joints mapped to our coordinates by name.
//
// Build (mujoco_robots.sh does this for every robot), on one line:
//   g++ -std=c++17 -O2 -DEOM_HEADER='"ur5.hpp"' -DEOM_NS=ur5 -I<dir of header>
//       -I<repo>/runtime/include -I<repo>/tests -I/usr/include/eigen3
//       mujoco_robots.cpp -lmujoco -ltinyxml2 -o bench_ur5
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
//    ignores <mimic>, so its accelerations are those of another system.
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
  std::vector<Eigen::VectorXd> qpos(pool, Eigen::VectorXd(m->nq)), qvel(pool, Eigen::VectorXd(m->nv));
  for (int i = 0; i < nq; ++i) {
    const int id = mj_name2id(m, mjOBJ_JOINT, joints[i].name.c_str());
    for (int k = 0; k < pool; ++k) {
      qpos[k][m->jnt_qposadr[id]] = states[k].q[i];
      qvel[k][m->jnt_dofadr[id]] = states[k].qd[i];
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
  std::mt19937_64 rng(20261205);
  std::vector<State> states;
  for (int k = 0; k < 64; ++k) states.push_back(random_state(joints, rng));
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
