// Derivation benchmark: builds two families of chains, derives their equations of motion with
// derive_equations (shared intermediates) and with derive_equations_literally (the naive
// reference that differentiates the Lagrangian), and prints one markdown table per family.
//
//   derive_bench          full run (planar chain n = 2..32, universal-joint chain n = 1..8)
//   derive_bench --quick  small n only, as a smoke test
//
// Before timing anything it checks the models numerically (a single rod about its pin has
// M = m l^2 / 3, and both derivations agree on small chains) and aborts if a check fails, so
// the benchmark cannot time a wrong model.
#include <cln/version.h>
#include <fmt/format.h>
#include <ginac/ginac.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "chain_models.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/literal_lagrange.hpp"
#include "eomgen/mechanics/mechanical_system.hpp"

#ifndef EOMGEN_BENCH_BUILD_TYPE
#define EOMGEN_BENCH_BUILD_TYPE "unknown"
#endif

namespace {

using eomgen::MechanicalSystem;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// timing

// Repeat small cases until a cell's timed runs take about target_seconds in total, with at
// least min_repeats runs. The full run asks for more than the 50 ms minimum so that medians
// stay stable on a shared 2-core machine; --quick uses the minimum.
struct RepeatPolicy {
  double target_seconds = 0.2;
  int min_repeats = 5;
};
RepeatPolicy repeat_policy;
constexpr double kSingleRunSeconds = 1.0;     // a first run this long is the only sample
constexpr int kMaxRepeats = 2000;
constexpr double kLiteralCapSeconds = 5.0;    // no literal run after one that took this long
// The literal derivation grows about exponentially with n, and the n of the table step by 2 to
// 8, so "the previous n took under 5 s" alone could start a run of many minutes. It is also
// skipped when the exponential extrapolation from the two previous literal runs exceeds this.
constexpr double kLiteralProjectedCapSeconds = 30.0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Timing {
  double median = 0;  // seconds
  int runs = 0;
};

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// Times f(). The first call is a warm-up whose result is returned (for counting and checks);
// unless it was slow, f is then called `repeats` more times, where repeats is chosen so that
// the timed calls take about repeat_policy.target_seconds in total (at least min_repeats),
// and the median of those is reported. A slow first call is the single sample. Only the call
// itself is timed: each result is destroyed after the clock stops.
template <class F>
auto measure(F&& f) -> std::pair<Timing, decltype(f())> {
  auto start = Clock::now();
  auto first = f();
  const double t1 = seconds_since(start);
  if (t1 >= kSingleRunSeconds) return {Timing{t1, 1}, std::move(first)};
  const double guess = std::ceil(repeat_policy.target_seconds / std::max(t1, 1e-7));
  const int repeats =
      static_cast<int>(std::clamp(guess, double(repeat_policy.min_repeats), double(kMaxRepeats)));
  std::vector<double> samples;
  samples.reserve(static_cast<std::size_t>(repeats));
  for (int i = 0; i < repeats; ++i) {
    start = Clock::now();
    auto result = f();
    samples.push_back(seconds_since(start));
  }
  return {Timing{median_of(samples), repeats}, std::move(first)};
}

// ---------------------------------------------------------------------------------------------
// tree size: every GiNaC node (add, mul, power, function, symbol, number...) counts one, and a
// subtree used twice counts twice. Memoized on node identity, so shared subtrees are walked
// once; the memo keeps each node alive, so an address cannot be reused by another node.

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t top = std::numeric_limits<std::uint64_t>::max();
  return a > top - b ? top : a + b;
}

class NodeCounter {
 public:
  std::uint64_t count(const GiNaC::ex& e) {
    const GiNaC::basic* key = &GiNaC::ex_to<GiNaC::basic>(e);
    if (auto it = memo_.find(key); it != memo_.end()) return it->second.second;
    std::uint64_t total = 1;
    for (std::size_t i = 0; i < e.nops(); ++i) total = saturating_add(total, count(e.op(i)));
    memo_.emplace(key, std::make_pair(e, total));
    return total;
  }
  std::uint64_t count(const GiNaC::matrix& m) {
    std::uint64_t total = 0;
    for (unsigned i = 0; i < m.rows(); ++i)
      for (unsigned j = 0; j < m.cols(); ++j) total = saturating_add(total, count(m(i, j)));
    return total;
  }

 private:
  std::unordered_map<const GiNaC::basic*, std::pair<GiNaC::ex, std::uint64_t>> memo_;
};

// ---------------------------------------------------------------------------------------------
// numeric checks

[[noreturn]] void fail(const std::string& message) {
  std::fflush(stdout);
  std::fprintf(stderr, "derive_bench: sanity check failed: %s\n", message.c_str());
  std::exit(EXIT_FAILURE);
}

double to_double(const GiNaC::ex& value, const std::string& what) {
  if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
  {
    std::ostringstream text;
    text << value;
    fail(fmt::format("{} did not evaluate to a real number: {}", what, text.str()));
  }
  return GiNaC::ex_to<GiNaC::numeric>(value).to_double();
}

double parameter_value(const MechanicalSystem& s, const std::string& name) {
  for (const auto& p : s.variables().parameters())
    if (p.name == name) return p.default_value;
  fail(fmt::format("the model has no parameter '{}'", name));
}

// parameters at their defaults, q_k and qd_k at an arbitrary non-special state, t = 0
GiNaC::exmap numeric_state(const MechanicalSystem& s) {
  GiNaC::exmap values = s.parameter_defaults();
  values[s.variables().time()] = 0;
  const auto& coords = s.variables().coordinates();
  for (std::size_t k = 0; k < coords.size(); ++k) {
    values[coords[k].q] = GiNaC::numeric(3 + 2 * static_cast<int>(k), 10);       // 0.3, 0.5, ...
    values[coords[k].qd] = GiNaC::numeric(7 - 3 * static_cast<int>(k), 10);     // 0.7, 0.4, ...
  }
  return values;
}

bool close(double a, double b, double tolerance = 1e-9) {
  return std::abs(a - b) <= tolerance * std::max({1.0, std::abs(a), std::abs(b)});
}

// A single planar rod pinned at its end: M(0,0) = m (l/2)^2 + m l^2/12 = m l^2 / 3.
void check_single_rod() {
  const MechanicalSystem s = eomgen::bench::planar_chain(1);
  const eomgen::EquationsOfMotion eom = eomgen::derive_equations(s);
  const double m = parameter_value(s, "m"), l = parameter_value(s, "l");
  const double got = to_double(eom.subexpressions.evaluate(eom.mass_matrix(0, 0), numeric_state(s)),
                               "planar n=1 M(0,0)");
  const double want = m * l * l / 3;
  if (!close(got, want))
    fail(fmt::format("planar chain n=1: M(0,0) = {} but m l^2/3 = {}", got, want));
  fmt::print("- planar chain n=1: M(0,0) = {:.6g} = m l^2/3 (about the pin)\n", got);
}

// A single box hung from a universal joint, at v = 0 (any u):
// M = diag(J11 + m (l/2)^2, J22 + m (l/2)^2).
void check_single_universal_body() {
  const MechanicalSystem s = eomgen::bench::universal_joint_chain(1);
  const eomgen::EquationsOfMotion eom = eomgen::derive_equations(s);
  const double m = parameter_value(s, "m"), l = parameter_value(s, "l"), h = parameter_value(s, "h");
  GiNaC::exmap values = numeric_state(s);
  values[s.variables().coordinates()[1].q] = 0;  // v1 = 0
  const double transverse = m * (l * l + h * h) / 12 + m * l * l / 4;
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned j = 0; j < 2; ++j) {
      const double got = to_double(eom.subexpressions.evaluate(eom.mass_matrix(i, j), values),
                                   "universal n=1 M");
      const double want = i == j ? transverse : 0.0;
      if (!close(got, want))
        fail(fmt::format("universal-joint chain n=1 at v=0: M({},{}) = {} but expected {}", i, j, got, want));
    }
  fmt::print("- universal-joint chain n=1 at v1=0: M = diag(J11 + m l^2/4, J22 + m l^2/4) = {:.6g} I\n",
             transverse);
}

// derive_equations and derive_equations_literally agree numerically on M and F.
void check_agreement(const std::string& name, const MechanicalSystem& s) {
  const eomgen::EquationsOfMotion eom = eomgen::derive_equations(s);
  const eomgen::LiteralLagrangeEquations lit = eomgen::derive_equations_literally(s);
  const GiNaC::exmap values = numeric_state(s);
  const GiNaC::exmap all = eom.subexpressions.evaluate_all(values);
  auto ours = [&](const GiNaC::ex& e) {
    return to_double(e.subs(all, GiNaC::subs_options::no_pattern).evalf(), name + " (ours)");
  };
  auto literal = [&](const GiNaC::ex& e) {
    return to_double(e.subs(values, GiNaC::subs_options::no_pattern).evalf(), name + " (literal)");
  };
  const unsigned n = eom.mass_matrix.rows();
  for (unsigned i = 0; i < n; ++i) {
    for (unsigned j = 0; j < n; ++j) {
      const double a = ours(eom.mass_matrix(i, j)), b = literal(lit.mass_matrix(i, j));
      if (!close(a, b)) fail(fmt::format("{}: M({},{}) = {} but the literal derivation gives {}", name, i, j, a, b));
    }
    const double a = ours(eom.forcing(i, 0)), b = literal(lit.forcing(i, 0));
    if (!close(a, b)) fail(fmt::format("{}: F({}) = {} but the literal derivation gives {}", name, i, a, b));
  }
  fmt::print("- {}: M and F agree with the literal Lagrangian derivation at a random state\n", name);
}

// ---------------------------------------------------------------------------------------------
// report

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

// the 1, 5 and 15 minute load averages: other work on the machine shows up in the timings
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  if (!(in >> one >> five >> fifteen)) return "unknown";
  return one + " " + five + " " + fifteen;
}

std::string ms(double seconds) {
  const double v = seconds * 1e3;
  if (v < 1) return fmt::format("{:.3f}", v);
  if (v < 100) return fmt::format("{:.2f}", v);
  return fmt::format("{:.0f}", v);
}

std::string count_text(std::uint64_t n) {
  return n == std::numeric_limits<std::uint64_t>::max() ? std::string(">= 2^64") : std::to_string(n);
}

void print_machine(bool quick) {
  fmt::print("# eomgen derivation benchmark{}\n\n", quick ? " (--quick)" : "");
  fmt::print("- machine: nproc {}, CPU {}, load average at start {}\n", sysconf(_SC_NPROCESSORS_ONLN),
             cpu_model(), load_average());
  fmt::print("- compiler: {}{}, build type {}, assertions {}\n", 
#if defined(__clang__)
             "clang ",
#elif defined(__GNUC__)
             "GCC ",
#else
             "",
#endif
             __VERSION__, EOMGEN_BENCH_BUILD_TYPE,
#ifdef NDEBUG
             "off"
#else
             "on"
#endif
  );
  fmt::print("- GiNaC {}.{}.{}, CLN {}.{}.{}\n", GINACLIB_MAJOR_VERSION, GINACLIB_MINOR_VERSION,
             GINACLIB_MICRO_VERSION, CL_VERSION_MAJOR, CL_VERSION_MINOR, CL_VERSION_PATCHLEVEL);
  fmt::print("- timing: median of repeated runs after one warm-up; small cases repeat until a cell\n"
             "  takes >= {:.0f} ms (at least {} runs); a first run over {:.0f} s is the single sample.\n"
             "  The literal derivation runs while the previous n took under {:.0f} s and the\n"
             "  exponential extrapolation from the two previous literal runs stays under {:.0f} s.\n"
             "  naive/ours is the ratio of the median derivation times.\n",
             repeat_policy.target_seconds * 1e3, repeat_policy.min_repeats, kSingleRunSeconds, kLiteralCapSeconds,
             kLiteralProjectedCapSeconds);
  fmt::print("- nodes: GiNaC tree size (every node counts, shared subtrees count each time they\n"
             "  occur) of all n x n entries of M, the n entries of F and the right-hand sides of the\n"
             "  intermediate definitions.\n\n");
}

struct Chain {
  std::string title;
  std::function<MechanicalSystem(std::size_t)> build;
  std::size_t dof_per_n;
  std::vector<std::size_t> sizes;
};

void run_chain(const Chain& chain) {
  fmt::print("## {}\n\n", chain.title);
  fmt::print("| n | dof | build [ms] | derive [ms] (runs) | defs | nodes M | nodes F | nodes defs "
             "| nodes total | literal [ms] (runs) | literal nodes M+F | naive/ours |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::fflush(stdout);
  std::string literal_skip;  // why the literal derivation no longer runs, once it stops
  std::vector<std::pair<std::size_t, double>> literal_history;  // (n, median seconds)
  for (const std::size_t n : chain.sizes) {
    auto [build_time, system] = measure([&] { return chain.build(n); });
    if (system.variables().coordinate_count() != n * chain.dof_per_n)
      fail(fmt::format("{} n={}: {} coordinates, expected {}", chain.title, n,
                       system.variables().coordinate_count(), n * chain.dof_per_n));
    const MechanicalSystem& s = system;

    auto [derive_time, eom] = measure([&] { return eomgen::derive_equations(s); });
    NodeCounter counter;
    const std::uint64_t nodes_m = counter.count(eom.mass_matrix);
    const std::uint64_t nodes_f = counter.count(eom.forcing);
    std::uint64_t nodes_defs = 0;
    for (const auto& d : eom.subexpressions.definitions()) nodes_defs += counter.count(d.value);

    std::string literal_nodes = "-", ratio = "-";
    if (literal_skip.empty() && literal_history.size() >= 2) {
      const auto [n0, t0] = literal_history[literal_history.size() - 2];
      const auto [n1, t1] = literal_history.back();
      const double per_n = std::pow(t1 / t0, 1.0 / (double(n1) - double(n0)));
      const double projected = t1 * std::pow(per_n, double(n) - double(n1));
      if (projected >= kLiteralProjectedCapSeconds)
        literal_skip = fmt::format("skipped: proj. > {:.0f} s", kLiteralProjectedCapSeconds);
    }
    std::string literal_cell = literal_skip;
    if (literal_skip.empty()) {
      auto [literal_time, lit] = measure([&] { return eomgen::derive_equations_literally(s); });
      NodeCounter literal_counter;
      literal_nodes = count_text(
          saturating_add(literal_counter.count(lit.mass_matrix), literal_counter.count(lit.forcing)));
      literal_cell = fmt::format("{} ({})", ms(literal_time.median), literal_time.runs);
      ratio = fmt::format("{:.1f}", literal_time.median / derive_time.median);
      literal_history.emplace_back(n, literal_time.median);
      if (literal_time.median >= kLiteralCapSeconds)
        literal_skip = fmt::format("skipped: prev > {:.0f} s", kLiteralCapSeconds);
    }

    fmt::print("| {} | {} | {} | {} ({}) | {} | {} | {} | {} | {} | {} | {} | {} |\n", n,
               n * chain.dof_per_n, ms(build_time.median), ms(derive_time.median), derive_time.runs,
               eom.subexpressions.size(), nodes_m, nodes_f, nodes_defs, nodes_m + nodes_f + nodes_defs,
               literal_cell, literal_nodes, ratio);
    std::fflush(stdout);
  }
  fmt::print("\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      quick = true;
    } else if (arg == "--help" || arg == "-h") {
      std::printf("usage: %s [--quick]\n  --quick  small chains only (smoke test)\n", argv[0]);
      return EXIT_SUCCESS;
    } else {
      std::fprintf(stderr, "%s: unknown argument '%s' (usage: %s [--quick])\n", argv[0], arg.c_str(), argv[0]);
      return 2;
    }
  }
  if (quick) repeat_policy = RepeatPolicy{0.05, 3};
  const auto start = Clock::now();
  print_machine(quick);

  fmt::print("Sanity checks (abort on failure):\n\n");
  check_single_rod();
  check_single_universal_body();
  check_agreement("planar chain n=3", eomgen::bench::planar_chain(3));
  check_agreement("universal-joint chain n=2", eomgen::bench::universal_joint_chain(2));
  fmt::print("\n");

  const std::vector<Chain> chains = {
      {"Planar chain of n rods (1 dof per joint)", eomgen::bench::planar_chain, 1,
       quick ? std::vector<std::size_t>{2, 4} : std::vector<std::size_t>{2, 4, 8, 12, 16, 24, 32}},
      {"3D chain of n bodies with universal joints (2 dof per joint)", eomgen::bench::universal_joint_chain, 2,
       quick ? std::vector<std::size_t>{1, 2} : std::vector<std::size_t>{1, 2, 4, 6, 8}},
  };
  for (const Chain& chain : chains) run_chain(chain);

  fmt::print("Total wall time: {:.1f} s, load average at end {}\n", seconds_since(start), load_average());
  return EXIT_SUCCESS;
}
