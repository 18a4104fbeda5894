#pragma once
// Comparisons of numbers and Eigen matrices for EXPECT_TRUE, with a failure that says where
// and by how much two values differ:
//   EXPECT_TRUE(matrices_near(lin.A, A, 1e-12));
//   EXPECT_TRUE(matrices_near_relative(generated.B, reference.B, 1e-6)) << "B";
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace eomgen::testing {

/// |a - b| <= tol * max(1, |a|, |b|)
inline ::testing::AssertionResult near_relative(double a, double b, double tol) {
  const double scale = std::max({1.0, std::fabs(a), std::fabs(b)});
  if (std::fabs(a - b) <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " differ by " << std::fabs(a - b)
                                       << " (tolerance " << tol * scale << ")";
}

namespace detail {

// An entry NaN in both matrices agrees (both are undefined there, as where a generated
// function and the symbolic value are both NaN); NaN in one of them only is a difference.
inline ::testing::AssertionResult entries_within(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected,
                                                 double tolerance) {
  if (actual.rows() != expected.rows() || actual.cols() != expected.cols())
    return ::testing::AssertionFailure() << "shapes differ: " << actual.rows() << "x" << actual.cols() << " vs "
                                         << expected.rows() << "x" << expected.cols() << " expected";
  Eigen::Index worst_i = -1, worst_j = -1;
  double worst = 0;
  for (Eigen::Index j = 0; j < actual.cols(); ++j)
    for (Eigen::Index i = 0; i < actual.rows(); ++i) {
      const double a = actual(i, j), e = expected(i, j);
      if (std::isnan(a) && std::isnan(e)) continue;
      const double gap = std::isnan(a) || std::isnan(e) ? INFINITY : std::fabs(a - e);
      if (worst_i < 0 || gap > worst) {
        worst = gap;
        worst_i = i;
        worst_j = j;
      }
    }
  if (worst_i < 0 || worst <= tolerance) return ::testing::AssertionSuccess();
  const Eigen::IOFormat rows(Eigen::FullPrecision, 0, ", ", "\n", "  [", "]");
  return ::testing::AssertionFailure() << "entry (" << worst_i << ", " << worst_j << ") is "
                                       << actual(worst_i, worst_j) << ", expected " << expected(worst_i, worst_j)
                                       << ": differs by " << worst << " (tolerance " << tolerance << ")\nactual:\n"
                                       << actual.format(rows) << "\nexpected:\n"
                                       << expected.format(rows);
}

inline double largest_magnitude(const Eigen::MatrixXd& m) {
  double largest = 0;
  for (Eigen::Index k = 0; k < m.size(); ++k)
    if (!std::isnan(m(k))) largest = std::max(largest, std::fabs(m(k)));
  return largest;
}

}  // namespace detail

/// Every entry of `actual` within `tolerance` of the one of `expected` (absolute).
inline ::testing::AssertionResult matrices_near(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected,
                                                double tolerance) {
  return detail::entries_within(actual, expected, tolerance);
}

/// Every entry of `actual` within tol * max(1, largest |entry| of either matrix) of the one of
/// `expected`: relative to the matrices' scale, absolute below 1.
inline ::testing::AssertionResult matrices_near_relative(const Eigen::MatrixXd& actual,
                                                         const Eigen::MatrixXd& expected, double tol) {
  const double scale = std::max({1.0, detail::largest_magnitude(actual), detail::largest_magnitude(expected)});
  return detail::entries_within(actual, expected, tol * scale);
}

}  // namespace eomgen::testing
