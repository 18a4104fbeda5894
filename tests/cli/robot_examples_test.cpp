// examples/robots/iiwa14_waypoints.eom: the KUKA iiwa 14 as `eomgen import` writes it, with a
// controller section of its own below (a joint-space PD to waypoints plus exact gravity
// compensation; docs/robots.md). The imported part must be what the importer writes now, so a
// change of the importer fails here until the file is rewritten (the command is in the file);
// and the arm, simulated, must hold still against gravity and settle on every waypoint.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {

using eomgen::testing::CliFixture;
using eomgen::testing::Outcome;
using eomgen::testing::quote;
using eomgen::testing::slurp;
namespace fs = std::filesystem;

const fs::path source = EOMGEN_SOURCE_DIR;
const fs::path example = source / "examples" / "robots" / "iiwa14_waypoints.eom";
const fs::path urdf = source / "models" / "robots" / "iiwa14.urdf";
// the first line of the hand-written part, after the imported text and one blank line
const std::string controller_marker = "\n# ==== controller";

class RobotExamples : public CliFixture {};

TEST_F(RobotExamples, ImportedPartIsWhatEomgenImportWritesNow) {
  const std::string text = slurp(example);
  const std::size_t at = text.find(controller_marker);
  ASSERT_NE(at, std::string::npos) << example << " has no line starting '" << controller_marker.substr(1) << "'";
  const Outcome imported = eomgen("import " + quote(urdf.string()));
  ASSERT_EQ(imported.status, 0) << imported.err;
  EXPECT_EQ(text.substr(0, at), imported.out)
      << example << ": the part above the controller section is no longer what `eomgen import "
      << "models/robots/iiwa14.urdf` writes; rewrite it with the command in the file's controller section";
  // and the whole file is a model
  const Outcome check = eomgen("check " + quote(example.string()));
  ASSERT_EQ(check.status, 0) << check.err;
  EXPECT_NE(check.out.find("Coordinates (n = 7)"), std::string::npos) << check.out;
}

/// The CSV of a run: its columns by name, one vector of values each.
std::map<std::string, std::vector<double>> read_columns(const fs::path& path) {
  std::istringstream text(slurp(path));
  std::string line;
  std::getline(text, line);
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(text, line)) {
    std::istringstream row(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(row, cell, ','); ++k) columns[names.at(k)].push_back(std::stod(cell));
    EXPECT_EQ(k, names.size()) << line;
  }
  return columns;
}

/// The numbers of the controller's `parameter NAME = NUMBER` lines, by name.
std::map<std::string, double> controller_parameters(const std::string& text) {
  std::map<std::string, double> out;
  const std::regex line("^parameter ([A-Za-z0-9_]+) = ([-+.0-9eE]+)");
  std::istringstream in(text.substr(text.find(controller_marker)));
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_search(l, m, line)) out[m[1]] = std::stod(m[2]);
  }
  return out;
}

TEST_F(RobotExamples, ArmHoldsAgainstGravityAndSettlesOnEveryWaypoint) {
  if (!EOMGEN_SIMULATION_TESTS) GTEST_SKIP() << "EOMGEN_SIMULATION_TESTS is off";
  const std::map<std::string, double> p = controller_parameters(slurp(example));
  ASSERT_EQ(p.count("move_time"), 1u);
  const double move = p.at("move_time");
  const std::vector<double> starts{p.at("t_move1"), p.at("t_move2"), p.at("t_move3")};
  const double t_end = starts.back() + move + 2.5;
  const fs::path csv = dir_ / "arm.csv";
  const Outcome run = eomgen("simulate " + quote(example.string()) + " --t-end " + std::to_string(t_end) +
                             " --sample 0.01 --no-plot -o " + quote(csv.string()) + " --cache-dir " +
                             quote(EOMGEN_TEST_CACHE_DIR));
  ASSERT_EQ(run.status, 0) << run.err;
  std::map<std::string, std::vector<double>> columns = read_columns(csv);
  const std::vector<double>& t = columns.at("t");
  const auto row_at = [&](double time) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (std::abs(t[i] - time) < std::abs(t[best] - time)) best = i;
    return best;
  };
  const auto q = [&](int joint) -> const std::vector<double>& {
    return columns.at("iiwa_joint_" + std::to_string(joint));
  };
  const auto qd = [&](int joint) -> const std::vector<double>& {
    return columns.at("iiwa_joint_" + std::to_string(joint) + "_dot");
  };

  // upright at rest until the first move: the compensation cancels gravity exactly (without
  // it the arm falls: its mass centres are off the joint axes)
  for (std::size_t i = 0; t[i] < starts[0]; ++i)
    for (int j = 1; j <= 7; ++j) EXPECT_NEAR(q(j)[i], 0.0, 1e-9) << "joint " << j << " at t = " << t[i];

  // the end of each hold: on the waypoint, at rest; and half-way through each move, visibly
  // on the way (the reference has moved by half its step there)
  for (int k = 1; k <= 3; ++k) {
    const double hold_end = k < 3 ? starts[static_cast<std::size_t>(k)] - 0.01 : t_end;
    const std::size_t end = row_at(hold_end), middle = row_at(starts[static_cast<std::size_t>(k - 1)] + move / 2);
    double largest_step = 0;
    for (int j = 1; j <= 7; ++j) {
      const std::string joint = "q" + std::to_string(j);
      const double goal = p.at(joint + "_wp" + std::to_string(k));
      const double before = k == 1 ? 0.0 : p.at(joint + "_wp" + std::to_string(k - 1));
      EXPECT_NEAR(q(j)[end], goal, 1e-5) << "joint " << j << ", waypoint " << k << ", t = " << t[end];
      EXPECT_NEAR(qd(j)[end], 0.0, 1e-4) << "joint " << j << ", waypoint " << k << ", t = " << t[end];
      largest_step = std::max(largest_step, std::abs(goal - before));
      if (std::abs(goal - before) > 0.1) {
        EXPECT_GT(std::abs(q(j)[middle] - before), 0.2 * std::abs(goal - before))
            << "joint " << j << " has hardly moved half-way to waypoint " << k;
      }
    }
    EXPECT_GT(largest_step, 0.5) << "waypoint " << k << " is too close to the one before to show";
  }
}

}  // namespace
