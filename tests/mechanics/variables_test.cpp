// Tests of eomgen::Variables: declaration of symbols, name checks, lookup and the total time
// derivative by the chain rule.
#include "eomgen/mechanics/variables.hpp"

#include <gtest/gtest.h>

#include <string>

#include "eomgen/base/error.hpp"
#include "support/expect_throw.hpp"
#include "support/symbolic_checks.hpp"

namespace {

using eomgen::DerivationError;
using eomgen::ModelError;
using eomgen::SymbolKind;
using eomgen::Variables;
using eomgen::testing::equal_after_expansion;
using GiNaC::cos;
using GiNaC::ex;
using GiNaC::pow;
using GiNaC::sin;

/// What Variables says of a name that is not an identifier.
std::string not_an_identifier(const std::string& name) {
  return "declaring '" + name + "': a name must be an identifier (a letter or '_' followed by letters, digits or '_')";
}

// ---------------------------------------------------------------------------------------------
// Declarations

TEST(VariablesDeclare, TimeIsNamedT) {
  Variables v;
  EXPECT_EQ(v.time().get_name(), "t");
  EXPECT_EQ(v.coordinate_count(), 0u);
}

TEST(VariablesDeclare, CoordinateCreatesNameRateAndAcceleration) {
  Variables v;
  const auto x = v.add_coordinate("x");
  EXPECT_EQ(x.name, "x");
  EXPECT_EQ(x.q.get_name(), "x");
  EXPECT_EQ(x.qd.get_name(), "x_dot");
  EXPECT_EQ(x.qdd.get_name(), "x_ddot");
  EXPECT_FALSE(x.q.is_equal(x.qd));
  EXPECT_FALSE(x.qd.is_equal(x.qdd));
  ASSERT_EQ(v.coordinate_count(), 1u);
  EXPECT_TRUE(v.coordinates()[0].q.is_equal(x.q));
  EXPECT_TRUE(v.coordinates()[0].qd.is_equal(x.qd));
  EXPECT_TRUE(v.coordinates()[0].qdd.is_equal(x.qdd));
}

TEST(VariablesDeclare, CoordinatesKeepDeclarationOrderInLists) {
  Variables v;
  const auto a = v.add_coordinate("a"), b = v.add_coordinate("b"), c = v.add_coordinate("c");
  const GiNaC::lst q = v.coordinate_list(), qd = v.rate_list();
  ASSERT_EQ(q.nops(), 3u);
  ASSERT_EQ(qd.nops(), 3u);
  EXPECT_TRUE(q.op(0).is_equal(a.q));
  EXPECT_TRUE(q.op(1).is_equal(b.q));
  EXPECT_TRUE(q.op(2).is_equal(c.q));
  EXPECT_TRUE(qd.op(0).is_equal(a.qd));
  EXPECT_TRUE(qd.op(1).is_equal(b.qd));
  EXPECT_TRUE(qd.op(2).is_equal(c.qd));
}

TEST(VariablesDeclare, ParameterKeepsDefaultAndUnit) {
  Variables v;
  const auto m = v.add_parameter("m", 2.5, "kg");
  EXPECT_EQ(m.name, "m");
  EXPECT_EQ(m.symbol.get_name(), "m");
  EXPECT_DOUBLE_EQ(m.default_value, 2.5);
  EXPECT_EQ(m.unit, "kg");
  ASSERT_EQ(v.parameters().size(), 1u);
  EXPECT_TRUE(v.parameters()[0].symbol.is_equal(m.symbol));
}

TEST(VariablesDeclare, InputIsRecorded) {
  Variables v;
  const auto u = v.add_input("torque");
  EXPECT_EQ(u.name, "torque");
  ASSERT_EQ(v.inputs().size(), 1u);
  EXPECT_TRUE(v.inputs()[0].symbol.is_equal(u.symbol));
}

TEST(VariablesDeclare, DuplicateNameThrowsModelErrorNamingIt) {
  Variables v;
  v.add_coordinate("x");
  v.add_parameter("m", 1.0);
  v.add_input("u");
  EXPECT_THROW_MESSAGE(v.add_coordinate("x"), ModelError, "declaring 'x': the name is already used");
  EXPECT_THROW_MESSAGE(v.add_parameter("x", 1.0), ModelError, "declaring 'x': the name is already used");
  EXPECT_THROW_MESSAGE(v.add_input("m"), ModelError, "declaring 'm': the name is already used");
  EXPECT_THROW_MESSAGE(v.add_coordinate("u"), ModelError, "declaring 'u': the name is already used");
  EXPECT_EQ(v.coordinate_count(), 1u);
  EXPECT_EQ(v.parameters().size(), 1u);
  EXPECT_EQ(v.inputs().size(), 1u);
}

TEST(VariablesDeclare, TimeNameIsReserved) {
  Variables v;
  EXPECT_THROW_MESSAGE(v.add_coordinate("t"), ModelError, "declaring 't': the name is already used");
  EXPECT_THROW_MESSAGE(v.add_parameter("t", 0.0), ModelError, "declaring 't': the name is already used");
}

TEST(VariablesDeclare, RateAndAccelerationNamesOfACoordinateAreReserved) {
  Variables v;
  v.add_coordinate("x");
  EXPECT_THROW_MESSAGE(v.add_coordinate("x_dot"), ModelError, "declaring 'x_dot': the name is already used");
  EXPECT_THROW_MESSAGE(v.add_parameter("x_dot", 1.0), ModelError, "declaring 'x_dot': the name is already used");
  EXPECT_THROW_MESSAGE(v.add_input("x_ddot"), ModelError, "declaring 'x_ddot': the name is already used");
  EXPECT_EQ(v.coordinate_count(), 1u);
}

TEST(VariablesDeclare, CoordinateWhoseRateNameIsTakenThrows) {
  Variables v;
  v.add_parameter("y_dot", 1.0);
  EXPECT_THROW_MESSAGE(v.add_coordinate("y"), ModelError, "declaring 'y_dot': the name is already used");
  EXPECT_EQ(v.coordinate_count(), 0u);
  EXPECT_FALSE(v.find("y").has_value());
}

// A failed add_coordinate("y") (because "y_dot" is taken) must not leave "y" claimed:
// declarations are all-or-nothing.
TEST(VariablesDeclare, FailedCoordinateDeclarationLeavesItsNameFree) {
  Variables v;
  v.add_parameter("y_dot", 1.0);
  EXPECT_THROW_MESSAGE(v.add_coordinate("y"), ModelError, "declaring 'y_dot': the name is already used");
  EXPECT_NO_THROW(v.add_parameter("y", 2.0));
}

TEST(VariablesDeclare, NonIdentifiersThrowModelErrorNamingThem) {
  Variables v;
  for (const std::string name : {"1x", "a-b", "a b", "x.y", "q'", "é"}) {
    EXPECT_THROW_MESSAGE(v.add_coordinate(name), ModelError, not_an_identifier(name)) << name;
    EXPECT_THROW_MESSAGE(v.add_parameter(name, 1.0), ModelError, not_an_identifier(name)) << name;
    EXPECT_THROW_MESSAGE(v.add_input(name), ModelError, not_an_identifier(name)) << name;
  }
  EXPECT_THROW_MESSAGE(v.add_coordinate(""), ModelError, not_an_identifier(""));
  EXPECT_EQ(v.coordinate_count(), 0u);
}

TEST(VariablesDeclare, IdentifiersWithUnderscoresAndDigitsAreAccepted) {
  Variables v;
  EXPECT_NO_THROW(v.add_coordinate("_theta2"));
  EXPECT_NO_THROW(v.add_parameter("L_1", 0.5));
  EXPECT_NO_THROW(v.add_input("F3"));
}

// ---------------------------------------------------------------------------------------------
// Lookup

TEST(VariablesLookup, FindReturnsEverySymbolByName) {
  Variables v;
  const auto x = v.add_coordinate("x");
  const auto m = v.add_parameter("m", 1.0);
  const auto u = v.add_input("u");
  ASSERT_TRUE(v.find("t").has_value());
  EXPECT_TRUE(v.find("t")->is_equal(v.time()));
  ASSERT_TRUE(v.find("x").has_value());
  EXPECT_TRUE(v.find("x")->is_equal(x.q));
  ASSERT_TRUE(v.find("x_dot").has_value());
  EXPECT_TRUE(v.find("x_dot")->is_equal(x.qd));
  ASSERT_TRUE(v.find("x_ddot").has_value());
  EXPECT_TRUE(v.find("x_ddot")->is_equal(x.qdd));
  ASSERT_TRUE(v.find("m").has_value());
  EXPECT_TRUE(v.find("m")->is_equal(m.symbol));
  ASSERT_TRUE(v.find("u").has_value());
  EXPECT_TRUE(v.find("u")->is_equal(u.symbol));
  EXPECT_FALSE(v.find("y").has_value());
  EXPECT_FALSE(v.find("m_dot").has_value());
}

TEST(VariablesLookup, KindOfClassifiesEverySymbol) {
  Variables v;
  const auto x = v.add_coordinate("x");
  const auto m = v.add_parameter("m", 1.0);
  const auto u = v.add_input("u");
  EXPECT_EQ(v.kind_of(v.time()), SymbolKind::time);
  EXPECT_EQ(v.kind_of(x.q), SymbolKind::coordinate);
  EXPECT_EQ(v.kind_of(x.qd), SymbolKind::rate);
  EXPECT_EQ(v.kind_of(x.qdd), SymbolKind::acceleration);
  EXPECT_EQ(v.kind_of(m.symbol), SymbolKind::parameter);
  EXPECT_EQ(v.kind_of(u.symbol), SymbolKind::input);
}

TEST(VariablesLookup, KindOfForeignSymbolIsEmptyEvenWithTheSameName) {
  Variables v;
  v.add_coordinate("x");
  const GiNaC::realsymbol foreign_x("x"), z("z");
  EXPECT_FALSE(v.kind_of(foreign_x).has_value());
  EXPECT_FALSE(v.kind_of(z).has_value());
  EXPECT_FALSE(v.kind_of(sin(z)).has_value());
}

TEST(VariablesLookup, CoordinateIndexOfPositionRateAndAcceleration) {
  Variables v;
  const auto a = v.add_coordinate("a");
  const auto b = v.add_coordinate("b");
  const auto m = v.add_parameter("m", 1.0);
  EXPECT_EQ(v.coordinate_index(a.q), 0u);
  EXPECT_EQ(v.coordinate_index(a.qd), 0u);
  EXPECT_EQ(v.coordinate_index(b.q), 1u);
  EXPECT_EQ(v.coordinate_index(b.qd), 1u);
  EXPECT_EQ(v.coordinate_index(b.qdd), 1u);
  EXPECT_FALSE(v.coordinate_index(m.symbol).has_value());
  EXPECT_FALSE(v.coordinate_index(v.time()).has_value());
  EXPECT_FALSE(v.coordinate_index(GiNaC::realsymbol("a")).has_value());
}

TEST(VariablesLookup, RequireKnownSymbolsAcceptsModelSymbols) {
  Variables v;
  const auto x = v.add_coordinate("x");
  const auto m = v.add_parameter("m", 1.0);
  const auto u = v.add_input("u");
  EXPECT_NO_THROW(v.require_known_symbols(m.symbol * sin(x.q) * x.qd + u.symbol * v.time() + x.qdd, "load"));
  EXPECT_NO_THROW(v.require_known_symbols(ex(3) * GiNaC::Pi, "constant"));
}

TEST(VariablesLookup, RequireKnownSymbolsRejectsForeignSymbolNamingIt) {
  Variables v;
  const auto x = v.add_coordinate("x");
  const GiNaC::realsymbol k("k_spring");
  EXPECT_THROW_MESSAGE(v.require_known_symbols(cos(x.q) + pow(k, 2), "spring force"), ModelError,
                       "spring force: 'k_spring' is not a time, coordinate, rate, parameter or input of this model");
  // a foreign symbol that merely shares a model name is still foreign
  EXPECT_THROW_MESSAGE(v.require_known_symbols(GiNaC::realsymbol("x"), "position"), ModelError,
                       "position: 'x' is not a time, coordinate, rate, parameter or input of this model");
}

// ---------------------------------------------------------------------------------------------
// Time derivative

TEST(VariablesTimeDerivative, ChainRuleThroughCoordinate) {
  Variables v;
  const auto q = v.add_coordinate("q");
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(sin(q.q)), cos(q.q) * q.qd));
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(pow(q.q, 3)), 3 * pow(q.q, 2) * q.qd));
}

TEST(VariablesTimeDerivative, ExplicitTimeDependence) {
  Variables v;
  const auto q = v.add_coordinate("q");
  const auto& t = v.time();
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(pow(t, 2) * q.q), 2 * t * q.q + pow(t, 2) * q.qd));
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(sin(3 * t)), 3 * cos(3 * t)));
}

TEST(VariablesTimeDerivative, RatesGiveAccelerations) {
  Variables v;
  const auto q = v.add_coordinate("q");
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(q.qd), q.qdd));
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(pow(q.qd, 2)), 2 * q.qd * q.qdd));
  EXPECT_TRUE(equal_after_expansion(v.time_derivative(q.q * q.qd), pow(q.qd, 2) + q.q * q.qdd));
}

TEST(VariablesTimeDerivative, SeveralCoordinatesAndParameters) {
  Variables v;
  const auto a = v.add_coordinate("a"), b = v.add_coordinate("b");
  const auto L = v.add_parameter("L", 1.0);
  EXPECT_TRUE(
      equal_after_expansion(v.time_derivative(L.symbol * cos(a.q - b.q)), -L.symbol * sin(a.q - b.q) * (a.qd - b.qd)));
}

TEST(VariablesTimeDerivative, ConstantsAndParametersHaveZeroRate) {
  Variables v;
  v.add_coordinate("q");
  const auto m = v.add_parameter("m", 3.0);
  EXPECT_TRUE(v.time_derivative(m.symbol).is_zero());
  EXPECT_TRUE(v.time_derivative(ex(7)).is_zero());
  EXPECT_TRUE(v.time_derivative(GiNaC::Pi * pow(m.symbol, 2)).is_zero());
}

TEST(VariablesTimeDerivative, InputThrowsDerivationErrorNamingIt) {
  Variables v;
  const auto q = v.add_coordinate("q");
  const auto u = v.add_input("motor");
  EXPECT_THROW_MESSAGE(v.time_derivative(u.symbol * q.q), DerivationError,
                       "time derivative: the expression contains the input 'motor', whose rate is unknown; inputs may "
                       "appear in loads but not in positions, rotations or constraints");
}

TEST(VariablesTimeDerivative, AccelerationThrowsDerivationErrorNamingIt) {
  Variables v;
  const auto q = v.add_coordinate("q");
  EXPECT_THROW_MESSAGE(
      v.time_derivative(q.qdd + q.q), DerivationError,
      "time derivative: the expression contains the acceleration 'q_ddot', whose rate is not a variable of the model");
}

TEST(VariablesTimeDerivative, ForeignSymbolThrows) {
  Variables v;
  const auto q = v.add_coordinate("q");
  const GiNaC::realsymbol z("z");
  EXPECT_THROW_MESSAGE(v.time_derivative(z * q.q), eomgen::Error, "time derivative: 'z' is not a symbol of this model");
}

// ---------------------------------------------------------------------------------------------
// Substitutions

TEST(VariablesSubstitution, AtRestZeroesRatesOnly) {
  Variables v;
  const auto q = v.add_coordinate("q");
  const ex e = q.q + q.qd * sin(q.q) + q.qdd + pow(q.qd, 2);
  EXPECT_TRUE(equal_after_expansion(v.at_rest(e), q.q + q.qdd));
}

TEST(VariablesSubstitution, WithoutAccelerationsZeroesAccelerationsOnly) {
  Variables v;
  const auto a = v.add_coordinate("a"), b = v.add_coordinate("b");
  const ex e = a.qdd * cos(b.q) + b.qdd * a.qd + a.q;
  EXPECT_TRUE(equal_after_expansion(v.without_accelerations(e), a.q));
}

}  // namespace
