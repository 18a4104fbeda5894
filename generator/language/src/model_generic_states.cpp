// States at which the elaborator tests what must hold for every state, not only at one: that a
// vector is not zero, a constraint not identically zero or dependent, a wheel's axle not along
// the normal of its plane.
#include <fmt/format.h>

#include <cmath>
#include <random>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {

std::optional<double> value_at(const GiNaC::ex& e, const GiNaC::exmap& state) {
  const std::optional<double> v = value_in_doubles(e, state);
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return v;
}

// Parameters at their defaults; coordinates, rates, inputs and time at irrational-looking values
// no special configuration is likely to hit. Three, so that what vanishes at one by chance does
// not pass for identically zero; the first is the state checks() takes Xi at.
std::vector<GiNaC::exmap> Elaborator::generic_states() const {
  const MechanicalSystem& sys = model_.system;
  const Variables& vars = sys.variables();
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> value(0.31, 1.17);
  std::vector<GiNaC::exmap> states;
  for (int k = 0; k < 3; ++k) {
    GiNaC::exmap state = sys.parameter_defaults();
    state[vars.time()] = k == 0 ? 0.73 : value(rng);
    for (const auto& c : vars.coordinates()) {
      state[c.q] = value(rng);
      state[c.qd] = value(rng);
    }
    for (const auto& u : vars.inputs()) state[u.symbol] = value(rng);
    states.push_back(std::move(state));
  }
  return states;
}

void Elaborator::reject_zero_vector(const eomgen::Vector& v, const GiNaC::ex& length, const SourceLocation& at,
                                    const std::string& what) const {
  const std::string message = fmt::format("{}: the vector is zero at the parameters' default values and a generic "
                                          "state, so it has no direction: expected a non-zero vector", what);
  if (v.is_zero()) throw SourceError(at, message);
  for (const GiNaC::exmap& state : generic_states()) {
    // against the size of its components, so that a length that cancels to rounding counts as zero
    double scale = 0;
    bool known = true;
    for (const auto& [frame, c] : v.terms())
      for (unsigned i = 0; i < 3; ++i) {
        const std::optional<double> component = value_at(c(i, 0), state);
        known = known && component;
        scale += std::fabs(component.value_or(0.0));
      }
    const std::optional<double> value = value_at(length, state);
    if (known && value && *value <= 1e-12 * scale) throw SourceError(at, message);
  }
}

}  // namespace eomgen::syntax
