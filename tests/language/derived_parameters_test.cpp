// Derived parameters (`parameter d = 0.45*L`): defined from other parameters in any order of the
// file, symbols of their own in the equations (which name them as the model does), computed from
// the parameters once per parameter set, so the equations follow a change of what they are
// defined from; cycles and definitions that are no function of parameters are refused where they
// are written, and so is a mistake inside a definition.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/codegen/emit_model.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"
#include "eomgen/report/equation_printer.hpp"

namespace eomgen {
namespace {

// A point mass on a massless rod of length d = 0.45 L, d written before L.
const std::string pendulum =
    "parameter m = 2 [kg]\n"
    "parameter g = 9.81 [m/s^2]\n"
    "parameter d = 0.45*L [m]\n"
    "parameter L = 2 [m]\n"
    "coordinate theta\n"
    "frame b = rotate(a, 3, theta)\n"
    "point p = w + d*b.1\n"
    "particle bob(mass = m, at = p)\n"
    "gravity = -g*a.2\n";

std::string error_of(const std::string& text) { return testing::model_error_text(text, "h.eom"); }

std::vector<std::string> parameter_names(const Model& model) {
  std::vector<std::string> names;
  for (const Parameter& p : model.system.variables().parameters()) names.push_back(p.name);
  return names;
}

TEST(DerivedParameters, AreSymbolsOfTheirOwnListedWithTheirDefinitionDefaultAndPlace) {
  const Model model = parse_model(pendulum, "h.eom");
  const Variables& v = model.system.variables();
  // L is created when d needs it, before its own line: still each parameter once
  EXPECT_EQ(parameter_names(model), (std::vector<std::string>{"m", "g", "L"}));
  ASSERT_EQ(v.derived_parameters().size(), 1u);
  const DerivedParameter& d = v.derived_parameters()[0];
  EXPECT_EQ(d.name, "d");
  EXPECT_DOUBLE_EQ(d.default_value, 0.9);
  EXPECT_EQ(d.unit, "m");
  ASSERT_EQ(model.derived_parameter_locations.size(), 1u);
  EXPECT_EQ(model.derived_parameter_locations[0].line, 3);
  EXPECT_EQ(model.derived_parameter_locations[0].column, 11);
  EXPECT_TRUE((d.definition - GiNaC::numeric(9, 20) * *v.find("L")).expand().is_zero());
  EXPECT_EQ(v.kind_of(d.symbol), SymbolKind::derived_parameter);
  EXPECT_TRUE(v.find("d")->is_equal(d.symbol));
  EXPECT_DOUBLE_EQ(GiNaC::ex_to<GiNaC::numeric>(model.system.parameter_defaults().at(d.symbol)).to_double(), 0.9);
}

TEST(DerivedParameters, TheEquationsNameThemAsTheModelDoes) {
  const Model model = parse_model(pendulum, "h.eom");
  const ModelEquations eom = derive_equations(model);
  const GiNaC::ex d = *model.system.variables().find("d"), m = *model.system.variables().find("m");
  EXPECT_TRUE((eom.subexpressions.expand(eom.mass_matrix(0, 0)) - m * d * d).expand().is_zero())
      << eom.mass_matrix(0, 0);
  PrintOptions options;
  options.parts = parse_equation_parts("M");
  EXPECT_NE(format_equations(model, eom, options).find("M[1,1] = m*d^2"), std::string::npos)
      << format_equations(model, eom, options);
}

TEST(DerivedParameters, TheEquationsFollowTheParameterTheyAreDefinedFrom) {
  const Model model = parse_model(pendulum, "h.eom");
  const ModelEquations eom = derive_equations(model);
  // M = m d^2, F = -m g d cos(theta) with d = 0.45 L
  for (const double L : {2.0, 3.0}) {
    const NumericEquations x = evaluate_equations(model, eom, {{"theta", 0.3}, {"L", L}});
    const double d = 0.45 * L;
    EXPECT_NEAR(x.mass_matrix(0, 0), 2 * d * d, 1e-13);
    EXPECT_NEAR(x.forcing(0), -2 * 9.81 * d * std::cos(0.3), 1e-12);
    EXPECT_NEAR(x.potential_energy, 2 * 9.81 * d * std::sin(0.3), 1e-12);
  }
}

TEST(DerivedParameters, MayBeDefinedFromDerivedOnesInAnyOrder) {
  const Model model = parse_model("parameter e = d/3 [m]\n" + pendulum + "point q = w + e*b.2\n"
                                  "particle second(mass = m, at = q)\n", "h.eom");
  const std::vector<DerivedParameter>& derived = model.system.variables().derived_parameters();
  ASSERT_EQ(derived.size(), 2u);
  // in the order they are computed: each after those it is defined from
  EXPECT_EQ(derived[0].name, "d");
  EXPECT_EQ(derived[1].name, "e");
  EXPECT_DOUBLE_EQ(derived[1].default_value, 0.3);
  EXPECT_EQ(model.derived_parameter_locations[1].line, 1);
  const NumericEquations x = evaluate_equations(model, derive_equations(model), {{"L", 3.0}});
  EXPECT_NEAR(x.mass_matrix(0, 0), 2 * (1.35 * 1.35 + 0.45 * 0.45), 1e-13);
}

TEST(DerivedParameters, AParameterWhoseValueIsAConstantExpressionStaysAParameter) {
  const Model model = parse_model("const n = 4\nparameter k = 2*pi/n [rad]\n" + pendulum, "h.eom");
  EXPECT_EQ(parameter_names(model), (std::vector<std::string>{"k", "m", "g", "L"}));
  EXPECT_DOUBLE_EQ(model.system.variables().parameters()[0].default_value, M_PI / 2);
}

TEST(DerivedParameters, TheGeneratedConstantsComputeThemAndTheParametersHaveNoFieldForThem) {
  const Model model = parse_model(pendulum, "h.eom");
  const std::string header = emit_model(model, derive_equations(model)).header;
  EXPECT_NE(header.find("    Scalar L = Scalar(2); // [m]\n"), std::string::npos);
  EXPECT_EQ(header.find("Scalar d = Scalar(0.9)"), std::string::npos);
  EXPECT_NE(header.find("  struct DerivedParameters {\n    Scalar d = Scalar(0);  // = 9/20*L [m]\n  };\n"),
            std::string::npos)
      << header.substr(0, 4000);
  EXPECT_NE(header.find("      derived.d = p.L * Scalar(0.45);\n"), std::string::npos) << header.substr(0, 4000);
  EXPECT_NE(header.find("    DerivedParameters<Scalar> derived;\n"), std::string::npos);
}

TEST(DerivedParameters, TheReportsListThemWithTheirDefinitionsAndDefaultsAndShowThemWrittenOutOnRequest) {
  const Model model = parse_model(pendulum, "h.eom");
  const ModelEquations eom = derive_equations(model);
  PrintOptions options;
  const std::string text = format_equations(model, eom, options);
  EXPECT_NE(text.find("  L = 2 [m]\nDerived parameters (each computed from the parameters and those before it):\n"
                      "  d = 9*L/20 = 0.9 [m]\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("M[1,1] = m*d^2\n"), std::string::npos) << text;
  options.expand_derived_parameters = true;
  EXPECT_NE(format_equations(model, eom, options).find("M[1,1] = 81*m*L^2/400\n"), std::string::npos)
      << format_equations(model, eom, options);
  options.expand_derived_parameters = false;
  options.format = EquationFormat::markdown;
  EXPECT_NE(format_equations(model, eom, options).find("| `d` | `9*L/20` | 0.9 | m |\n"), std::string::npos);
  options.format = EquationFormat::latex;
  EXPECT_NE(format_equations(model, eom, options).find("\\item Derived parameters: $d = \\frac{9 L}{20} = 0.9$~m\n"),
            std::string::npos)
      << format_equations(model, eom, options).substr(0, 1500);
}

// The model of issue 28: each derived parameter uses the one before it twice, so written out it
// is a tree of 2^N nodes. As symbols they are N short definitions: a thousand of them check,
// derive and evaluate at once.
std::string chained_parameters(int n) {
  std::string text = "parameter L = 0.5 [m]\nparameter g = 9.81 [m/s^2]\nparameter m = 1 [kg]\nparameter a0 = L [m]\n";
  for (int i = 1; i <= n; ++i)
    text += "parameter a" + std::to_string(i) + " = a" + std::to_string(i - 1) + "*(1 + sin(a" + std::to_string(i - 1) +
            "/L)) + L [m]\n";
  return text + "coordinate q\nframe b = rotate(a, 3, q)\npoint p = w - a" + std::to_string(n) +
         "*b.2\nparticle bob(mass = m, at = p)\ngravity = -g*a.2\n";
}

TEST(DerivedParameters, AChainOfAThousandEachUsingTheOneBeforeTwiceIsAThousandSymbols) {
  const Model model = parse_model(chained_parameters(1000), "chain.eom");
  ASSERT_EQ(model.system.variables().derived_parameters().size(), 1001u);
  const ModelEquations eom = derive_equations(model);
  for (const double L : {0.5, 0.25}) {
    double a = L;
    for (int i = 1; i <= 1000; ++i) a = a * (1 + std::sin(a / L)) + L;
    const NumericEquations x = evaluate_equations(model, eom, {{"q", 0.3}, {"L", L}});
    EXPECT_NEAR(x.mass_matrix(0, 0), a * a, 1e-9 * a * a) << L;
    EXPECT_NEAR(x.forcing(0), -9.81 * a * std::sin(0.3), 1e-9 * a) << L;
  }
  const std::string header = emit_model(model, eom).header;
  EXPECT_NE(header.find("      derived.a1000 = "), std::string::npos);
}

TEST(DerivedParameters, AMistakeInADefinitionIsReportedThereNamingTheParametersAsWritten) {
  const std::string rod = "parameter lam_p = 2 [kg/m]\nparameter lp = 0.5 [m]\nparameter mp = lam_p*lp [kg]\n";
  const std::string rest = "coordinate theta\nframe b = rotate(a, 3, theta)\npoint c = w + lp/2*b.1\n"
                           "body rod(mass = mp, centre = c, frame = b, inertia = diag(Ip, Ip, Ip))\n";
  // lp instead of lp^2: named as written, not as lam_p and lp
  EXPECT_EQ(error_of(rod + "parameter Ip = mp*lp/12 [kg m^2]\n" + rest),
            "h.eom:4:16: error: parameter 'Ip': the term '1/12*lp*mp' has dimension kg m, expected kg m^2 for its "
            "unit [kg m^2]");
  // without a unit: the definition's own disagreement, at the definition, not where it is used
  EXPECT_EQ(error_of(rod + "parameter Ip = mp*lp^2/12 + lp\n" + rest),
            "h.eom:4:16: error: parameter 'Ip': the terms '1/12*lp^2*mp' and 'lp' have different dimensions, kg m^2 "
            "and m");
}

TEST(DerivedParameters, ACycleIsReportedWhereItCloses) {
  EXPECT_EQ(error_of("parameter k1 = 2*k2\nparameter k2 = k3 + 1\nparameter k3 = k1\n" + pendulum),
            "h.eom:1:11: error: parameter 'k1' is defined through a cycle: k1 -> k2 -> k3 -> k1");
  EXPECT_EQ(error_of("parameter k = k + 1\n" + pendulum),
            "h.eom:1:11: error: parameter 'k' is defined through a cycle: k -> k");
}

TEST(DerivedParameters, ADefinitionFromACoordinateARateAnInputTimeOrAPointIsRefusedAtTheName) {
  const std::string expected = ": error: parameter 'k': expected an expression of numbers, consts and other "
                               "parameters, got the ";
  EXPECT_EQ(error_of("parameter k = 2*theta\n" + pendulum), "h.eom:1:17" + expected + "coordinate 'theta'");
  EXPECT_EQ(error_of(pendulum + "parameter k = 2*theta_dot\n"), "h.eom:10:17" + expected + "rate 'theta_dot'");
  EXPECT_EQ(error_of("input u [N]\nparameter k = u\n" + pendulum), "h.eom:2:15" + expected + "input 'u'");
  EXPECT_EQ(error_of("parameter k = L*t\n" + pendulum), "h.eom:1:17" + expected + "time 't'");
  EXPECT_EQ(error_of("parameter k = norm(position(p))\n" + pendulum), "h.eom:1:29" + expected + "point 'p'");
  EXPECT_EQ(error_of("parameter k = dot(b.1, a.1)\n" + pendulum), "h.eom:1:19" + expected + "frame 'b'");
}

TEST(DerivedParameters, ADefinitionWithoutAFiniteRealValueAtTheDefaultsIsRefused) {
  const std::string expected = ": the value at the other parameters' default values is not a finite real number: "
                               "expected a definition that has one";
  EXPECT_EQ(error_of("parameter k = sqrt(1 - L)\n" + pendulum), "h.eom:1:15: error: parameter 'k'" + expected);
  EXPECT_EQ(error_of("parameter z = 0 [m]\nparameter k = L/z\n" + pendulum), "h.eom:2:15: error: parameter 'k'" + expected);
}

TEST(DerivedParameters, InAModelWithUnitsTheirDefinitionHasTheirUnitOrGivesThemOne) {
  EXPECT_EQ(error_of("parameter k = 0.45*L [kg]\n" + pendulum),
            "h.eom:1:15: error: parameter 'k': the term '9/20*L' has dimension m, expected kg for its unit [kg]");
  // without a unit, the definition's: a length, which is no mass
  EXPECT_EQ(error_of("parameter k = 0.45*L\n" + pendulum + "particle second(mass = k, at = p)\n"),
            "h.eom:11:24: error: particle 'second': the term 'k' has dimension m, expected kg for a mass");
  EXPECT_NO_THROW(parse_model("parameter k = 0.45*L\n" + pendulum + "point q = w + k*b.2\n"
                              "particle second(mass = m, at = q)\n", "h.eom"));
}

TEST(DerivedParameters, DuplicateNamesAreStillFoundInTheFilesOrder) {
  EXPECT_EQ(error_of("parameter d = 1\n" + pendulum),
            "h.eom:4:11: error: duplicate name 'd': already declared as a parameter at h.eom:1:11");
}

}  // namespace
}  // namespace eomgen
