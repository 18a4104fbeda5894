#pragma once
// Shared test helpers: numeric comparison of symbolic results at random states.
#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen::testing {

/// Numeric value of a constant expression (after substitution), as double.
inline double to_double(const GiNaC::ex& e) {
  const GiNaC::ex v = e.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v)) {
    ADD_FAILURE() << "expression is not numeric after substitution: " << v;
    return NAN;
  }
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

/// A random state: every coordinate and rate in [-1.5, 1.5], inputs in [-2, 2], t in [0, 3];
/// parameters at their defaults. Deterministic for a given seed.
inline GiNaC::exmap random_state(const MechanicalSystem& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-1.5, 1.5), input(-2.0, 2.0), time(0.0, 3.0);
  GiNaC::exmap m = s.parameter_defaults();
  m[s.variables().time()] = time(rng);
  for (const auto& c : s.variables().coordinates()) {
    m[c.q] = angle(rng);
    m[c.qd] = angle(rng);
  }
  for (const auto& u : s.variables().inputs()) m[u.symbol] = input(rng);
  return m;
}

/// |a - b| <= tol * max(1, |a|, |b|)
inline ::testing::AssertionResult near_relative(double a, double b, double tol) {
  const double scale = std::max({1.0, std::fabs(a), std::fabs(b)});
  if (std::fabs(a - b) <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " differ by " << std::fabs(a - b)
                                       << " (tolerance " << tol * scale << ")";
}

/// Compares two symbolic matrices entry by entry at a numeric point; `a` may use the
/// intermediates of `za`, `b` plain model symbols.
inline ::testing::AssertionResult matrices_agree_at(const GiNaC::matrix& a, const Subexpressions& za,
                                                    const GiNaC::matrix& b, const GiNaC::exmap& point,
                                                    double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return ::testing::AssertionFailure() << "shapes differ: " << a.rows() << "x" << a.cols() << " vs "
                                         << b.rows() << "x" << b.cols();
  const GiNaC::exmap all = za.evaluate_all(point);
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) {
      const double x = to_double(a(i, j).subs(all, GiNaC::subs_options::no_pattern));
      const double y = to_double(b(i, j).subs(point, GiNaC::subs_options::no_pattern));
      auto r = near_relative(x, y, tol);
      if (!r) return r << " at entry (" << i << "," << j << ")";
    }
  return ::testing::AssertionSuccess();
}

}  // namespace eomgen::testing
