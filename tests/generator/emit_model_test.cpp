// Header assembly: identifiers that cannot inject code, byte-identical output, metadata.
#include "eomgen/emit_model.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eomgen {
namespace {

const char* const pendulum_on_cart = R"(
model cart "cart with a pendulum; tricky \ description */ ??="
parameter int = 2 [kg]
parameter _hidden = 1
parameter l = 0.5 [m]
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

TEST(CppIdentifier, KeywordsReservedNamesAndOwnLocalsGetATrailingUnderscore) {
  EXPECT_EQ(cpp_identifier("mass"), "mass");
  EXPECT_EQ(cpp_identifier("int"), "int_");
  EXPECT_EQ(cpp_identifier("class"), "class_");
  EXPECT_EQ(cpp_identifier("q"), "q_");
  EXPECT_EQ(cpp_identifier("Scalar"), "Scalar_");
  EXPECT_EQ(cpp_identifier("_hidden"), "v_hidden");
  EXPECT_EQ(cpp_identifier("a__b"), "a_b");
  EXPECT_EQ(cpp_identifier("x_"), "x__");  // never ends in a single '_' of ours: no clash with mangled names
}

TEST(CppStringContents, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(cpp_string_contents("a\"b\\c"), "a\\\"b\\\\c");
  EXPECT_EQ(cpp_string_contents("x\ny"), "x\\012y");
  EXPECT_EQ(cpp_string_contents("?" "?="), "\\077\\077=");
}

TEST(EmitModel, ModelTextCannotInjectCode) {
  const std::string header = generate(pendulum_on_cart);
  EXPECT_NE(header.find("Scalar int_ = Scalar(2);"), std::string::npos);
  EXPECT_NE(header.find("Scalar v_hidden = Scalar(1);"), std::string::npos);
  EXPECT_NE(header.find("p.int_"), std::string::npos);
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

TEST(EmitModel, MetadataAndSizes) {
  const std::string h = generate(pendulum_on_cart);
  EXPECT_NE(h.find("static constexpr int nq = 2;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr int nu = 1;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr int nc = 0;"), std::string::npos);
  EXPECT_NE(h.find("static constexpr int ny = 3;"), std::string::npos);
  EXPECT_NE(h.find(R"(coordinate_names{{"x", "theta"}})"), std::string::npos);
  EXPECT_NE(h.find(R"(output_names{{"bob_position_1", "bob_position_2", "bob_position_3"}})"), std::string::npos);
  EXPECT_NE(h.find("namespace cart {"), std::string::npos);
  EXPECT_EQ(h.find("inverse"), std::string::npos);
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

}  // namespace
}  // namespace eomgen
