#pragma once
// The timing harness of the MuJoCo peer programs (mujoco_bench.cpp for the chains,
// mujoco_robots.cpp for the shipped robots): ns per call of several operations measured in
// interleaved rounds, so that other work on a shared machine falls on every operation alike,
// and the relative error both programs report in their cross-checks.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace peers {

/// One timed operation: f(k) works on state k of a pool of states (k < the pool size).
struct TimedOp {
  std::string key, label;
  std::function<void(int)> f;
};

/// The ns per call of an operation over the rounds.
struct Timing {
  double median = 0, minimum = 0;
};

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

/// max |a - b| / max |b| over n entries (max |a - b| where b is zero).
inline double relative_error(const double* a, const double* b, int n) {
  double num = 0, den = 0;
  for (int i = 0; i < n; ++i) {
    num = std::max(num, std::abs(a[i] - b[i]));
    den = std::max(den, std::abs(b[i]));
  }
  return den > 0 ? num / den : num;
}

/// ns per call of each op: a batch of each in turn per round, `rounds` rounds. A batch takes
/// about 2 ms (calibrated per op first) and cycles through states 0 .. pool - 1 (pool: a power
/// of 2).
inline std::vector<Timing> time_interleaved(const std::vector<TimedOp>& ops, int rounds, int pool) {
  using Clock = std::chrono::steady_clock;
  const auto run = [&](const TimedOp& op, long n) {
    const auto t0 = Clock::now();
    for (long i = 0; i < n; ++i) op.f(int(i & (pool - 1)));
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  std::vector<long> iters(ops.size());
  for (size_t o = 0; o < ops.size(); ++o) {
    for (long n = 16;; n *= 2) {
      const double s = run(ops[o], n);
      if (s > 2e-3 || n > (1L << 28)) {
        iters[o] = std::max<long>(16, long(n * 2e-3 / s));
        break;
      }
    }
  }
  std::vector<std::vector<double>> ns(ops.size());
  for (int r = 0; r < rounds; ++r)
    for (size_t o = 0; o < ops.size(); ++o) ns[o].push_back(1e9 * run(ops[o], iters[o]) / double(iters[o]));
  std::vector<Timing> out;
  for (const auto& v : ns) out.push_back({median(v), *std::min_element(v.begin(), v.end())});
  return out;
}

/// Prints the timings, for people and as "RESULT ns_<key> median" and "RESULT nsmin_<key> min"
/// lines for the scripts' tables.
inline void print_timings(const std::vector<TimedOp>& ops, const std::vector<Timing>& timings, int rounds) {
  std::printf("ns per call (median and min of %d interleaved rounds):\n", rounds);
  for (size_t o = 0; o < ops.size(); ++o) {
    const char* key = ops[o].key.c_str();
    std::printf("  %-14s %10.1f %10.1f   %s\n", key, timings[o].median, timings[o].minimum, ops[o].label.c_str());
    std::printf("RESULT ns_%s %.1f\nRESULT nsmin_%s %.1f\n", key, timings[o].median, key, timings[o].minimum);
  }
}

}  // namespace peers
