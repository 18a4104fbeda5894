// Tests for integrators.hpp: every registered method is found by its name and run by
// simulate(), every registered tableau has the order it claims (Butcher's order conditions,
// checked on all rooted trees), and the adaptive stepper runs an embedded pair that is not
// registered, so that registering another one is a row, not a new stepper.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "eomrt/eomrt.hpp"
#include "eomrt/simulate.hpp"
#include "runtime/handwritten_models.hpp"

namespace eomrt {
namespace {

using testing::Oscillator;

// ---- the registry as a list ----

TEST(Registry, NamesAreDistinctAndFindTheirRow) {
  std::set<std::string> names;
  for (const IntegratorInfo& info : integrators) {
    SCOPED_TRACE(info.name);
    EXPECT_TRUE(names.insert(info.name).second);
    ASSERT_NE(find_integrator(std::string(info.name)), nullptr);
    EXPECT_EQ(find_integrator(std::string(info.name))->method, info.method);
    EXPECT_EQ(find_integrator(info.method), &info);
    EXPECT_STREQ(to_string(info.method), info.name);
    EXPECT_EQ(is_adaptive(info.method), info.adaptive);
    EXPECT_GT(std::string(info.description).size(), 10u);
  }
  EXPECT_EQ(find_integrator(std::string("dp45")), nullptr);
  EXPECT_EQ(find_integrator(std::string("")), nullptr);
}

// the command line accepts exactly these names; a new method adds one, never renames one
TEST(Registry, HoldsTheMethodsTheCommandLineHasAlwaysAccepted) {
  std::vector<std::string> names;
  for (const IntegratorInfo& info : integrators) names.push_back(info.name);
  EXPECT_EQ(names, (std::vector<std::string>{"euler", "rk4", "dp5"}));
  EXPECT_STREQ(to_string(default_integrator), "dp5");
  EXPECT_STREQ(to_string(default_fixed_step_integrator), "rk4");
}

TEST(Registry, RowsCarryTheirTableauAndItsKind) {
  EXPECT_EQ(&std::get<0>(integrator_registry).tableau, &euler);
  EXPECT_EQ(&std::get<1>(integrator_registry).tableau, &rk4);
  EXPECT_EQ(&std::get<2>(integrator_registry).tableau, &dormand_prince54);
  std::apply(
      [](const auto&... entry) {
        const auto check = [](const auto& e) {
          SCOPED_TRACE(e.name);
          EXPECT_EQ(e.adaptive, is_embedded_tableau_v<std::decay_t<decltype(e.tableau)>>);
          EXPECT_EQ(e.info().order, e.tableau.order);
        };
        (check(entry), ...);
      },
      integrator_registry);
}

TEST(Registry, VisitGivesTheRowOfTheMethodAndRejectsAnUnregisteredOne) {
  for (const IntegratorInfo& info : integrators) {
    const std::string visited =
        visit_integrator(info.method, [](const auto& entry) { return std::string(entry.name); });
    EXPECT_EQ(visited, info.name);
  }
  const auto unregistered = static_cast<Integrator>(99);
  EXPECT_STREQ(to_string(unregistered), "unknown");
  EXPECT_THROW(visit_integrator(unregistered, [](const auto&) { return 0; }), std::invalid_argument);
}

// ---- simulate() runs every registered method ----

TEST(Registry, SimulateRunsEveryRegisteredMethodToTheExactSolution) {
  // m = 2, k = 8: x = cos(2 t) from x = 1 at rest
  for (const IntegratorInfo& info : integrators) {
    SCOPED_TRACE(info.name);
    SimulationOptions<double> o;
    o.integrator = info.method;
    o.t_end = 1.0;
    o.step = 1e-4;
    const SimulationResult<Oscillator, double> r =
        simulate<Oscillator>(Oscillator::Parameters<double>{}, ModelTypes<Oscillator, double>::State(1.0, 0.0), o);
    ASSERT_EQ(r.status, SimulationStatus::ok) << to_string(r.status);
    EXPECT_EQ(r.t, 1.0);
    // Euler's error is O(h); the others are far below it
    EXPECT_NEAR(r.x(0), std::cos(2.0), info.order == 1 ? 1e-3 : 1e-8);
    if (!info.adaptive) {
      EXPECT_EQ(r.steps, 10000);
    }
  }
}

TEST(Registry, SimulateRejectsAnUnregisteredMethodBeforeTheLoop) {
  SimulationOptions<double> o;
  o.integrator = static_cast<Integrator>(99);
  try {
    simulate<Oscillator>(Oscillator::Parameters<double>{}, ModelTypes<Oscillator, double>::State(1.0, 0.0), o);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "simulate: integrator expected a registered method, got 99");
  }
}

// ---- order conditions on rooted trees ----

// A rooted tree as the list of its root's subtrees, kept sorted by their text so that a tree
// has one representation: "[]" is a single node, "[[][]]" a root with two leaves.
struct Tree {
  std::vector<Tree> children;

  std::string text() const {
    std::string s = "[";
    for (const Tree& c : children) s += c.text();
    return s + "]";
  }
  int nodes() const {
    int n = 1;
    for (const Tree& c : children) n += c.nodes();
    return n;
  }
  // gamma(t) = |t| prod gamma(children): the exact solution's coefficient is 1 / gamma
  long double density() const {
    long double g = nodes();
    for (const Tree& c : children) g *= c.density();
    return g;
  }
  void sort() {
    for (Tree& c : children) c.sort();
    std::sort(children.begin(), children.end(), [](const Tree& a, const Tree& b) { return a.text() < b.text(); });
  }
};

// the trees with one node more: a leaf added at each node of t
std::vector<Tree> grown(const Tree& t) {
  std::vector<Tree> out;
  Tree with_leaf = t;
  with_leaf.children.emplace_back();
  out.push_back(with_leaf);
  for (std::size_t i = 0; i < t.children.size(); ++i)
    for (const Tree& child : grown(t.children[i])) {
      Tree copy = t;
      copy.children[i] = child;
      out.push_back(copy);
    }
  return out;
}

// every rooted tree with 1 to p nodes (1, 1, 2, 4, 9, 20 of each order)
std::vector<Tree> trees_up_to(int p) {
  std::vector<Tree> all{Tree{}}, last{Tree{}};
  for (int order = 2; order <= p; ++order) {
    std::set<std::string> seen;
    std::vector<Tree> next;
    for (const Tree& t : last)
      for (Tree g : grown(t)) {
        g.sort();
        if (seen.insert(g.text()).second) next.push_back(g);
      }
    all.insert(all.end(), next.begin(), next.end());
    last = next;
  }
  return all;
}

// Phi_i(t) = prod over the children c of sum_j a_ij Phi_j(c), and 1 for a single node
template <std::size_t S>
std::array<long double, S> stage_weights(const ButcherTableau<S>& tableau, const Tree& t) {
  std::array<long double, S> phi;
  phi.fill(1);
  for (const Tree& c : t.children) {
    const std::array<long double, S> below = stage_weights(tableau, c);
    for (std::size_t i = 0; i < S; ++i) {
      long double sum = 0;
      for (std::size_t j = 0; j < S; ++j) sum += tableau.a[i][j] * below[j];
      phi[i] *= sum;
    }
  }
  return phi;
}

// the largest |sum_i w_i Phi_i(t) - 1 / gamma(t)| over the trees of the given order
template <std::size_t S>
long double order_defect(const ButcherTableau<S>& tableau, const Coefficient (&weights)[S], int order) {
  long double worst = 0;
  for (const Tree& t : trees_up_to(order)) {
    if (t.nodes() != order) continue;
    const std::array<long double, S> phi = stage_weights(tableau, t);
    long double sum = 0;
    for (std::size_t i = 0; i < S; ++i) sum += weights[i] * phi[i];
    worst = std::max(worst, std::abs(sum - 1 / t.density()));
  }
  return worst;
}

// weights of order p satisfy the conditions of every tree up to p nodes, and (being of order
// p exactly) miss one of p + 1
template <std::size_t S>
void expect_order(const ButcherTableau<S>& tableau, const Coefficient (&weights)[S], int p) {
  for (int order = 1; order <= p; ++order)
    EXPECT_LT(order_defect(tableau, weights, order), 1e-15L) << "order " << order;
  EXPECT_GT(order_defect(tableau, weights, p + 1), 1e-6L) << "order " << p + 1;
}

TEST(OrderConditions, RootedTreesAreCountedRight) {
  std::array<int, 7> count{};
  for (const Tree& t : trees_up_to(6)) ++count[static_cast<std::size_t>(t.nodes())];
  EXPECT_EQ(count, (std::array<int, 7>{0, 1, 1, 2, 4, 9, 20}));
}

TEST(OrderConditions, EveryRegisteredTableauHasTheOrderItClaims) {
  std::apply(
      [](const auto&... entry) {
        const auto check = [](const auto& e) {
          SCOPED_TRACE(e.name);
          expect_order(e.tableau, e.tableau.b, e.tableau.order);
          if constexpr (std::decay_t<decltype(e)>::adaptive)
            expect_order(e.tableau, e.tableau.b_hat, e.tableau.embedded_order);
        };
        (check(entry), ...);
      },
      integrator_registry);
}

// ---- another embedded pair through the same stepper ----

// Bogacki-Shampine 3(2) (Appl. Math. Lett. 2(4), 1989), MATLAB's ode23: FSAL, and no dense
// weights, so its dense output is the cubic Hermite interpolant (of order 3, like the pair)
// clang-format off
constexpr EmbeddedTableau<4> bogacki_shampine32{
    {/*a=*/{{0, 0, 0, 0},
            {1.0L / 2, 0, 0, 0},
            {0, 3.0L / 4, 0, 0},
            {2.0L / 9, 1.0L / 3, 4.0L / 9, 0}},
     /*b=*/{2.0L / 9, 1.0L / 3, 4.0L / 9, 0},
     /*c=*/{0, 1.0L / 2, 3.0L / 4, 1},
     /*order=*/3},
    /*b_hat=*/{7.0L / 24, 1.0L / 4, 1.0L / 3, 1.0L / 8},
    /*embedded_order=*/2,
    /*dense=*/{}};
// clang-format on
static_assert(is_consistent(bogacki_shampine32) && is_fsal(bogacki_shampine32));

TEST(AnotherEmbeddedPair, BogackiShampineHasItsOrders) {
  expect_order(bogacki_shampine32, bogacki_shampine32.b, 3);
  expect_order(bogacki_shampine32, bogacki_shampine32.b_hat, 2);
}

TEST(AnotherEmbeddedPair, IntegratesToItsToleranceWithThirdOrderSteps) {
  // x'' = -x from (1, 0) over 10 s, observed on a grid from the dense output
  const auto oscillator = [](double, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) { dxdt << x(1), -x(0); };
  std::vector<double> grid;
  for (int i = 1; i <= 100; ++i) grid.push_back(0.1 * i);
  std::vector<double> errors, steps;
  for (const double rtol : {1e-5, 1e-7, 1e-9}) {
    AdaptiveOptions<double> o;
    o.rtol = rtol;
    o.atol = rtol;
    double worst = 0;
    const auto r = integrate_adaptive(
        bogacki_shampine32, oscillator, 0.0, Eigen::Vector2d(1, 0), grid, o,
        [&](double t, const Eigen::Vector2d& x) { worst = std::max(worst, std::abs(x(0) - std::cos(t))); });
    ASSERT_EQ(r.status, AdaptiveStatus::ok);
    // FSAL: 3 evaluations per attempt, plus the first stage and the starting-step probe
    EXPECT_LE(r.evaluations, 3 * (r.accepted + r.rejected) + 2);
    std::printf("[ bs32     ] rtol %.0e: %5lld steps, %lld rejected, worst grid error %.2e\n", rtol, r.accepted,
                r.rejected, worst);
    EXPECT_LT(worst, 200 * rtol);
    errors.push_back(std::abs(r.x(0) - std::cos(10.0)));
    steps.push_back(static_cast<double>(r.accepted));
  }
  // steps ~ rtol^(-1/3): a hundredfold tolerance costs about 100^(1/3) = 4.6 times the steps
  for (std::size_t i = 1; i < steps.size(); ++i) {
    EXPECT_GT(steps[i] / steps[i - 1], 3.0);
    EXPECT_LT(steps[i] / steps[i - 1], 7.0);
  }
}

TEST(AnotherEmbeddedPair, APairThatIsNotFsalIsRejectedBeforeStepping) {
  EmbeddedTableau<4> not_fsal = bogacki_shampine32;
  not_fsal.a[3][0] = 1.0L / 9;
  not_fsal.a[3][1] = 4.0L / 9;  // the row still sums to c = 1, but is no longer b
  const auto f = [](double, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) { dxdt = -x; };
  AdaptiveWorkspace<Eigen::Vector2d, 4> ws(2);
  EXPECT_THROW(adaptive_start(not_fsal, f, 0.0, Eigen::Vector2d(1, 0), 1.0, AdaptiveOptions<double>(), ws),
               std::invalid_argument);
}

}  // namespace
}  // namespace eomrt
