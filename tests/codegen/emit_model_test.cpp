// Header assembly: identifiers that cannot inject code, byte-identical output, metadata.
#include "eomgen/codegen/emit_model.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <vector>

#include "eomgen/base/content_hash.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_throw.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

const char* const pendulum_on_cart = R"(
model cart "cart with a pendulum; tricky \ description */ ??="
parameter int = 2
parameter _hidden = 1
parameter l = 0.5
parameter g = 9.81
coordinate x, theta
input push
frame b = rotate(a, 3, theta)
point cart = w + x*a.1
point bob = cart + l*b.1
particle cart_mass(mass = int, at = cart)
particle bob_mass(mass = _hidden, at = bob)
gravity = g*a.1
force drive(at = cart, force = push*a.2)
output bob_position = position(bob)
)";

std::string generate(const std::string& text) {
  const Model model = parse_model(text, "cart.eom");
  return emit_model(model, derive_equations(model), {"eomgen_models", "cart.eom"}).header;
}

TEST(CppStringContents, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(cpp_string_contents("a\"b\\c"), "a\\\"b\\\\c");
  EXPECT_EQ(cpp_string_contents("x\ny"), "x\\012y");
  EXPECT_EQ(cpp_string_contents("?" "?="), "\\077\\077=");
}

TEST(EmitModel, ModelTextCannotInjectCode) {
  const std::string header = generate(pendulum_on_cart);
  EXPECT_NE(header.find("Scalar int_ = Scalar(2);"), std::string::npos);
  EXPECT_NE(header.find("Scalar v_0_hidden_ = Scalar(1); // '_hidden'"), std::string::npos);
  EXPECT_NE(header.find("p.int_"), std::string::npos);
  // renamed fields are explained where they are declared
  EXPECT_NE(header.find("/// A field has its parameter's name, unless"), std::string::npos);
  // the description survives only inside a string literal, escaped
  EXPECT_NE(header.find(R"(description = "cart with a pendulum; tricky \\ description */ \077\077=";)"), std::string::npos);
  EXPECT_EQ(header.find("description */ ?" "?="), std::string::npos);
}

TEST(EmitModel, SameModelGivesByteIdenticalHeaders) {
  const std::string first = generate(pendulum_on_cart);
  // shift GiNaC's symbol serial numbers, which its term order depends on
  std::vector<GiNaC::realsymbol> dummies;
  for (int i = 0; i < 500; ++i) dummies.emplace_back("dummy" + std::to_string(i));
  const std::string second = generate(pendulum_on_cart);
  EXPECT_EQ(first, second);
}

// each function declares `using std::f;` for exactly the <cmath> functions its statements call
TEST(EmitModel, EveryFunctionDeclaresTheCmathFunctionsItCallsAndNoOther) {
  const std::string h = generate(pendulum_on_cart);
  std::size_t functions = 0, with_calls = 0;
  for (std::size_t at = h.find("noexcept {\n"); at != std::string::npos; at = h.find("noexcept {\n", at + 1)) {
    const std::string body = h.substr(at + 11, h.find("\n  }\n", at) - at - 11);
    // the overloads taking Parameters only forward to those taking the Constants
    if (body.find(">(p)") != std::string::npos && body.find('\n') == std::string::npos) continue;
    // the size test every function makes, which calls nothing
    if (h.substr(h.rfind('\n', at), at - h.rfind('\n', at)).find(" fits(") != std::string::npos) continue;
    ++functions;
    bool any = false;
    for (const ir::CallOp& call : ir::call_ops) {
      const std::string name = call.cpp_name, declaration = "using std::" + name + ";";
      // a call is the name followed by '(' after a character that cannot end an identifier
      bool called = false;
      for (std::size_t k = body.find(name + "("); k != std::string::npos; k = body.find(name + "(", k + 1))
        called = called || (k > 0 && !std::isalnum(static_cast<unsigned char>(body[k - 1])) && body[k - 1] != '_');
      EXPECT_EQ(body.find(declaration) != std::string::npos, called) << name << " in\n" << body.substr(0, 600);
      any = any || called;
    }
    with_calls += any ? 1 : 0;
  }
  // M, F, M and F, Xi, Xi_t, b, phi, T, V, y, forward_dynamics, inverse_dynamics, G, C, the
  // bob's Jacobian and bias, the regressor and pi
  EXPECT_EQ(functions, 18u);
  EXPECT_GT(with_calls, 8u);
}

// a tree without constraints gets forward_dynamics(), which checks the pivots and qdd; a
// constrained model says why it has none
TEST(EmitModel, ForwardDynamicsForTreesAndAReasonOtherwise) {
  const Model tree = load_model(testing::shipped_model_path("double_pendulum"));
  const EmittedModel emitted = emit_model(tree, derive_equations(tree));
  EXPECT_TRUE(emitted.no_forward_dynamics.empty());
  const std::string& h = emitted.header;
  EXPECT_NE(h.find("static constexpr bool has_forward_dynamics = true;"), std::string::npos);
  EXPECT_NE(h.find("static bool forward_dynamics(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& "
                   "q, const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u, const "
                   "Parameters<typename DerivedQ::Scalar>& p, Out0&& qdd) noexcept {"),
            std::string::npos);
  EXPECT_NE(h.find("    Eigen::Matrix<Scalar, 2, 1> pivot;\n"), std::string::npos);
  EXPECT_NE(h.find("    for (int k = 0; k < 2; ++k) regular = regular && pivot(k) > Scalar(0);\n"), std::string::npos);
  EXPECT_NE(h.find("    for (int k = 0; k < qdd.size(); ++k) regular = regular && isfinite(qdd(k));\n"
                   "    return regular;\n"),
            std::string::npos);
  const Model coin = load_model(testing::shipped_model_path("rolling_coin"));
  const EmittedModel constrained = emit_model(coin, derive_equations(coin));
  EXPECT_EQ(constrained.no_forward_dynamics, "the model has constraints");
  EXPECT_NE(constrained.header.find("static constexpr bool has_forward_dynamics = false;"), std::string::npos);
  EXPECT_EQ(constrained.header.find("static bool forward_dynamics("), std::string::npos);
}

TEST(EmitModel, MetadataAndSizes) {
  const std::string h = generate(pendulum_on_cart);
  EXPECT_NE(h.find("static constexpr int nq = 2;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr int nu = 1;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr int nc = 0;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr int ny = 3;"), std::string::npos);
  EXPECT_NE(h.find(R"(coordinate_names{{"x", "theta"}})"), std::string::npos);
  EXPECT_NE(h.find(R"(output_names{{"bob_position_1", "bob_position_2", "bob_position_3"}})"), std::string::npos);
  EXPECT_NE(h.find("namespace cart {"), std::string::npos);
  EXPECT_EQ(h.find(".inverse()"), std::string::npos);
}

// holonomic, nonholonomic, holonomic: Xi rows 0 and 2 are phi's entries 0 and 1
const char* const mixed_constraints = R"(
model mixed
coordinate x, y, z, s
point p = w + x*a.1 + y*a.2 + z*a.3
particle bob(mass = 1, at = p)
potential stiffness = s^2/2
constraint h1: x = s
constraint nh: y_dot = x_dot
constraint h2: z = 1
)";

TEST(EmitModel, HolonomicRowsGiveTheRowOfXiOfEachEntryOfPhi) {
  const std::string h = generate(mixed_constraints);
  EXPECT_NE(h.find("static constexpr int nh = 2;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr std::array<int, nh> holonomic_rows{{0, 2}};  // row of Xi of each entry of phi\n"),
            std::string::npos);
  EXPECT_NE(generate(pendulum_on_cart).find("std::array<int, nh> holonomic_rows{{}};"), std::string::npos);
}

TEST(EmitModel, IndependentSpeedsAsDeclaredOrNone) {
  const std::string declared = generate(std::string(mixed_constraints) + "independent s\n");
  EXPECT_NE(declared.find("static constexpr int ni = 1;  // independent speeds declared in the model (0: none, "
                          "null space from QR of Xi)\n"), std::string::npos);
  EXPECT_NE(declared.find("static constexpr std::array<int, ni> independent_speeds{{3}};  // their coordinate indices\n"),
            std::string::npos);
  const std::string none = generate(mixed_constraints);
  EXPECT_NE(none.find("static constexpr int ni = 0;"), std::string::npos);
  EXPECT_NE(none.find("std::array<int, ni> independent_speeds{{}};"), std::string::npos);
}

TEST(EmitModel, ModelHashChangesWithTheDeclaredIndependentSpeeds) {
  auto hash = [](const std::string& header) {
    const std::size_t at = header.find("model_hash = \"");
    return header.substr(at, 32);
  };
  const std::string none = hash(generate(mixed_constraints));
  const std::string s = hash(generate(std::string(mixed_constraints) + "independent s\n"));
  const std::string x = hash(generate(std::string(mixed_constraints) + "independent x\n"));
  EXPECT_NE(none, s);
  EXPECT_NE(none, x);
  EXPECT_NE(s, x);
}

TEST(EmitModel, IndependentSpeedsSetThroughTheApiAreChecked) {
  Model model = parse_model(mixed_constraints, "mixed.eom");
  const ModelEquations eom = derive_equations(model);
  model.independent_speeds = {4};
  EXPECT_THROW_MESSAGE(
      emit_model(model, eom), EmitError,
      "emitting 'mixed': independent speed 0 is coordinate index 4: expected distinct indices below nq = 4");
  model.independent_speeds = {0, 1};
  EXPECT_THROW_MESSAGE(emit_model(model, eom), EmitError,
                       "emitting 'mixed': expected nq - nc = 1 independent speeds, got 2");
  model.independent_speeds = {3};
  EXPECT_NO_THROW(emit_model(model, eom));
}

TEST(EmitModel, MassMatrixIsComputedAsOneTriangleAndMirrored) {
  const std::string h = generate(pendulum_on_cart);
  EXPECT_NE(h.find("M(1, 0) = M(0, 1);"), std::string::npos);
  EXPECT_EQ(h.find("M(1, 0) = p"), std::string::npos);
}

TEST(EmitModel, StatisticsShowSharingReducesOperations) {
  const Model model = parse_model(pendulum_on_cart, "cart.eom");
  const EmittedModel e = emit_model(model, derive_equations(model));
  bool found = false;
  for (const auto& s : e.statistics)
    if (s.function == "mass_matrix_and_forcing") {
      found = true;
      EXPECT_LT(s.optimized.total(), s.unoptimized.total());
      EXPECT_GT(s.optimized.total(), 0u);
    }
  EXPECT_TRUE(found);
}

TEST(EmitModel, StatisticsListTheConstantsApartFromTheWorkPerCall) {
  const Model model = parse_model(pendulum_on_cart, "cart.eom");
  const EmittedModel e = emit_model(model, derive_equations(model));
  ASSERT_FALSE(e.statistics.empty());
  // int * g and _hidden * g of the potential forces, at least
  EXPECT_EQ(e.statistics.front().function, constants_statistics_name);
  EXPECT_GE(e.statistics.front().optimized.multiplications, 2u);
  EmitOptions baseline;
  baseline.share_subexpressions = false;
  const EmittedModel unshared = emit_model(model, derive_equations(model), baseline);
  EXPECT_EQ(unshared.statistics.front().optimized.total(), 0u);
}

TEST(EmitModel, EveryFunctionTakesTheConstantsAndTheParametersOverloadForwardsToIt) {
  const std::string h = generate(pendulum_on_cart);
  EXPECT_NE(h.find("  template <class Scalar>\n  class Constants {\n"), std::string::npos);
  EXPECT_NE(h.find("explicit Constants(const Parameters<Scalar>& parameters) noexcept : p(parameters) {"),
            std::string::npos);
  // neither t (nothing moves with time here) nor u (the push along a.2 does no work on x or
  // theta) is read: only they are [[maybe_unused]]
  EXPECT_NE(h.find("static void mass_matrix_and_forcing([[maybe_unused]] const typename DerivedQ::Scalar& t, const "
                   "Eigen::MatrixBase<DerivedQ>& q, const Eigen::MatrixBase<DerivedQd>& qd, [[maybe_unused]] const "
                   "Eigen::MatrixBase<DerivedU>& u, const Constants<typename DerivedQ::Scalar>& c, Out0&& M, "
                   "Out1&& F) noexcept {"),
            std::string::npos);
  EXPECT_NE(h.find("    mass_matrix_and_forcing(t, q, qd, u, Constants<typename DerivedQ::Scalar>(p), "
                   "std::forward<Out0>(M), std::forward<Out1>(F));\n"),
            std::string::npos);
  EXPECT_NE(h.find("    return kinetic_energy(t, q, qd, Constants<typename DerivedQ::Scalar>(p));\n"), std::string::npos);
  // the overload doing the work comes first: the first definition a text search finds
  EXPECT_LT(h.find("Constants<typename DerivedQ::Scalar>& c, Out0&& M, Out1&& F"),
            h.find("Parameters<typename DerivedQ::Scalar>& p, Out0&& M, Out1&& F"));
  // per call, parameters are read from the copy the Constants hold (only their constructor reads p)
  const std::string after_constants = h.substr(h.find("  };\n", h.find("class Constants {")));
  EXPECT_NE(after_constants.find("c.p.l"), std::string::npos);
  EXPECT_EQ(after_constants.find(" p.l * "), std::string::npos);
}

// the text of each generated function ("\n  /// doc ... \n  }\n"), in order
std::vector<std::string> functions_of(const std::string& header) {
  const std::string opening = "\n  template <";
  std::vector<std::string> functions;
  for (std::size_t at = header.find(opening); at != std::string::npos; at = header.find(opening, at + 1)) {
    const std::size_t line = header.find('\n', at + 1);
    const std::string next = header.substr(line + 1, header.find('\n', line + 1) - line - 1);
    if (next.rfind("  static ", 0) != 0 || next.find(" fits(") != std::string::npos) continue;
    const std::size_t start = header.rfind("\n  /// ", at), end = header.find("\n  }\n", at);
    functions.push_back(header.substr(start, end + 5 - start));
  }
  return functions;
}

// forward_dynamics() grows linearly with a chain, M, F and their Cholesky solve like its cube (or
// faster): derivation prefers the first only where it is estimated to take fewer operations, and
// the header says what derivation chose
TEST(EmitModel, ForwardDynamicsIsPreferredWhereItCostsLessThanMAndFWithTheCholeskyPath) {
  for (double n : {2.0, 16.0}) {
    const Model model = load_model(testing::shipped_model_path("planar_chain"), {{"n", n}});
    const ModelEquations eom = derive_equations(model);
    const HeaderFunctions functions = derive_header_functions(model, eom);
    ASSERT_TRUE(functions.forward_dynamics.has_value()) << n;
    const double size = n, fd = functions.forward_dynamics->estimated_operations;
    // the runtime's Cholesky path as measured, in operations of generated code (header_functions.cpp)
    EXPECT_EQ(functions.mass_matrix_path_operations,
              functions.mass_matrix_form.estimated_operations + 120 + 14 * size * size) << n;
    EXPECT_EQ(functions.prefers_forward_dynamics, fd < functions.mass_matrix_path_operations) << n;
    EXPECT_TRUE(functions.prefers_forward_dynamics) << n << ": " << fd << " against " << functions.mass_matrix_path_operations;
    const EmittedModel emitted = emit_model(model, functions);
    EXPECT_EQ(emitted.prefers_forward_dynamics, functions.prefers_forward_dynamics);
    const std::string line = fmt::format("static constexpr bool prefers_forward_dynamics = {};",
                                         emitted.prefers_forward_dynamics);
    EXPECT_NE(emitted.header.find(line), std::string::npos) << n;
  }
}

// M and F come from the recursions exactly where those are estimated smaller than the closed
// form kept by the derivation: not for a chain of 2, for one of 8; the emitted M + F then take
// fewer operations than the closed form's would. A chain of 16 is derived with the recursions
// already (DynamicsForm), and emitted as derived.
TEST(EmitModel, MassMatrixAndForcingComeFromTheRecursionsOnlyWhereTheyAreSmaller) {
  const auto operations = [](const EmittedModel& emitted) {
    for (const FunctionStatistics& s : emitted.statistics)
      if (s.function == "mass_matrix_and_forcing") return s.optimized.total();
    return std::uint64_t{0};
  };
  for (double n : {2.0, 8.0}) {
    const Model model = load_model(testing::shipped_model_path("planar_chain"), {{"n", n}});
    const ModelEquations eom = derive_equations(model);
    ASSERT_EQ(eom.dynamics, DynamicsForm::closed_form) << n;
    const EmittedModel emitted = emit_model(model, eom);
    const double closed = eom.resolution == KinematicsResolution::local ? eom.estimated_operations_local
                                                                       : eom.estimated_operations_inertial;
    EXPECT_GT(emitted.estimated_operations_recursions, 0.0) << n;
    EXPECT_EQ(emitted.mass_matrix_from_recursions, emitted.estimated_operations_recursions < closed) << n;
    EXPECT_EQ(emitted.mass_matrix_from_recursions, n > 2) << n;
    if (n > 2) {
      EXPECT_LT(operations(emitted), 0.6 * closed) << n;
    }
  }
  {
    const Model model = load_model(testing::shipped_model_path("planar_chain"), {{"n", 16}});
    const ModelEquations eom = derive_equations(model);
    ASSERT_EQ(eom.dynamics, DynamicsForm::recursions);
    const EmittedModel emitted = emit_model(model, eom);
    EXPECT_TRUE(emitted.mass_matrix_from_recursions);
    EXPECT_EQ(emitted.estimated_operations_recursions, eom.estimated_operations_recursions);
    const double closed = derive_equations(model.system, KinematicsResolution::inertial).estimated_operations_inertial;
    EXPECT_LT(operations(emitted), 0.6 * closed);
  }
  // a tree with constraints has them (M and F are the tree's), kept only where smaller: the
  // rolling coin's closed form is
  const Model coin = load_model(testing::shipped_model_path("rolling_coin"));
  const EmittedModel rolling = emit_model(coin, derive_equations(coin));
  EXPECT_FALSE(rolling.mass_matrix_from_recursions);
  EXPECT_GT(rolling.estimated_operations_recursions, 0.0);
  // no recursions without a tree (the second rod turns by an absolute angle): the estimate says so
  const Model absolute = parse_model("coordinate q1, q2\n"
                                     "frame b = rotate(a, 3, q1)\n"
                                     "frame c = rotate(a, 3, q2)\n"
                                     "point p1 = w + b.1\n"
                                     "point p2 = p1 + c.1\n"
                                     "particle bob1(mass = 1, at = p1)\n"
                                     "particle bob2(mass = 1, at = p2)\n",
                                     "absolute.eom");
  const EmittedModel emitted = emit_model(absolute, derive_equations(absolute));
  EXPECT_FALSE(emitted.mass_matrix_from_recursions);
  EXPECT_TRUE(std::isnan(emitted.estimated_operations_recursions));
}

TEST(EmitModel, AGivenLinearizationAddsItsFunctionsAndChangesNoOther) {
  // the double pendulum has forward_dynamics, the rolling coin (constrained) has not
  for (const auto& [name, count] : {std::pair<const char*, std::size_t>{"double_pendulum", 48u}, {"rolling_coin", 46u}}) {
    const Model model = load_model(testing::shipped_model_path(name));
    const ModelEquations eom = derive_equations(model);
    const std::string plain = emit_model(model, eom).header;
    const std::string linearized = emit_model(model, eom, linearize_symbolic(model, eom)).header;
    const std::vector<std::string> functions = functions_of(plain);
    // each function taking Constants, then Parameters
    ASSERT_EQ(functions.size(), count) << name;
    for (const std::string& f : functions) EXPECT_NE(linearized.find(f), std::string::npos) << name << f;
    EXPECT_EQ(plain.find("linearization"), std::string::npos) << name;
    EXPECT_NE(linearized.find("static void linearization_terms("), std::string::npos) << name;
    // the factorizations are the runtime's: a linearized header includes what a plain one does,
    // Eigen/Core, and Eigen/Cholesky only with constraints (the inverse dynamics' multipliers)
    EXPECT_EQ(linearized.find("#include <Eigen/LU>"), std::string::npos) << name;
    EXPECT_EQ(linearized.find("#include <Eigen/Cholesky>") != std::string::npos, model.system.constraints().size() > 0)
        << name;
    EXPECT_NE(linearized.find("#include <Eigen/Core>\n"), std::string::npos) << name;
  }
}

// linearization_terms() as eomgen emitted it when it computed the linearization itself
// (f09668f), then as the local-frame derivation gave it with its parameter-only values read from
// the Constants, then with the rolling coin in the inertial form (its estimates 174 local, 170
// inertial once a value and its negation count as one), then with the signatures that take any
// Eigen expression and a sum's x - x cancelled in lowering, then with sin and cos of one angle
// both computed before the first output (one sincos); when the derivation, the lowering or the
// printer changes on purpose, take the new hashes
TEST(EmitModel, LinearizationTermsAreThoseEmittedWhenEmissionLinearizedItself) {
  const std::pair<const char*, std::uint64_t> expected[] = {{"double_pendulum", 0x34d9a8d8c6cebed7ull},
                                                            {"rolling_coin", 0x9ba21737762c85c6ull}};
  for (const auto& [name, hash] : expected) {
    const Model model = load_model(testing::shipped_model_path(name));
    const ModelEquations eom = derive_equations(model);
    const EmittedModel emitted = emit_model(model, eom, linearize_symbolic(model, eom), {"eomgen_models", name});
    std::string terms;
    for (const std::string& f : functions_of(emitted.header))
      if (f.find("static void linearization_terms(") != std::string::npos && terms.empty()) terms = f;
    EXPECT_EQ(content_hash(terms), hash) << name << terms;
    // linearization_terms, and last without constraints the forward dynamics' derivatives
    const auto& last = emitted.statistics.back().function;
    EXPECT_EQ(last, eom.constraint_count == 0 ? "forward_dynamics_derivatives" : "linearization_terms") << name;
    EXPECT_EQ(emitted.statistics[emitted.statistics.size() - (eom.constraint_count == 0 ? 2 : 1)].function,
              "linearization_terms")
        << name;
  }
}

}  // namespace
}  // namespace eomgen
