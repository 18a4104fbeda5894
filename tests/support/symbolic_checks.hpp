#pragma once
// Comparisons of symbolic results, exactly (after expansion or light simplification) or in
// numbers at a point, with a failure that names the entry and both values.
#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <string>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "eomgen/symbolic/subexpressions.hpp"
#include "support/numeric_checks.hpp"

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

/// e with the symbols of `at` replaced by their values, as a real double (a failure otherwise).
inline double value_at(const GiNaC::ex& e, const GiNaC::exmap& at) {
  const GiNaC::ex v = e.subs(at, GiNaC::subs_options::no_pattern).evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real()) {
    ADD_FAILURE() << "not a real number after substitution: " << v;
    return NAN;
  }
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

/// Every entry of m at `at` (see value_at above).
inline Eigen::MatrixXd value_at(const GiNaC::matrix& m, const GiNaC::exmap& at) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = value_at(m(i, j), at);
  return out;
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

namespace detail {

template <class Reduce>
::testing::AssertionResult vanishes(const GiNaC::ex& a, const GiNaC::ex& b, Reduce reduce) {
  const GiNaC::ex d = reduce(a - b);
  if (d.is_zero()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (difference " << d << ")";
}

template <class Reduce>
::testing::AssertionResult entries_vanish(const GiNaC::matrix& a, const GiNaC::matrix& b, Reduce reduce) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return ::testing::AssertionFailure() << "shapes differ: " << a.rows() << "x" << a.cols() << " vs " << b.rows()
                                         << "x" << b.cols();
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) {
      ::testing::AssertionResult r = vanishes(a(i, j), b(i, j), reduce);
      if (!r) return ::testing::AssertionFailure() << "entry (" << i << "," << j << "): " << r.message();
    }
  return ::testing::AssertionSuccess();
}

inline GiNaC::ex expanded(const GiNaC::ex& d) { return d.expand(); }

// sin and cos of a sum written out by the addition theorems (the derivation keeps a run of
// rotations about one axis as one angle, sin(q1 + q2); a hand derivation may not)
struct SplitAngleSums : GiNaC::map_function {
  GiNaC::ex operator()(const GiNaC::ex& e) override {
    const GiNaC::ex x = e.map(*this);
    const std::string name = GiNaC::is_a<GiNaC::function>(x) ? GiNaC::ex_to<GiNaC::function>(x).get_name() : "";
    const bool sine = name == "sin", cosine = name == "cos";
    if ((!sine && !cosine) || !GiNaC::is_a<GiNaC::add>(x.op(0))) return x;
    const GiNaC::ex first = x.op(0).op(0), rest = x.op(0) - first;
    const GiNaC::ex s1 = GiNaC::sin(first), c1 = GiNaC::cos(first);
    const GiNaC::ex s2 = (*this)(GiNaC::sin(rest)), c2 = (*this)(GiNaC::cos(rest));
    return sine ? s1 * c2 + c1 * s2 : c1 * c2 - s1 * s2;
  }
};

inline GiNaC::ex simplified(const GiNaC::ex& d) {
  SplitAngleSums split;
  return simplify_for_display(split(d));
}

}  // namespace detail

/// a - b expands to zero, entry by entry: the same polynomial in the same functions.
inline ::testing::AssertionResult equal_after_expansion(const GiNaC::matrix& a, const GiNaC::matrix& b) {
  return detail::entries_vanish(a, b, detail::expanded);
}
inline ::testing::AssertionResult equal_after_expansion(const GiNaC::ex& a, const GiNaC::ex& b) {
  return detail::vanishes(a, b, detail::expanded);
}

/// a - b is zero after expansion, the addition theorems and sin^2 + cos^2 = 1 (simplify_for_display),
/// entry by entry.
inline ::testing::AssertionResult equal_after_simplification(const GiNaC::matrix& a, const GiNaC::matrix& b) {
  return detail::entries_vanish(a, b, detail::simplified);
}
inline ::testing::AssertionResult equal_after_simplification(const GiNaC::ex& a, const GiNaC::ex& b) {
  return detail::vanishes(a, b, detail::simplified);
}

/// Every entry of m is zero after expansion and sin^2 + cos^2 = 1.
inline ::testing::AssertionResult simplifies_to_zero(const GiNaC::matrix& m) {
  return equal_after_simplification(m, GiNaC::matrix(m.rows(), m.cols()));
}

}  // namespace eomgen::testing
