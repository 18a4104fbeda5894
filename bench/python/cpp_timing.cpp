// The C++ side of the Python benchmark of issue 32 (bench/python/python_bench.py compiles and
// runs it; not part of the build): the generated functions a model's Python module calls, timed
// from C++ on the same header, the same states and the same parameters, so that the module's
// cost per call is its C++ cost plus an overhead the script takes as the difference.
//
//   g++ -O2 -DNDEBUG -std=c++17 -I<dir of model.hpp> -I/usr/include/eigen3 \
//       -DMODEL_NS=eomgen_models::cart_pole cpp_timing.cpp -o cpp_timing
//   yes | head -15 | cpp_timing STATES_FILE N SECONDS_PER_ROUND
//
// STATES_FILE holds N states as float64 in the order t[N], Q[N][nq], QD[N][nq], U[N][nu] (what
// the script passes to the module's batch calls). Four operations are timed:
//   fd_one     forward_dynamics at state 0, one call after another (the module's one-state call)
//   mf_one     mass_matrix_and_forcing at state 0, likewise
//   fd_batch   forward_dynamics of the N states, written to an N x nq array (the batch call)
//   mf_batch   mass_matrix_and_forcing of the N states, into N x nq x nq and N x nq arrays
// The one-state calls go through a noinline wrapper, as a call from another translation unit
// is: nothing of a call is hoisted out of the loop that repeats it. The batch loops are inlined,
// as the module's are.
//
// Output, one JSON object a line: first qdd, M and F at state 0 and qdd of the last state of
// the batch (the script's cross-check) and how many calls (passes, for a batch) a round makes,
// each calibrated to about SECONDS_PER_ROUND; then, for each line read on standard input, one
// round: every operation in turn, its ns per call (per state for a batch). The script writes a
// line between its own rounds, so that C++ and Python rounds alternate and other work on a
// shared machine falls on both alike. The program ends at the end of its input.
#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <functional>
#include <string>
#include <vector>

#include "model.hpp"

#ifndef MODEL_NS
#error "define MODEL_NS, the namespace of the generated model (eomgen_models::NAME)"
#endif

namespace {

using Model = MODEL_NS::Model;
constexpr int nq = Model::nq;
constexpr int nu = Model::nu;
using Constants = Model::Constants<double>;
using Vec = Eigen::Matrix<double, nq, 1>;
using Mat = Eigen::Matrix<double, nq, nq, (nq == 1 ? Eigen::ColMajor : Eigen::RowMajor)>;
using Inputs = Eigen::Matrix<double, nu, 1>;
using ConstMap = Eigen::Map<const Vec>;
using ConstInputMap = Eigen::Map<const Inputs>;

volatile double sink = 0;

// the states as the script wrote them
struct States {
  long n = 0;
  std::vector<double> t, q, qd, u;
};

States read_states(const char* path, long n) {
  States s;
  s.n = n;
  s.t.resize(n);
  s.q.resize(n * nq);
  s.qd.resize(n * nq);
  s.u.resize(n * nu);
  std::ifstream in(path, std::ios::binary);
  const auto read = [&in](std::vector<double>& v) {
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
  };
  read(s.t);
  read(s.q);
  read(s.qd);
  read(s.u);
  if (!in) {
    std::fprintf(stderr, "cpp_timing: %s does not hold %ld states of nq = %d, nu = %d\n", path, n, nq, nu);
    std::exit(2);
  }
  return s;
}

__attribute__((noinline)) bool call_fd(double t, const Vec& q, const Vec& qd, const Inputs& u, const Constants& c,
                                       Vec& qdd) {
  return Model::forward_dynamics(t, q, qd, u, c, qdd);
}

__attribute__((noinline)) void call_mf(double t, const Vec& q, const Vec& qd, const Inputs& u, const Constants& c,
                                       Mat& M, Vec& F) {
  Model::mass_matrix_and_forcing(t, q, qd, u, c, M, F);
}

struct Op {
  const char* key;
  std::function<void(long)> run;  // run(n): n calls (one-state ops) or n passes (batches)
  double per = 1;                 // what one unit of run() counts: 1 call, or N states
};

template <class M>
std::string json_array(const M& m) {
  std::string s = "[";
  char buf[64];
  for (int i = 0; i < m.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%.17g", i ? ", " : "", m.data()[i]);
    s += buf;
  }
  return s + "]";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: cpp_timing STATES_FILE N SECONDS_PER_ROUND (then one line on stdin per round)\n");
    return 2;
  }
  const long n = std::atol(argv[2]);
  const double seconds = std::atof(argv[3]);
  if (n < 1 || !(seconds > 0)) {
    std::fprintf(stderr, "cpp_timing: expected N >= 1 and SECONDS_PER_ROUND > 0\n");
    return 2;
  }
  const States s = read_states(argv[1], n);
  const Constants c{Model::Parameters<double>{}};

  // state 0 as the one-state calls take it, and the batches' outputs
  const double t0 = s.t[0];
  const Vec q0 = ConstMap(s.q.data()), qd0 = ConstMap(s.qd.data());
  Inputs u0 = Inputs::Zero();
  if (nu > 0) u0 = ConstInputMap(s.u.data());
  std::vector<double> qdd_out(n * nq), M_out(n * nq * nq), F_out(n * nq);

  std::vector<Op> ops;
  ops.push_back({"fd_one", [&](long calls) {
                   Vec qdd;
                   double sum = 0;
                   for (long i = 0; i < calls; ++i) {
                     call_fd(t0, q0, qd0, u0, c, qdd);
                     sum += qdd(0);
                   }
                   sink = sum;
                 }});
  ops.push_back({"mf_one", [&](long calls) {
                   Mat M;
                   Vec F;
                   double sum = 0;
                   for (long i = 0; i < calls; ++i) {
                     call_mf(t0, q0, qd0, u0, c, M, F);
                     sum += M(0, 0) + F(0);
                   }
                   sink = sum;
                 }});
  ops.push_back({"fd_batch",
                 [&](long passes) {
                   bool regular = true;
                   for (long p = 0; p < passes; ++p)
                     for (long k = 0; k < n; ++k) {
                       Eigen::Map<Vec> qdd(qdd_out.data() + k * nq);
                       regular = Model::forward_dynamics(s.t[k], ConstMap(s.q.data() + k * nq),
                                                         ConstMap(s.qd.data() + k * nq),
                                                         ConstInputMap(nu > 0 ? s.u.data() + k * nu : u0.data()), c,
                                                         qdd) &&
                                 regular;
                     }
                   sink = regular ? qdd_out[0] : -1;
                 },
                 double(n)});
  ops.push_back({"mf_batch",
                 [&](long passes) {
                   for (long p = 0; p < passes; ++p)
                     for (long k = 0; k < n; ++k) {
                       Eigen::Map<Mat> M(M_out.data() + k * nq * nq);
                       Eigen::Map<Vec> F(F_out.data() + k * nq);
                       Model::mass_matrix_and_forcing(s.t[k], ConstMap(s.q.data() + k * nq),
                                                      ConstMap(s.qd.data() + k * nq),
                                                      ConstInputMap(nu > 0 ? s.u.data() + k * nu : u0.data()), c, M, F);
                     }
                   sink = M_out[0] + F_out[0];
                 },
                 double(n)});

  // calibrate: the count of units that takes about `seconds`
  using Clock = std::chrono::steady_clock;
  const auto time_of = [](const Op& op, long units) {
    const auto start = Clock::now();
    op.run(units);
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  std::vector<long> units(ops.size());
  for (size_t o = 0; o < ops.size(); ++o)
    for (long u = 1;; u *= 2) {
      double took = time_of(ops[o], u);
      if (took > seconds / 4 || u > (1L << 30)) {
        took = std::min(took, time_of(ops[o], u));  // once more: the first may have paid for page faults
        units[o] = std::max(1L, long(u * seconds / took));
        break;
      }
    }

  // the cross-check values and the calibration
  Vec qdd;
  const bool regular = call_fd(t0, q0, qd0, u0, c, qdd);
  Mat M;
  Vec F;
  call_mf(t0, q0, qd0, u0, c, M, F);
  ops[2].run(1);  // fills qdd_out
  std::printf("{\"nq\": %d, \"nu\": %d, \"n\": %ld, \"regular\": %s, \"qdd\": %s, \"M\": %s, \"F\": %s, "
              "\"batch_qdd_last\": %s, \"units\": {",
              nq, nu, n, regular ? "true" : "false", json_array(qdd).c_str(), json_array(M).c_str(),
              json_array(F).c_str(), json_array(Eigen::Map<const Vec>(qdd_out.data() + (n - 1) * nq)).c_str());
  for (size_t o = 0; o < ops.size(); ++o) std::printf("%s\"%s\": %ld", o ? ", " : "", ops[o].key, units[o]);
  std::printf("}}\n");
  std::fflush(stdout);

  // one round per line of input
  for (std::string line; std::getline(std::cin, line);) {
    std::printf("{");
    for (size_t o = 0; o < ops.size(); ++o)
      std::printf("%s\"%s\": %.3f", o ? ", " : "", ops[o].key,
                  1e9 * time_of(ops[o], units[o]) / (double(units[o]) * ops[o].per));
    std::printf("}\n");
    std::fflush(stdout);
  }
  return 0;
}
