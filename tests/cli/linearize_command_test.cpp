// `eomgen linearize` as a user runs it on the shipped bicycle: the completed operating point,
// the reduced second-order form in JSON, and a sweep of the forward speed as text, CSV, JSON
// and a plot; malformed requests are usage errors that run nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
  EXPECT_THAT(run.out, HasSubstr("Solved from the constraints: y_dot = 0, psi_dot = 0, theta_dot = 0, theta_r_dot = "
                                 "-16.66666666666666"));
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

TEST_F(Linearize, APointOffTheConstraintsNamesTheConstraint) {
  const auto run = eomgen("linearize " + bicycle + " --at x_dot=5,theta_r_dot=1,y_dot=0,psi_dot=0,theta_dot=0");
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.err, HasSubstr("violates the constraint 'rear_2'"));
  EXPECT_THAT(run.err, HasSubstr("leave out one of the rates it involves (x_dot, theta_dot, theta_r_dot)"));
}

}  // namespace
