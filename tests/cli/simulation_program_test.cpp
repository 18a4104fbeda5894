// The simulation program's main() (generator/cli/simulation_program/), run in-process on a
// generated model: the CSV and summary for a command line as `eomgen simulate` writes it, the
// default sampling, and arguments eomgen never writes, which are reported as its bug.
// (`eomgen simulate` itself, with its checks in the user's terms, is simulate_command_test.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "simple_pendulum.hpp"
#include "simulation_main.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using Pendulum = eomgen_models::simple_pendulum::Model;

struct Outcome {
  int status;
  std::string out, err;
};

Outcome run_program(std::vector<std::string> arguments) {
  std::string program = "simulate";
  std::vector<char*> argv{program.data()};
  for (std::string& a : arguments) argv.push_back(a.data());
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const int status = eomgen::simulation_program::simulation_main<Pendulum>(static_cast<int>(argv.size()), argv.data());
  std::fflush(stdout);
  std::fflush(stderr);
  Outcome run{status, ::testing::internal::GetCapturedStdout(), ::testing::internal::GetCapturedStderr()};
  return run;
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class SimulationProgram : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    csv_ = fs::temp_directory_path() / ("eomgen_simulation_program_" + std::string(info->name()) + ".csv");
  }
  void TearDown() override { fs::remove(csv_); }
  fs::path csv_;
};

TEST_F(SimulationProgram, WritesTheCsvAndTheSummaryForTheCommandLineEomgenWrites) {
  const Outcome run =
      run_program({"--t-end", "1", "--method", "rk4", "--solver", "kkt", "--stabilization", "projection", "--dt",
                   "0.01", "--set", "l=0.80000000000000004", "--init", "theta=0.20000000000000001", "--init",
                   "theta_dot=0.10000000000000001", "--csv", csv_.string()});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_THAT(run.out, StartsWith("simulated simple_pendulum from t = 0 to 1 s with rk4 (dt 0.01): 100 steps, "
                                  "400 evaluations, "));
  EXPECT_THAT(run.out, HasSubstr("\nenergy T+V: "));
  EXPECT_THAT(run.out, HasSubstr("\nrows: 101\n"));
  const std::vector<std::string> lines = lines_of(csv_);
  ASSERT_EQ(lines.size(), 102u);
  EXPECT_EQ(lines[0], "t,theta,theta_dot,T,V,T+V,bob_pos_1,bob_pos_2,bob_pos_3,bob_vel_1,bob_vel_2,bob_vel_3,height");
  // every number as %.17g, so that it reads back exactly
  EXPECT_THAT(lines[1], StartsWith("0,0.20000000000000001,0.10000000000000001,"));
  EXPECT_THAT(lines.back(), StartsWith("1,"));
}

// simulate always generates the animation's recording as the last outputs (scene_recording.hpp):
// they never reach the CSV, and with --scene they go to their own file with t, q, T and V
TEST_F(SimulationProgram, OutputsFromSceneFirstOnGoToTheSceneFileAndNeverToTheCsv) {
  const fs::path scene = fs::path(csv_).replace_extension(".scene");
  const Outcome run = run_program({"--t-end", "1", "--method", "rk4", "--dt", "0.5", "--init", "theta=0.25",
                                   "--csv", csv_.string(), "--scene-first", "3", "--scene", scene.string()});
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> lines = lines_of(csv_), scene_lines = lines_of(scene);
  fs::remove(scene);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "t,theta,theta_dot,T,V,T+V,bob_pos_1,bob_pos_2,bob_pos_3");
  ASSERT_EQ(scene_lines.size(), 3u);  // no header: t, theta, T, V, bob_vel_1..3, height
  EXPECT_THAT(scene_lines[0], StartsWith("0,0.25,0,"));
  EXPECT_EQ(std::count(scene_lines[0].begin(), scene_lines[0].end(), ','), 7);
  EXPECT_THAT(scene_lines[2], StartsWith("1,"));
  const Outcome without = run_program({"--t-end", "1", "--csv", csv_.string(), "--scene", scene.string()});
  EXPECT_EQ(without.status, 2);
  EXPECT_THAT(without.err, HasSubstr("--scene without --scene-first"));
}

TEST_F(SimulationProgram, SamplesAboutAThousandRowsWhenNoIntervalIsGiven) {
  const Outcome run = run_program({"--t-end", "2", "--method", "dp5", "--solver", "null-space", "--stabilization",
                                   "none", "--init", "theta=1", "--csv", csv_.string()});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("with dp5 (rtol 1e-08, atol 1e-10)"));
  EXPECT_THAT(run.out, HasSubstr("\nrows: 1001\n"));
  EXPECT_EQ(lines_of(csv_).size(), 1002u);
}

// eomgen checks the request against the model and the registry before it builds the program;
// an argument it would never write is its bug, said so, with exit status 2 and no CSV
TEST_F(SimulationProgram, ArgumentsEomgenNeverWritesAreReportedAsItsBug) {
  const std::string csv = csv_.string();
  const struct {
    std::vector<std::string> arguments;
    std::string message;
  } cases[] = {
      {{"--t-end", "1"}, "--t-end and --csv are required"},
      {{"--t-end", "1", "--csv", csv, "--frobnicate", "1"}, "'--frobnicate'"},
      {{"--t-end", "1", "--csv", csv, "--dt"}, "'--dt'"},
      {{"--t-end", "1", "--csv", csv, "--method", "rk45"}, "--method 'rk45'"},
      {{"--t-end", "1", "--csv", csv, "--solver", "qr"}, "'--solver'"},
      {{"--t-end", "abc", "--csv", csv}, "--t-end 'abc'"},
      {{"--t-end", "1", "--csv", csv, "--set", "mass=2"}, "--set 'mass=2': no such name in simple_pendulum"},
      {{"--t-end", "1", "--csv", csv, "--init", "phi_dot=2"}, "--init 'phi_dot=2': no such name in simple_pendulum"},
      {{"--t-end", "1", "--csv", csv, "--input", "u=2"}, "--input 'u=2': no such name in simple_pendulum"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.message);
    const Outcome run = run_program(c.arguments);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err, "error: malformed argument from eomgen simulate: " + c.message + "\n");
    EXPECT_EQ(run.out, "");
    EXPECT_FALSE(fs::exists(csv_));
  }
}

// what simulate() itself refuses is reported with its message
TEST_F(SimulationProgram, OptionsSimulateRejectsAreUsageErrors) {
  const Outcome run = run_program({"--t-end", "-1", "--method", "dp5", "--csv", csv_.string()});
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "error: simulate: time span expected finite with t_end >= t0, got [0, -1]\n");
}

}  // namespace
