// `eomgen linearize` as a user runs it on the shipped bicycle: the completed operating point,
// the reduced second-order form in JSON, and a sweep of the forward speed as text, CSV, JSON
// and a plot; malformed requests are usage errors that run nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

class Linearize : public eomgen::testing::CliFixture {
 protected:
  std::string bicycle = eomgen::testing::quote(std::string(EOMGEN_SOURCE_DIR) + "/models/whipple_bicycle.eom");
};

TEST_F(Linearize, TheBicycleAtSpeedSolvesItsRatesAndPrintsThePapersSecondOrderForm) {
  const auto run = eomgen("linearize " + bicycle + " --at x_dot=5 --drop-cyclic");
  ASSERT_EQ(run.status, 0) << run.err;
  // the rear wheel's rate is -x_dot / rR = -5 / 0.3, to the last digits the solve leaves
  EXPECT_THAT(run.out, HasSubstr("Solved from the constraints: y_dot = 0, psi_dot = 0, phi_dot = 0, theta_dot = 0, "
                                 "theta_r_dot = -16.6666666666666"));
  EXPECT_THAT(run.out, HasSubstr("State kept: [phi, delta, phi_dot, delta_dot]; dropped as cyclic: x, y, psi, "
                                 "theta_r, theta_f, theta_r_dot"));
  EXPECT_THAT(run.out, HasSubstr("Second-order form M dqdd + D dqd + K dq = B_u du in phi, delta (reduced"));
  EXPECT_THAT(run.out, HasSubstr("Linear system (notes, Theorem A.21): asymptotically stable"));
}

TEST_F(Linearize, JsonHoldsThePointTheSecondOrderFormAndTheEigenvalues) {
  const auto run = eomgen("linearize " + bicycle + " --at x_dot=5 --drop-cyclic -f json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["model"], "whipple_bicycle");
  EXPECT_EQ(j["point"]["x_dot"], 5.0);
  EXPECT_NEAR(j["point"]["theta_r_dot"].get<double>(), -5 / 0.3, 1e-12);
  EXPECT_EQ(j["second_order"]["coordinates"], nlohmann::json({"phi", "delta"}));
  EXPECT_NEAR(j["second_order"]["M"][0][0].get<double>(), 80.81722, 1e-12);
  EXPECT_NEAR(j["second_order"]["D"][0][1].get<double>(), 5 * 33.86641391492494, 1e-11);
  EXPECT_EQ(j["eigenvalues"].size(), 4u);
  EXPECT_EQ(j["linear"], "asymptotically stable");
}

TEST_F(Linearize, SweepFindsTheWeaveAndCapsizeSpeedsInEveryFormat) {
  const auto text = eomgen("linearize " + bicycle + " --drop-cyclic --sweep x_dot=0:10:0.5");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, StartsWith("Stability of whipple_bicycle against x_dot from 0 to 10 in steps of 0.5\n"));
  EXPECT_THAT(text.out, HasSubstr("  x_dot = 4.29238253634: unstable -> asymptotically stable\n"
                                  "  x_dot = 6.02426201539: asymptotically stable -> unstable\n"));

  const auto json = eomgen("linearize " + bicycle + " --drop-cyclic --sweep x_dot=0:10:0.5 -f json");
  ASSERT_EQ(json.status, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["points"].size(), 21u);
  ASSERT_EQ(j["changes"].size(), 2u);
  EXPECT_NEAR(j["changes"][0]["value"].get<double>(), 4.29238253634111, 1e-9);
  EXPECT_NEAR(j["changes"][1]["value"].get<double>(), 6.02426201538837, 1e-9);

  const fs::path table_path = dir_ / "work" / "speeds.csv", plot_path = dir_ / "work" / "speeds.svg";
  const auto csv = eomgen("linearize " + bicycle + " --drop-cyclic --sweep x_dot=0:10:0.5 -f csv -o " +
                          eomgen::testing::quote(table_path.string()) + " --plot " +
                          eomgen::testing::quote(plot_path.string()));
  ASSERT_EQ(csv.status, 0) << csv.err;
  const std::string table = eomgen::testing::slurp(table_path);
  EXPECT_THAT(table, StartsWith("x_dot,verdict,re1,im1,re2,im2,re3,im3,re4,im4\n0,unstable,"));
  EXPECT_THAT(csv.out, HasSubstr("x_dot = 4.29238253634: unstable -> asymptotically stable"));
  EXPECT_THAT(eomgen::testing::slurp(plot_path), HasSubstr("<svg"));
}

TEST_F(Linearize, MalformedSweepsAreUsageErrors) {
  for (const std::string arguments :
       {" --sweep x_dot=0:10", " --sweep x_dot=10:0:1", " --sweep x_dot=0:10:0", " --sweep x_dot=0:1e9:1e-9",
        " --sweep nope=0:1:0.5", " --sweep x_dot=0:1:0.5 --at x_dot=2", " --plot p.svg", " -f csv",
        " --sweep x_dot=0:1:0.5 --plot p.pdf", " --sweep x_dot=0:1:0.5 -f latex"}) {
    SCOPED_TRACE(arguments);
    const auto run = eomgen("linearize " + bicycle + " --drop-cyclic" + arguments);
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_THAT(run.err, StartsWith("eomgen: error: "));
    EXPECT_EQ(run.out, "");
  }
}

TEST_F(Linearize, ASweepOfADerivedParameterNamesWhatToSweepInstead) {
  const std::string derived = model("derived.eom",
                                    "parameter L = 2 [m]\nparameter d = L/2 [m]\nparameter m = 1 [kg]\n"
                                    "coordinate x\npoint p = w + (x + d)*a.1\nparticle bob(mass = m, at = p)\n");
  const auto run = eomgen("linearize " + eomgen::testing::quote(derived) + " --sweep d=0:1:0.5");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "eomgen: error: --sweep: 'd' is defined from other parameters of derived, and follows them: "
                     "expected one of those it is defined from: L\n");
}

TEST_F(Linearize, RatesThatContradictRollingMoveTheLeastTheyMustAndSaySo) {
  const auto run = eomgen("linearize " + bicycle + " --at x_dot=5,theta_r_dot=1,y_dot=0,psi_dot=0,theta_dot=0");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("Moved onto the constraints (the given values admit no consistent state; each moved "
                                 "the least it must): "));
  EXPECT_THAT(run.out, HasSubstr("theta_r_dot = "));
}

// a four-bar linkage (crank a1 = 0.3, coupler 1, rocker 0.8, ground 1.1; absolute angles) as a
// user writes it from docs/model-language.md
const std::string four_bar = eomgen::testing::quote(std::string(EOMGEN_SOURCE_DIR) + "/tests/cli/models/four_bar.eom");

// the closures at q1 = 0.5, by circle intersection: (q2, q3) = (0.710597, 1.669397) and
// (-1.051057, -2.009857)
TEST_F(Linearize, AFourBarClosesItsLoopFromTheGivenCrankAngleOnTheGuessedBranch) {
  const std::string& path = four_bar;
  const auto first = eomgen("linearize " + path + " --at q1=0.5");
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("Solved from the constraints: q2 = 0.71059732708969"));
  const auto other = eomgen("linearize " + path + " --at q1=0.5 --guess q2=-1,q3=-2 -f json");
  ASSERT_EQ(other.status, 0) << other.err;
  const nlohmann::json j = nlohmann::json::parse(other.out);
  EXPECT_EQ(j["point"]["q1"], 0.5);
  EXPECT_NEAR(j["point"]["q2"].get<double>(), -1.051057, 1e-6);
  EXPECT_NEAR(j["point"]["q3"].get<double>(), -2.009857, 1e-6);
  EXPECT_TRUE(j["moved"].empty());
}

TEST_F(Linearize, AFullGuessNearTheConstraintsIsCompletedAndTheMovesPrinted) {
  const std::string& path = four_bar;
  const auto run = eomgen("linearize " + path + " --at q1=0.5,q2=0.7146,q3=1.665 -f json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j["moved"].size(), 3u);
  for (const auto& m : j["moved"]) EXPECT_LT(std::abs(m["used"].get<double>() - m["given"].get<double>()), 0.006);
  EXPECT_NEAR(j["point"]["q2"].get<double>(), 0.7114, 1e-3);
}

TEST_F(Linearize, TheEquilibriumOfAFourBarStartsFromItsClosedGuess) {
  const std::string& path = four_bar;
  const auto run = eomgen("linearize " + path + " --at q1=-1.5,q2=0.5,q3=1.5 --equilibrium -f json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_TRUE(j["equilibrium"].get<bool>());
  // hanging: the crank down and to the left of its pivot, the mechanism's centre of mass lowest
  EXPECT_NEAR(j["point"]["q1"].get<double>(), -1.8339926088179, 1e-9);
}

TEST_F(Linearize, GuessesNameOnlyCoordinatesAndRatesNotGivenElsewhere) {
  const std::string& path = four_bar;
  const auto unknown = eomgen("linearize " + path + " --at q1=0.5 --guess g=1");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_THAT(unknown.err, HasSubstr("--guess: 'g' is not a coordinate or rate of four_bar"));
  const auto twice = eomgen("linearize " + path + " --at q1=0.5 --guess q1=1");
  EXPECT_EQ(twice.status, 2);
  EXPECT_THAT(twice.err, HasSubstr("--guess: 'q1' is also given in --at"));
}

TEST_F(Linearize, ALoopThatCannotCloseNamesTheConstraint) {
  const std::string& path = four_bar;
  const auto run = eomgen("linearize " + path + " --at q1=0.3 --guess q2=0.2,q3=2.5 --set d1=3");
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.err, HasSubstr("no state near the point satisfies the constraint 'loop_x'"));
}

TEST_F(Linearize, EvalWarnsOfAStateOffTheConstraints) {
  const std::string& path = four_bar;
  const auto run = eomgen("eval " + path + " --at q1=0.5");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("warning: the state violates the constraint 'loop_x': phi = -0.637"));
  const auto on = eomgen("eval " + path + " --at q1=0.5,q2=0.7105973270896951,q3=1.6693970778594451");
  ASSERT_EQ(on.status, 0) << on.err;
  EXPECT_EQ(on.err, "");
}

}  // namespace
