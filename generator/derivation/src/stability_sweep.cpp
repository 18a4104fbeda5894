#include "eomgen/derivation/stability_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "eomgen/base/error.hpp"

namespace eomgen {

std::vector<double> SweepRange::values() const {
  if (!std::isfinite(from) || !std::isfinite(to) || !std::isfinite(step) || !(step > 0) || !(from <= to))
    throw Error(fmt::format("sweep of {}: expected FROM <= TO and a positive STEP, got {}:{}:{}", name, from, to, step));
  const double intervals = (to - from) / step;
  if (!(intervals < static_cast<double>(max_sweep_points)))
    throw Error(fmt::format("sweep of {}: {}:{}:{} has more than {} points; take a larger step", name, from, to, step,
                            max_sweep_points));
  // a millionth of a step of slack, so that 0:1:0.1 ends at 1 despite 0.1's rounding
  const auto count = static_cast<std::size_t>(std::floor(intervals + 1e-6)) + 1;
  std::vector<double> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(std::min(to, from + static_cast<double>(i) * step));
  return out;
}

namespace {

struct Evaluated {
  LinearModel lin;
  StabilityReport report;
  bool equilibrium = true;
};

class Sweeper {
 public:
  Sweeper(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic, const NamedValues& base,
          const SweepRange& range, const LinearizeOptions& options)
      : model_(model), eom_(eom), symbolic_(symbolic), base_(base), range_(range), options_(options) {}

  Evaluated at(double value) const {
    NamedValues point = base_;
    point[range_.name] = value;
    try {
      Evaluated e;
      e.lin = linearize(model_, eom_, symbolic_, point, options_);
      e.report = assess_stability(e.lin.A);
      const double scale = std::max(1.0, e.lin.A.cwiseAbs().maxCoeff());
      e.equilibrium = e.lin.qdd0.size() == 0 || e.lin.qdd0.cwiseAbs().maxCoeff() <= 1e-9 * scale;
      return e;
    } catch (const Error& error) {
      throw Error(fmt::format("sweeping {} at {} = {}: {}", model_.name, range_.name, value, error.what()));
    }
  }

 private:
  const Model& model_;
  const ModelEquations& eom_;
  const SymbolicLinearization& symbolic_;
  const NamedValues& base_;
  const SweepRange& range_;
  const LinearizeOptions& options_;
};

/// how many eigenvalues are zero to the verdict's tolerance (assess_stability's)
std::size_t zero_modes(const Eigen::VectorXcd& eigenvalues) {
  double scale = 1;
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i) scale = std::max(scale, std::abs(eigenvalues(i)));
  std::size_t count = 0;
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i) count += std::abs(eigenvalues(i)) <= 1e-9 * scale;
  return count;
}

/// the largest real part of the eigenvalues without the `skip` of smallest modulus
double largest_real_part(const Eigen::VectorXcd& eigenvalues, std::size_t skip) {
  std::vector<std::complex<double>> by_modulus(eigenvalues.data(), eigenvalues.data() + eigenvalues.size());
  std::sort(by_modulus.begin(), by_modulus.end(),
            [](const auto& a, const auto& b) { return std::abs(a) < std::abs(b); });
  double largest = -HUGE_VAL;
  for (std::size_t i = std::min(skip, by_modulus.size()); i < by_modulus.size(); ++i)
    largest = std::max(largest, by_modulus[i].real());
  return largest;
}

}  // namespace

StabilitySweep sweep_stability(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                               const NamedValues& base, const SweepRange& range, const LinearizeOptions& options,
                               double tolerance) {
  const Sweeper sweeper(model, eom, symbolic, base, range, options);
  StabilitySweep sweep;
  sweep.name = range.name;
  for (const double value : range.values()) {
    const Evaluated e = sweeper.at(value);
    sweep.points.push_back({value, e.lin.state_names, e.report.eigenvalues, e.report.linear, e.equilibrium});
  }
  for (std::size_t i = 0; i + 1 < sweep.points.size(); ++i) {
    const SweepPoint &left = sweep.points[i], &right = sweep.points[i + 1];
    if (!left.equilibrium || !right.equilibrium || left.linear == right.linear) continue;
    const std::size_t skip = std::min(zero_modes(left.eigenvalues), zero_modes(right.eigenvalues));
    // the sign of the largest real part where it changes sign; else the verdict itself (a
    // change between "stable" and "asymptotically stable" within the axis's tolerance)
    const bool by_real_part = (largest_real_part(left.eigenvalues, skip) > 0) != (largest_real_part(right.eigenvalues, skip) > 0);
    const auto side = [&](double value) {
      const Evaluated e = sweeper.at(value);
      return by_real_part ? largest_real_part(e.report.eigenvalues, skip) > 0 : e.report.linear == left.linear;
    };
    const bool left_side = by_real_part ? largest_real_part(left.eigenvalues, skip) > 0 : true;
    double lo = left.value, hi = right.value;
    while (hi - lo > tolerance * std::max(1.0, std::abs(lo))) {
      const double mid = lo + (hi - lo) / 2;
      if (mid <= lo || mid >= hi) break;  // adjacent doubles
      (side(mid) == left_side ? lo : hi) = mid;
    }
    sweep.changes.push_back({lo + (hi - lo) / 2, left.linear, right.linear});
  }
  return sweep;
}

}  // namespace eomgen
