// Peer benchmark: one eomgen-generated chain model against MuJoCo on the same chain.
//
// Build (mujoco_bench.sh does this for every chain and n):
//   g++ -std=c++17 -O2 -DEOM_HEADER='"planar_chain_8.hpp"' -DEOM_NS=planar_chain \
//       -I<dir of header> -I<repo>/runtime/include -I/usr/include/eigen3 \
//       mujoco_bench.cpp -lmujoco -o bench
// Run:  bench MODEL.xml [rounds]
//
// 1. cross-check at random states (fixed seed): MuJoCo's mj_fullM(qM), -qfrc_bias and qacc
//    after mj_forward against our M, F and qdd (relative max-abs errors); then kinematics
//    (body xmat against the DCMs of docs/conventions.md, tip position and velocity against the
//    model's outputs), which is what pins down the joint axis signs and order;
// 2. ns per call, interleaved rounds, medians (see the op list in main);
// 3. 10 s of RK4 at dt = 1 ms from q = 0.3 (all joint angles; universal: beta = -0.2),
//    qd = 0: wall times (eomrt::simulate, plain eomrt::rk_step loops, mj_step with RK4;
//    interleaved repetitions, median and min) and max |difference| of q, qd at 1 s and 10 s.
// Machine-readable lines start with "RESULT key value".
#include EOM_HEADER

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <eomrt/dynamics_unconstrained.hpp>
#include <eomrt/simulate.hpp>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "interleaved_timing.hpp"

using Model = eomgen_models::EOM_NS::Model;
constexpr int nq = Model::nq;
using Vec = Model::Vector<double>;
using Mat = Model::MassMatrix<double>;
using Clock = std::chrono::steady_clock;

static volatile double g_sink = 0;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MODEL.xml [rounds]\n", argv[0]);
    return 2;
  }
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 21;
  char err[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, err, sizeof err);
  if (!m) {
    std::fprintf(stderr, "mj_loadXML: %s\n", err);
    return 1;
  }
  mjData* d = mj_makeData(m);
  if (m->nq != nq || m->nv != nq) {
    std::fprintf(stderr, "size mismatch: MuJoCo nq %d nv %d, ours %d\n", m->nq, m->nv, nq);
    return 1;
  }
  std::printf("MuJoCo %s (mj_version %d), model %s, nq = %d, nM = %d\n", mj_versionString(),
              mj_version(), Model::name, nq, m->nM);
  std::printf("RESULT nq %d\n", nq);

  const Model::Parameters<double> p;  // the model's defaults = the MJCF's values
  // the parameter-only values, computed once as a controller would (every timed call takes them)
  const Model::Constants<double> c(p);
  const Model::Inputs<double> u = Model::Inputs<double>::Zero();
  const double t = 0;

  // ---- 1. cross-check --------------------------------------------------------------------
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  constexpr int pool = 64;
  std::vector<Vec> Q(pool), QD(pool);
  for (int k = 0; k < pool; ++k)
    for (int i = 0; i < nq; ++i) Q[k](i) = uni(rng), QD[k](i) = 2 * uni(rng);
  {
    double eM = 0, eF = 0, eA = 0, maxpassive = 0;
    std::vector<double> full(nq * nq);
    eomrt::DynamicsWorkspace<Model, double> ws;
    for (int k = 0; k < 8; ++k) {  // 8 random states, worst error reported
      mju_copy(d->qpos, Q[k].data(), nq);
      mju_copy(d->qvel, QD[k].data(), nq);
      mj_forward(m, d);
      mj_fullM(m, full.data(), d->qM);  // row-major dense, symmetric
      if (eomrt::forward_dynamics_unconstrained<Model, double>(p, ws, t, Q[k], QD[k], u) !=
          eomrt::DynamicsStatus::ok) {
        std::fprintf(stderr, "our forward dynamics failed\n");
        return 1;
      }
#ifndef EOM_WITHOUT_MASS_MATRIX
      // a model with forward_dynamics() is solved without M and F: evaluate them to compare
      Model::mass_matrix_and_forcing(t, Q[k], QD[k], u, p, ws.M, ws.F);
      Mat Mt = ws.M.transpose();  // row-major view of ours, to compare with full[]
      std::vector<double> negbias(nq);
      for (int i = 0; i < nq; ++i) negbias[i] = -d->qfrc_bias[i];
      eM = std::max(eM, peers::relative_error(Mt.data(), full.data(), nq * nq));
      eF = std::max(eF, peers::relative_error(ws.F.data(), negbias.data(), nq));
#else
      eM = eF = std::numeric_limits<double>::quiet_NaN();
#endif
      eA = std::max(eA, peers::relative_error(ws.qdd.data(), d->qacc, nq));
      for (int i = 0; i < nq; ++i) maxpassive = std::max(maxpassive, std::abs(d->qfrc_passive[i]));
    }
    std::printf("cross-check (8 random states, q in [-1,1], qd in [-2,2]; max-abs error / max-abs value):\n");
    std::printf("  M vs mj_fullM(qM): %.3g   F vs -qfrc_bias: %.3g   qdd vs qacc: %.3g\n", eM, eF, eA);
    std::printf("  MuJoCo nefc = %d, ncon = %d, max |qfrc_passive| = %g\n", d->nefc, d->ncon, maxpassive);
    std::printf("RESULT err_M %.3g\nRESULT err_F %.3g\nRESULT err_qdd %.3g\n", eM, eF, eA);
  }
  // Kinematic check. M, F and qacc cannot tell a joint axis from its negative, nor hinge x-y
  // from y-x, here: the mirrored chain has the same dynamics in its coordinates (verified:
  // axis -x or swapped axes in the universal MJCF still pass the check above to 1e-15). So
  // compare each body's orientation with the DCMs of docs/conventions.md built from q, and the tip
  // position and velocity with the model's outputs (tip = o_n, tip_velocity, in a).
  {
    using M3 = Eigen::Matrix3d;
    auto C = [](int axis, double x) {  // principal rotations of docs/conventions.md
      const double c = std::cos(x), s = std::sin(x);
      M3 r;
      if (axis == 1) r << 1, 0, 0, 0, c, s, 0, -s, c;
      else if (axis == 2) r << c, 0, -s, 0, 1, 0, s, 0, c;
      else r << c, s, 0, -s, c, 0, 0, 0, 1;
      return r;
    };
    const bool univ = std::string(Model::name).find("universal") != std::string::npos;
    const int nb = univ ? nq / 2 : nq;
    double eR = 0, eTip = 0, eVel = 0;
    Model::OutputVector<double> y;
    std::vector<double> jacp(3 * nq);
    for (int k = 0; k < 8; ++k) {
      mju_copy(d->qpos, Q[k].data(), nq);
      mju_copy(d->qvel, QD[k].data(), nq);
      mj_forward(m, d);
      M3 Cba = M3::Identity();  // C_{b_i a}
      for (int i = 0; i < nb; ++i) {
        Cba = univ ? M3(C(2, Q[k](2 * i + 1)) * C(1, Q[k](2 * i)) * Cba) : M3(C(3, Q[k](i)) * Cba);
        const int body = i + 1;  // body 0 is the world
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> xmat(d->xmat + 9 * body);
        eR = std::max(eR, (M3(xmat) - Cba.transpose()).cwiseAbs().maxCoeff());  // xmat = C_ab
      }
      // tip = lower end of the last rod: body frame offset (0,-l,0) planar, (0,0,-l) universal
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> xn(d->xmat + 9 * nb);
      const Eigen::Vector3d off = univ ? Eigen::Vector3d(0, 0, -p.l) : Eigen::Vector3d(0, -p.l, 0);
      Eigen::Vector3d tip = Eigen::Vector3d(d->xpos + 3 * nb) + M3(xn) * off;
      mj_jac(m, d, jacp.data(), nullptr, tip.data(), nb);
      Eigen::Vector3d vtip = Eigen::Map<Eigen::Matrix<double, 3, nq, nq == 1 ? Eigen::ColMajor : Eigen::RowMajor>>(jacp.data()) * QD[k];
      Model::outputs(t, Q[k], QD[k], u, p, y);
      eTip = std::max(eTip, (tip - y.segment<3>(0)).cwiseAbs().maxCoeff());
      eVel = std::max(eVel, (vtip - y.segment<3>(3)).cwiseAbs().maxCoeff());
    }
    std::printf("kinematics (8 random states, max-abs): xmat vs C_ab from q: %.3g   tip position vs "
                "outputs: %.3g   tip velocity (mj_jac) vs outputs: %.3g\n", eR, eTip, eVel);
    std::printf("RESULT err_R %.3g\nRESULT err_tip %.3g\nRESULT err_vtip %.3g\n", eR, eTip, eVel);
  }

  // ---- 2. ns per call ----------------------------------------------------------------------
  // Each op cycles through the same pool of 64 random states (q, qd); MuJoCo ops include
  // copying q, qd into mjData (2 nq doubles), ours read the pool vectors directly.
  eomrt::DynamicsWorkspace<Model, double> ws;
  Mat M;
  Vec F, qdd;
  Eigen::LLT<Mat> llt;
  std::vector<double> x(nq);
  auto set_state = [&](int k) {
    mju_copy(d->qpos, Q[k].data(), nq);
    mju_copy(d->qvel, QD[k].data(), nq);
  };
  using Op = peers::TimedOp;
  std::vector<Op> ops = {
#ifndef EOM_WITHOUT_MASS_MATRIX
      {"ours_MF", "ours: mass_matrix_and_forcing (M, F)",
       [&](int k) {
         Model::mass_matrix_and_forcing(t, Q[k], QD[k], u, c, M, F);
         g_sink = g_sink + M(nq - 1, 0) + F(0);
       }},
#endif
      {"ours_fd", "ours: eomrt::forward_dynamics_unconstrained (forward_dynamics() where the model prefers it, else M, F, LLT, pivot check, solve)",
       [&](int k) {
         eomrt::forward_dynamics_unconstrained<Model, double>(c, ws, t, Q[k], QD[k], u);
         g_sink = g_sink + ws.qdd(0);
       }},
#ifndef EOM_WITHOUT_MASS_MATRIX
      {"ours_fd_raw", "ours: M, F + Eigen LLT solve (no singularity check)",
       [&](int k) {
         Model::mass_matrix_and_forcing(t, Q[k], QD[k], u, c, M, F);
         llt.compute(M);
         qdd = llt.solve(F);
         g_sink = g_sink + qdd(0);
       }},
#endif
      {"mj_M", "MuJoCo: mj_kinematics + mj_comPos + mj_crb (qM)",
       [&](int k) {
         set_state(k);
         mj_kinematics(m, d);
         mj_comPos(m, d);
         mj_crb(m, d);
         g_sink = g_sink + d->qM[0];
       }},
      {"mj_bias", "MuJoCo: mj_kinematics + mj_comPos + mj_comVel + mj_rne(flg_acc=0)",
       [&](int k) {
         set_state(k);
         mj_kinematics(m, d);
         mj_comPos(m, d);
         mj_comVel(m, d);
         mj_rne(m, d, 0, d->qfrc_bias);
         g_sink = g_sink + d->qfrc_bias[0];
       }},
      {"mj_MF", "MuJoCo: kinematics + comPos + crb + comVel + rne (qM, qfrc_bias)",
       [&](int k) {
         set_state(k);
         mj_kinematics(m, d);
         mj_comPos(m, d);
         mj_crb(m, d);
         mj_comVel(m, d);
         mj_rne(m, d, 0, d->qfrc_bias);
         g_sink = g_sink + d->qM[0] + d->qfrc_bias[0];
       }},
      {"mj_fd", "MuJoCo: mj_MF + mj_factorM + mj_solveM (qacc = M^-1 (-bias))",
       [&](int k) {
         set_state(k);
         mj_kinematics(m, d);
         mj_comPos(m, d);
         mj_crb(m, d);
         mj_factorM(m, d);
         mj_comVel(m, d);
         mj_rne(m, d, 0, d->qfrc_bias);
         for (int i = 0; i < nq; ++i) x[i] = -d->qfrc_bias[i];
         mj_solveM(m, d, d->qacc, x.data(), 1);
         g_sink = g_sink + d->qacc[0];
       }},
      {"mj_forward", "MuJoCo: mj_forward (contacts disabled)",
       [&](int k) {
         set_state(k);
         mj_forward(m, d);
         g_sink = g_sink + d->qacc[0];
       }},
  };
  // verify the hand-assembled MuJoCo forward dynamics against mj_forward once
  {
    auto op = [&](const std::string& key) -> Op& {
      return *std::find_if(ops.begin(), ops.end(), [&](const Op& o) { return o.key == key; });
    };
    op("mj_fd").f(3);
    std::vector<double> a(d->qacc, d->qacc + nq);
    op("mj_forward").f(3);
    std::printf("  mj_fd pipeline vs mj_forward qacc: %.3g\n", peers::relative_error(a.data(), d->qacc, nq));
  }
  const std::vector<peers::Timing> timings = peers::time_interleaved(ops, rounds, pool);
#ifdef EOM_WITHOUT_MASS_MATRIX
  // a chain this long has M and F too large for the compiler: their rows are not measured
  for (const char* key : {"ours_MF", "ours_fd_raw"}) std::printf("RESULT ns_%s nan\nRESULT nsmin_%s nan\n", key, key);
#endif
  peers::print_timings(ops, timings, rounds);

  // ---- 3. simulation -----------------------------------------------------------------------
  using State = eomrt::ModelTypes<Model, double>::State;
  State x0;
  const bool universal = std::string(Model::name).find("universal") != std::string::npos;
  for (int i = 0; i < nq; ++i) x0(i) = universal && i % 2 ? -0.2 : 0.3;
  x0.tail<nq>().setZero();
  const int steps_total = 10000, steps_1s = 1000;
  std::vector<double> wall_ours, wall_mj, wall_loop_fd, wall_loop_raw;
  State ours_1s, ours_10s, mj_1s, mj_10s, loop_fd_10s, loop_raw_10s;
  // plain loops of eomrt::rk_step (rk4 tableau, h = 1e-3, t = s h), without simulate()'s
  // bookkeeping: with the runtime's forward_dynamics_unconstrained, and with a bare LLT solve
  eomrt::DynamicsWorkspace<Model, double> ws_loop;
  Mat M2;
  Vec F2, q2, qd2;
  Eigen::LLT<Mat> llt2;
  auto rhs_fd = [&](double tt, const State& xs, State& dx) {
    q2 = xs.head<nq>();
    qd2 = xs.tail<nq>();
    const bool ok = eomrt::forward_dynamics_unconstrained<Model, double>(c, ws_loop, tt, q2, qd2, u) ==
                    eomrt::DynamicsStatus::ok;
    dx.head<nq>() = qd2;
    dx.tail<nq>() = ws_loop.qdd;
    return ok;
  };
  auto rhs_raw = [&](double tt, const State& xs, State& dx) {
    q2 = xs.head<nq>();
    qd2 = xs.tail<nq>();
#ifndef EOM_WITHOUT_MASS_MATRIX
    Model::mass_matrix_and_forcing(tt, q2, qd2, u, c, M2, F2);
    llt2.compute(M2);
    dx.head<nq>() = qd2;
    dx.tail<nq>() = llt2.solve(F2);
#else
    (void)tt;
    dx.setConstant(std::numeric_limits<double>::quiet_NaN());
#endif
  };
  auto plain_loop = [&](auto& rhs, State& xe) {
    eomrt::RkWorkspace<State, 4> rw(2 * nq);
    xe = x0;
    const auto t0 = Clock::now();
    for (int s = 0; s < steps_total; ++s)
      if (!eomrt::rk_step(eomrt::rk4, rhs, s * 1e-3, xe, 1e-3, rw)) std::abort();
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  const int sim_reps = 5;
  for (int rep = 0; rep < sim_reps; ++rep) {
    {
      eomrt::SimulationOptions<double> o;
      o.integrator = eomrt::Integrator::rk4;
      o.step = 1e-3;
      o.t_end = 10.0;
      o.sample_interval = 1.0;  // observer at 1, 2, ..., 10 s only (each sample = 1 extra eval)
      const auto t0 = Clock::now();
      auto res = eomrt::simulate<Model>(
          p, x0, o, eomrt::ZeroInputs{}, [&](const auto& s) {
            if (std::abs(s.t - 1.0) < 1e-9) ours_1s << s.q, s.qd;
          });
      wall_ours.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      if (res.status != eomrt::SimulationStatus::ok || res.steps != steps_total) {
        std::fprintf(stderr, "our simulation: %s, %lld steps\n", eomrt::to_string(res.status),
                     res.steps);
        return 1;
      }
      ours_10s = res.x;
    }
    {
      const auto t0 = Clock::now();
      mj_resetData(m, d);
      mju_copy(d->qpos, x0.data(), nq);
      mju_zero(d->qvel, nq);
      for (int s = 0; s < steps_total; ++s) {
        mj_step(m, d);
        if (s + 1 == steps_1s) {
          for (int i = 0; i < nq; ++i) mj_1s(i) = d->qpos[i], mj_1s(nq + i) = d->qvel[i];
        }
      }
      wall_mj.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      for (int i = 0; i < nq; ++i) mj_10s(i) = d->qpos[i], mj_10s(nq + i) = d->qvel[i];
      if (std::abs(d->time - 10.0) > 1e-9) std::fprintf(stderr, "MuJoCo time %.17g\n", d->time);
    }
    wall_loop_fd.push_back(plain_loop(rhs_fd, loop_fd_10s));
#ifndef EOM_WITHOUT_MASS_MATRIX
    wall_loop_raw.push_back(plain_loop(rhs_raw, loop_raw_10s));
#else
    wall_loop_raw.push_back(std::numeric_limits<double>::quiet_NaN());
    loop_raw_10s.setConstant(std::numeric_limits<double>::quiet_NaN());
#endif
  }
  const double d1q = (ours_1s.head<nq>() - mj_1s.head<nq>()).cwiseAbs().maxCoeff();
  const double d1v = (ours_1s.tail<nq>() - mj_1s.tail<nq>()).cwiseAbs().maxCoeff();
  const double d10q = (ours_10s.head<nq>() - mj_10s.head<nq>()).cwiseAbs().maxCoeff();
  const double d10v = (ours_10s.tail<nq>() - mj_10s.tail<nq>()).cwiseAbs().maxCoeff();
  const double wo = peers::median(wall_ours), wm = peers::median(wall_mj);
  std::printf("simulation 10 s, RK4, dt 1 ms (median of %d): ours %.4f s, MuJoCo %.4f s\n",
              sim_reps, wo, wm);
  std::printf("  max|dq|, max|dqd| at 1 s: %.3g, %.3g   at 10 s: %.3g, %.3g\n", d1q, d1v, d10q,
              d10v);
  std::printf("  final q1 ours %.15g MuJoCo %.15g\n", ours_10s(0), mj_10s(0));
  const double wlf = peers::median(wall_loop_fd), wlr = peers::median(wall_loop_raw);
  std::printf("  plain rk_step loops: with forward_dynamics_unconstrained %.4f s, with bare LLT %.4f s"
              " (max|dx| at 10 s vs simulate(): %.3g, %.3g)\n",
              wlf, wlr, (loop_fd_10s - ours_10s).cwiseAbs().maxCoeff(),
              (loop_raw_10s - ours_10s).cwiseAbs().maxCoeff());
  std::printf("RESULT sim_loop_fd %.5f\nRESULT sim_loop_raw %.5f\n", wlf, wlr);
  std::printf("RESULT simmin_loop_fd %.5f\nRESULT simmin_loop_raw %.5f\n",
              *std::min_element(wall_loop_fd.begin(), wall_loop_fd.end()),
              *std::min_element(wall_loop_raw.begin(), wall_loop_raw.end()));
  std::printf("RESULT sim_ours %.5f\nRESULT sim_mj %.5f\n", wo, wm);
  std::printf("RESULT simmin_ours %.5f\nRESULT simmin_mj %.5f\n",
              *std::min_element(wall_ours.begin(), wall_ours.end()),
              *std::min_element(wall_mj.begin(), wall_mj.end()));
  std::printf("RESULT dq_1s %.3g\nRESULT dqd_1s %.3g\nRESULT dq_10s %.3g\nRESULT dqd_10s %.3g\n",
              d1q, d1v, d10q, d10v);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
