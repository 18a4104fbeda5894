#pragma once
/// \file
/// The registry of the integrators simulate() offers: one row per method with its name, its
/// Butcher tableau (an embedded pair for an adaptive method) and a one-line description.
/// simulate() steps with the row's tableau; `eomgen simulate` takes its `--method` choices,
/// help and messages from these rows, and so does the program it compiles. Adding a method is
/// its tableau (tableau.hpp), its enumerator and its row below.
///
/// Needs no Eigen, so that the eomgen command can include it.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "eomrt/tableau.hpp"

namespace eomrt {

/// An integration method of simulate(); what it is is its row in integrator_registry.
enum class Integrator { euler, rk4, dormand_prince };

/// What a row of the registry says about its method, whatever the size of its tableau.
struct IntegratorInfo {
  Integrator method;
  /// the name `eomgen simulate --method` accepts and its summary prints
  const char* name;
  /// true: an embedded pair, stepped with error control (rk_adaptive.hpp); false: fixed steps
  /// (rk_fixed.hpp)
  bool adaptive;
  /// global order of the propagated solution
  int order;
  /// one line for the command's help
  const char* description;
};

/// One row of the registry: a method and its tableau.
/// \tparam Tableau  ButcherTableau<S> for a fixed-step method, EmbeddedTableau<S> for an
///                  adaptive one
template <class Tableau>
struct IntegratorEntry {
  static constexpr bool adaptive = is_embedded_tableau_v<Tableau>;
  Integrator method;
  const char* name;
  const Tableau& tableau;
  const char* description;

  constexpr IntegratorInfo info() const {
    return {method, name, adaptive, tableau.order, description};
  }
};

/// \return a row of the registry (C++17 cannot deduce an aggregate's template argument)
template <class Tableau>
constexpr IntegratorEntry<Tableau> integrator(Integrator method, const char* name,
                                              const Tableau& tableau, const char* description) {
  return {method, name, tableau, description};
}

/// The registry, one row per enumerator of Integrator and in their order (checked below).
inline constexpr std::tuple integrator_registry{
    integrator(Integrator::euler, "euler", euler, "explicit Euler, order 1, fixed step"),
    integrator(Integrator::rk4, "rk4", rk4, "classical Runge-Kutta, order 4, fixed step"),
    integrator(Integrator::dormand_prince, "dp5", dormand_prince54,
               "Dormand-Prince 5(4), adaptive step with error control"),
};

/// The rows of the registry without their tableaus, in the same order, for listing them.
inline constexpr auto integrators = std::apply(
    [](const auto&... entry) {
      return std::array<IntegratorInfo, sizeof...(entry)>{entry.info()...};
    },
    integrator_registry);

/// The method simulate() takes by default; `eomgen simulate` takes it unless given a step.
inline constexpr Integrator default_integrator = Integrator::dormand_prince;
/// The method `eomgen simulate` takes when given a step (--dt) and no method.
inline constexpr Integrator default_fixed_step_integrator = Integrator::rk4;

/// \return the registry's row for \p method, or nullptr if it has none (a value cast from an
///         integer that is no enumerator)
constexpr const IntegratorInfo* find_integrator(Integrator method) {
  for (const IntegratorInfo& info : integrators)
    if (info.method == method) return &info;
  return nullptr;
}

/// \return the row whose name is \p name, or nullptr if there is none
constexpr const IntegratorInfo* find_integrator(std::string_view name) {
  for (const IntegratorInfo& info : integrators)
    if (name == info.name) return &info;
  return nullptr;
}

/// \return the method's name (as the eomgen command spells it), or "unknown"
inline const char* to_string(Integrator method) {
  const IntegratorInfo* info = find_integrator(method);
  return info != nullptr ? info->name : "unknown";
}

/// \return true if \p method is registered and steps adaptively
constexpr bool is_adaptive(Integrator method) {
  // compares rows, not pointers: GCC's UndefinedBehaviorSanitizer makes a pointer test
  // non-constant, and static_asserts below use this
  for (const IntegratorInfo& info : integrators)
    if (info.method == method) return info.adaptive;
  return false;
}

namespace detail {

template <std::size_t I, class F>
decltype(auto) visit_integrator_from(Integrator method, F& f) {
  if constexpr (I + 1 < std::tuple_size_v<std::decay_t<decltype(integrator_registry)>>) {
    if (std::get<I>(integrator_registry).method != method)
      return visit_integrator_from<I + 1>(method, f);
  } else if (std::get<I>(integrator_registry).method != method) {
    throw std::invalid_argument("visit_integrator: method expected a registered Integrator, got " +
                                std::to_string(static_cast<int>(method)));
  }
  return f(std::get<I>(integrator_registry));
}

constexpr bool registered(Integrator method) {
  for (const IntegratorInfo& info : integrators)
    if (info.method == method) return true;
  return false;
}

// every rule the steppers rely on, for every row: a typo in the registry breaks the build
constexpr bool registry_is_well_formed() {
  for (std::size_t i = 0; i < integrators.size(); ++i) {
    if (static_cast<std::size_t>(integrators[i].method) != i) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (std::string_view(integrators[i].name) == integrators[j].name) return false;
  }
  return std::apply(
      [](const auto&... entry) {
        return ((is_consistent(entry.tableau) && (!entry.adaptive || is_fsal(entry.tableau))) &&
                ...);
      },
      integrator_registry);
}

}  // namespace detail

static_assert(detail::registry_is_well_formed(),
              "integrator_registry: rows must follow the enumerators of Integrator, have distinct "
              "names and consistent tableaus, and the adaptive ones FSAL pairs");
static_assert(detail::registered(default_integrator) &&
                  detail::registered(default_fixed_step_integrator) &&
                  !is_adaptive(default_fixed_step_integrator),
              "integrators.hpp: the defaults must be registered, the fixed-step one not adaptive");

/// Calls f(entry) with the registry's row for \p method, its tableau with its own type (so f
/// is compiled for every row: `if constexpr (std::decay_t<decltype(entry)>::adaptive)` tells
/// the kinds apart) and returns what f returns, which must be one type for every row.
/// @throws std::invalid_argument if \p method has no row (find_integrator gives nullptr)
template <class F>
decltype(auto) visit_integrator(Integrator method, F&& f) {
  return detail::visit_integrator_from<0>(method, f);
}

}  // namespace eomrt
