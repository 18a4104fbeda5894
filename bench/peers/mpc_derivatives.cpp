// Benchmark of the derivatives for MPC (issue 36): one model generated with --linearization
// (a chain or a shipped robot), against its own forward dynamics and against MuJoCo 2.2.2's
// mjd_transitionFD on the same system with the same integrator.
//
// Build (mpc_derivatives.sh does this for every case), on one line:
//   g++ -std=c++17 -O2 -DEOM_HEADER='"ur5.hpp"' -DEOM_NS=ur5 -I<dir of header>
//       -I<repo>/runtime/include -I<repo>/tests -I/usr/include/eigen3
//       mpc_derivatives.cpp -lmujoco -ltinyxml2 -o mpc_ur5
// Run:  mpc_ur5 MODEL.{xml,urdf} [rounds]
//   MODEL.xml: a chain as mujoco_chains.py writes it, MuJoCo's joints in the order of our
//   coordinates; MODEL.urdf: a shipped robot, prepared as the robot tests prepare it
//   (tests/support/mujoco_robot.hpp), its joints found by our coordinates' names.
//
// 1. cross-check at 4 random states: our Phi = dx_next/dx of one RK4 step (eomrt::step_derivatives)
//    against MuJoCo's A of mjd_transitionFD (RK4, centered differences) on the state
//    [q; qd] (max-abs error / max-abs value, worst state);
// 2. ns per call, interleaved rounds over a pool of 64 states (q and qd uniform in [-1, 1], zero
//    input; medians and minima), keys in the RESULT lines: our forward_dynamics (forward),
//    forward_dynamics_derivatives (derivatives), eomrt::linearization (linearize) and
//    eomrt::step_derivatives with RK4 (step), all with the model's Constants; the linearization
//    as a header without forward_dynamics_derivatives takes it (terms: linearization_terms at
//    the accelerations from M's Cholesky factor, then -M^-1 [K, D] and M^-1 B_u); MuJoCo's
//    mj_forward and mjd_transitionFD (transitionFD: RK4, forward differences, eps 1e-6), each
//    preceded by copying the state into its mjData.
// The step is h = 1 ms in both. Machine-readable lines start with "RESULT key value".
#include EOM_HEADER

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <eomrt/linearization.hpp>
#include <eomrt/step_derivatives.hpp>
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
using State = Eigen::Matrix<double, 2 * nq, 1>;
constexpr double step = 1e-3;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The model MuJoCo compiles from the file: a chain's MJCF as it is, a URDF prepared as the robot
// tests prepare it (through a virtual file, so nothing is written)
mjModel* load(const std::string& path) {
  char error[1000] = "";
  mjModel* m = nullptr;
  if (path.size() > 5 && path.compare(path.size() - 5, 5, ".urdf") == 0) {
    mju_user_warning = [](const char*) {};
    const std::string prepared = eomgen::testing::prepare_urdf_for_mujoco(read_text(path));
    const auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    const char* file = "robot.urdf";
    if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(prepared.size())) != 0)
      throw std::runtime_error("cannot make MuJoCo's virtual file");
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], prepared.data(), prepared.size());
    m = mj_loadXML(file, vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
  } else {
    m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  }
  if (!m) throw std::runtime_error(std::string("MuJoCo refuses the model: ") + error);
  if (m->nq != nq || m->nv != nq) throw std::runtime_error("MuJoCo's model has other degrees of freedom than ours");
  return m;
}

// MuJoCo's degree of freedom (= its qpos address: hinges and slides only) of each of our
// coordinates: by name for a robot, in order for a chain
std::vector<int> dofs_of_coordinates(const mjModel* m, bool by_name) {
  std::vector<int> dof(nq);
  for (int i = 0; i < nq; ++i) {
    if (!by_name) {
      dof[i] = i;
      continue;
    }
    const int id = mj_name2id(m, mjOBJ_JOINT, Model::coordinate_names[i]);
    if (id < 0) throw std::runtime_error(std::string("MuJoCo has no joint ") + Model::coordinate_names[i]);
    if (m->jnt_qposadr[id] != m->jnt_dofadr[id]) throw std::runtime_error("a joint with qpos and dof apart");
    dof[i] = m->jnt_dofadr[id];
  }
  return dof;
}

int run(const std::string& path, int rounds) {
  mjModel* m = load(path);
  const std::unique_ptr<mjModel, void (*)(mjModel*)> model(m, mj_deleteModel);
  const std::unique_ptr<mjData, void (*)(mjData*)> data(mj_makeData(m), mj_deleteData);
  mjData* d = data.get();
  m->opt.timestep = step;
  m->opt.integrator = mjINT_RK4;
  const std::vector<int> dof = dofs_of_coordinates(m, path.size() > 5 && path.compare(path.size() - 5, 5, ".urdf") == 0);
  const int na = m->na, ns = 2 * m->nv + na;
  std::printf("MuJoCo %s, %s: nq = %d, nu = %d (MuJoCo's nu = %d)\n", mj_versionString(), Model::name, nq, Model::nu,
              m->nu);
  std::printf("RESULT nq %d\n", nq);

  constexpr int pool = 64;
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<State> states(pool);
  for (State& x : states)
    for (int i = 0; i < 2 * nq; ++i) x(i) = value(rng);
  std::vector<std::vector<double>> qpos(pool, std::vector<double>(nq)), qvel(pool, std::vector<double>(nq));
  for (int k = 0; k < pool; ++k)
    for (int i = 0; i < nq; ++i) qpos[k][dof[i]] = states[k](i), qvel[k][dof[i]] = states[k](nq + i);
  const auto set_state = [&](int k) {
    mju_copy(d->qpos, qpos[k].data(), nq);
    mju_copy(d->qvel, qvel[k].data(), nq);
    mju_zero(d->act, na);
    mju_zero(d->ctrl, m->nu);
    d->time = 0;
  };

  const Model::Constants<double> c{Model::Parameters<double>{}};
  const Inputs u = Inputs::Zero();
  static eomrt::LinearizationWorkspace<Model, double> linearization;
  static eomrt::StepDerivativesWorkspace<Model, 4> step_ws;
  Vec qdd;
  Eigen::Matrix<double, nq, nq> by_q, by_qd;
  Eigen::Matrix<double, nq, Model::nu> by_u;
  std::vector<double> A(static_cast<std::size_t>(ns) * ns), B(static_cast<std::size_t>(ns) * std::max(m->nu, 1));

  // 1. Phi against MuJoCo's A (row-major, MuJoCo's order of degrees of freedom)
  double error_phi = 0;
  for (int k = 0; k < 4; ++k) {
    if (eomrt::step_derivatives<Model>(eomrt::rk4, c, step_ws, 0.0, step, states[k], u) != eomrt::DynamicsStatus::ok)
      throw std::runtime_error("our step derivatives failed");
    set_state(k);
    mjd_transitionFD(m, d, 1e-6, 1, A.data(), B.data(), nullptr, nullptr);
    Eigen::Matrix<double, 2 * nq, 2 * nq> theirs;
    for (int r = 0; r < 2 * nq; ++r)
      for (int s = 0; s < 2 * nq; ++s) {
        const int mr = r < nq ? dof[r] : m->nv + dof[r - nq], ms = s < nq ? dof[s] : m->nv + dof[s - nq];
        theirs(r, s) = A[static_cast<std::size_t>(mr) * ns + ms];
      }
    error_phi = std::max(error_phi, peers::relative_error(step_ws.Phi.data(), theirs.data(), 4 * nq * nq));
  }
  std::printf("cross-check (4 states): Phi of one RK4 step vs mjd_transitionFD's A (centered): %.3g\n", error_phi);
  std::printf("RESULT err_phi %.3g\n", error_phi);

  // 2. timings
  double sink = 0;
  std::vector<peers::TimedOp> ops;
  ops.push_back({"forward", "our forward_dynamics", [&](int k) {
                   Model::forward_dynamics(0.0, states[k].head<nq>(), states[k].tail<nq>(), u, c, qdd);
                   sink += qdd(0);
                 }});
  ops.push_back({"derivatives", "our forward_dynamics_derivatives", [&](int k) {
                   Model::forward_dynamics_derivatives(0.0, states[k].head<nq>(), states[k].tail<nq>(), u, c, by_q,
                                                       by_qd, by_u);
                   sink += by_q(0, 0);
                 }});
  ops.push_back({"linearize", "eomrt::linearization", [&](int k) {
                   const Vec q = states[k].head<nq>(), qd = states[k].tail<nq>();
                   eomrt::linearization<Model>(c, linearization, 0.0, q, qd, u);
                   sink += linearization.A(nq, 0);
                 }});
  // the path before forward_dynamics_derivatives: linearization_terms at qdd0 (from M's Cholesky
  // factor) and the three solves with the factor, as eomrt::linearization takes for a header
  // without the derivatives
  ops.push_back({"terms", "linearization_terms, Cholesky and solves", [&](int k) {
                   const Vec q = states[k].head<nq>(), qd = states[k].tail<nq>();
                   eomrt::second_order_linearization<Model>(c, linearization, 0.0, q, qd, u);
                   eomrt::detail::write_first_order_form(linearization.dynamics.mass_llt, linearization.terms,
                                                         linearization.A, linearization.B);
                   sink += linearization.A(nq, 0);
                 }});
  ops.push_back({"step", "eomrt::step_derivatives (RK4)", [&](int k) {
                   eomrt::step_derivatives<Model>(eomrt::rk4, c, step_ws, 0.0, step, states[k], u);
                   sink += step_ws.Phi(0, 0);
                 }});
  ops.push_back({"mj_forward", "MuJoCo mj_forward", [&](int k) {
                   set_state(k);
                   mj_forward(m, d);
                   sink += d->qacc[0];
                 }});
  ops.push_back({"transitionFD", "MuJoCo mjd_transitionFD (RK4, forward)", [&](int k) {
                   set_state(k);
                   mjd_transitionFD(m, d, 1e-6, 0, A.data(), m->nu > 0 ? B.data() : nullptr, nullptr, nullptr);
                   sink += A[0];
                 }});
  peers::print_timings(ops, peers::time_interleaved(ops, rounds, pool), rounds);
  std::printf("(checksum %g)\n", sink == 12345.678 ? 1.0 : 0.0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MODEL.{xml,urdf} [rounds]\n", argv[0]);
    return 2;
  }
  try {
    return run(argv[1], argc > 2 ? std::atoi(argv[2]) : 21);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
}
