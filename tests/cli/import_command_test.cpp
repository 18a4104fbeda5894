// `eomgen import ROBOT.urdf` and the other commands given a URDF, through the built program
// (issue 29): the model goes to standard output or, whole, to -o; bad input exits 1 with
// file:line:col: error: and writes nothing, not even over an existing -o file; -o naming the
// URDF itself is refused before anything runs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::testing::Outcome;
using eomgen::testing::quote;
using eomgen::testing::slurp;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

std::string robot_path(const std::string& stem) {
  return (fs::path(EOMGEN_SOURCE_DIR) / "models" / "robots" / (stem + ".urdf")).string();
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    out.push_back(text.substr(at, end - at));
    at = end == std::string::npos ? text.size() : end + 1;
  }
  return out;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename());
  std::sort(files.begin(), files.end());
  return files;
}

const char* const inertia = R"(<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>)";

// a pendulum whose arm has a mass `mass` and an inertia `arm_inertia`, and a hand on it
std::string pendulum(const std::string& mass = "1", const std::string& arm_inertia = inertia,
                     const std::string& hand_inertia = inertia) {
  return "<robot name=\"pendulum\">\n"
         "  <link name=\"base\"/>\n"
         "  <link name=\"arm\">\n"
         "    <inertial><origin xyz=\"0 0 -0.5\"/>\n"
         "      <mass value=\"" + mass + "\"/>\n"
         "      " + arm_inertia + "\n"
         "    </inertial>\n"
         "  </link>\n"
         "  <link name=\"hand\"><inertial><mass value=\"0.5\"/>" + hand_inertia + "</inertial></link>\n"
         "  <joint name=\"hinge\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>"
         "<axis xyz=\"0 1 0\"/></joint>\n"
         "  <joint name=\"wrist\" type=\"continuous\"><parent link=\"arm\"/><child link=\"hand\"/>"
         "<origin xyz=\"0 0 -1\"/><axis xyz=\"0 1 0\"/></joint>\n"
         "</robot>\n";
}

class ImportCommand : public eomgen::testing::CliFixture {};

TEST_F(ImportCommand, PrintsTheModelOnStandardOutputNamingItsSource) {
  const Outcome run = eomgen("import " + quote(robot_path("ur5")));
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(first_line(run.out), "# Robot 'ur5', imported by `eomgen import` from ur5.urdf.");
  EXPECT_THAT(run.out, HasSubstr("\nmodel ur5 \"ur5 (imported from ur5.urdf)\"\n"));
  EXPECT_THAT(run.out, HasSubstr("\ncoordinate shoulder_pan_joint\n"));
}

// the file -o writes is the text the command prints, and reads as the URDF itself does
TEST_F(ImportCommand, TheWrittenModelChecksAsTheUrdfItselfDoes) {
  for (const std::string stem : {"ur5", "iiwa14", "panda", "two_arm_torso"}) {
    SCOPED_TRACE(stem);
    const std::string out = (dir_ / "work" / (stem + ".eom")).string();
    const Outcome written = eomgen("import " + quote(robot_path(stem)) + " -o " + quote(out));
    EXPECT_EQ(written.status, 0) << written.err;
    EXPECT_EQ(written.out, "");
    EXPECT_EQ(written.err, "");
    EXPECT_EQ(slurp(out), eomgen("import " + quote(robot_path(stem))).out);
    const Outcome from_model = eomgen("check " + quote(out));
    const Outcome from_urdf = eomgen("check " + quote(robot_path(stem)));
    EXPECT_EQ(from_model.status, 0) << from_model.err;
    EXPECT_EQ(from_urdf.status, 0) << from_urdf.err;
    EXPECT_THAT(from_urdf.out, StartsWith("Model: " + stem + "\nDescription: " + stem + " (imported from " + stem +
                                          ".urdf)\n"));
    EXPECT_THAT(from_urdf.out, HasSubstr("Derivation: ok"));
    EXPECT_EQ(from_model.out, from_urdf.out);
  }
}

TEST_F(ImportCommand, ABadUrdfExitsOneAtItsPlaceAndWritesNothing) {
  const std::string bad = model("bad.urdf", pendulum("-2"));
  const fs::path out = dir_ / "work" / "out.eom";
  const std::string expected =
      bad + ":5:13: error: link 'arm': the mass -2 is negative: expected a mass of zero or more\n";
  const Outcome printed = eomgen("import " + quote(bad));
  EXPECT_EQ(printed.status, 1);
  EXPECT_EQ(printed.out, "");
  EXPECT_EQ(printed.err, expected);
  const Outcome to_file = eomgen("import " + quote(bad) + " -o " + quote(out.string()));
  EXPECT_EQ(to_file.status, 1);
  EXPECT_EQ(to_file.err, expected);
  EXPECT_FALSE(fs::exists(out));
  // an error of the written model's names (found while writing it), over an existing file
  std::string colliding = pendulum();
  colliding.replace(colliding.find("name=\"hand\""), 11, "name=\"arm.mass\"");
  colliding.replace(colliding.find("link=\"hand\""), 11, "link=\"arm.mass\"");
  const std::string collide = model("collide.urdf", colliding);
  const std::string previous = "# a model of the user's, to be kept\n";
  model("out.eom", previous);
  const Outcome kept = eomgen("import " + quote(collide) + " -o " + quote(out.string()));
  EXPECT_EQ(kept.status, 1);
  EXPECT_THAT(kept.err, StartsWith(collide + ":9:3: error: link 'arm.mass' becomes the name 'arm_mass' in the "
                                          "model, which link 'arm' (line 3) already has"));
  EXPECT_EQ(slurp(out), previous);
  // nothing beside: no temporary file left behind
  EXPECT_EQ(files_in(dir_ / "work"), (std::vector<fs::path>{"bad.urdf", "collide.urdf", "out.eom"}));
}

TEST_F(ImportCommand, EveryCommandReportsABadUrdfAtItsPlace) {
  const std::string bad = model("bad.urdf", pendulum("nan"));
  for (const std::string command : {"check", "derive", "eval", "generate", "linearize"}) {
    SCOPED_TRACE(command);
    const Outcome run = eomgen(command + " " + quote(bad));
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "");
    EXPECT_EQ(run.err, bad + ":5:13: error: link 'arm': mass: 'nan' is not a number\n");
  }
}

TEST_F(ImportCommand, AnOutputThatIsTheUrdfItselfIsRefusedAndTheUrdfKept) {
  const std::string text = pendulum();
  const std::string urdf = model("robot.urdf", text);
  fs::create_symlink(urdf, dir_ / "work" / "robot.eom");
  for (const std::string& target : {urdf, (dir_ / "work" / "robot.eom").string()}) {
    SCOPED_TRACE(target);
    const Outcome run = eomgen("import " + quote(urdf) + " -o " + quote(target));
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.out, "");
    EXPECT_THAT(run.err, StartsWith("eomgen: error: -o: '" + target + "' is the model file"));
    EXPECT_EQ(slurp(urdf), text);
    EXPECT_TRUE(fs::is_symlink(dir_ / "work" / "robot.eom"));
  }
}

TEST_F(ImportCommand, RepairInertiaListsEveryRepairedLinkOnStandardError) {
  // the arm's 3 > 1 + 1, the hand's rank-one placeholder
  const std::string urdf = model(
      "robot.urdf", pendulum("2", R"(<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/>)",
                             R"(<inertia ixx="1e-6" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>)"));
  const Outcome refused = eomgen("import " + quote(urdf));
  EXPECT_EQ(refused.status, 1);
  EXPECT_THAT(refused.err, StartsWith(urdf + ":6:7: error: link 'arm': the inertia has the principal moments 1, 1, 3"));
  EXPECT_THAT(refused.err, HasSubstr("--repair-inertia"));
  EXPECT_EQ(eomgen("check " + quote(urdf)).status, 1);

  const fs::path out = dir_ / "work" / "robot.eom";
  const Outcome repaired = eomgen("import " + quote(urdf) + " --repair-inertia -o " + quote(out.string()));
  EXPECT_EQ(repaired.status, 0) << repaired.err;
  const std::vector<std::string> said = lines(repaired.err);
  ASSERT_EQ(said.size(), 2u) << repaired.err;
  EXPECT_THAT(said[0], StartsWith("eomgen: --repair-inertia: link 'arm': inertia with principal moments 1, 1, 3"));
  EXPECT_THAT(said[0], HasSubstr("replaced by one with 1.5, 1.5, 3"));
  EXPECT_THAT(said[1], StartsWith("eomgen: --repair-inertia: link 'hand': inertia with principal moments 0, 0, 1e-06"));
  const Outcome check = eomgen("check " + quote(out.string()));
  EXPECT_EQ(check.status, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("Bodies (2): arm_body, hand_body\n"));
  // every command takes the repair too (the model it reads is the repaired one; the repairs are
  // in the text's comments), and only for a URDF
  const Outcome checked = eomgen("check " + quote(urdf) + " --repair-inertia");
  EXPECT_EQ(checked.status, 0) << checked.err;
  EXPECT_THAT(checked.out, HasSubstr("Bodies (2): arm_body, hand_body\n"));
  const Outcome not_urdf = eomgen("check " + quote(out.string()) + " --repair-inertia");
  EXPECT_EQ(not_urdf.status, 2);
  EXPECT_THAT(not_urdf.err, HasSubstr("--repair-inertia: applies to a robot's URDF file (.urdf)"));
  // a robot with nothing to repair: nothing said
  const Outcome sound = eomgen("import " + quote(model("sound.urdf", pendulum())) + " --repair-inertia");
  EXPECT_EQ(sound.status, 0) << sound.err;
  EXPECT_EQ(sound.err, "");
}

TEST_F(ImportCommand, DeriveEvalAndGenerateReadAUrdf) {
  const std::string ur5 = quote(robot_path("ur5"));
  const Outcome derived = eomgen("derive " + ur5 + " --only M");
  EXPECT_EQ(derived.status, 0) << derived.err;
  EXPECT_THAT(derived.out, HasSubstr("M[6,6] ="));

  const Outcome evaluated = eomgen("eval " + ur5 + " --at shoulder_lift_joint=0.3 -f json");
  EXPECT_EQ(evaluated.status, 0) << evaluated.err;
  const nlohmann::json json = nlohmann::json::parse(evaluated.out);
  EXPECT_EQ(json["model"], "ur5");
  EXPECT_EQ(json["coordinates"], nlohmann::json({"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                                 "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"}));
  EXPECT_EQ(json["state"]["shoulder_lift_joint"], 0.3);
  ASSERT_EQ(json["M"].size(), 6u);
  // M is symmetric positive: its diagonal at least
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_GT(json["M"][i][i].get<double>(), 0) << i;
    for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(json["M"][i][k], json["M"][k][i]) << i << ", " << k;
  }

  const fs::path header = dir_ / "work" / "ur5.hpp";
  const Outcome generated = eomgen("generate " + ur5 + " -o " + quote(header.string()));
  EXPECT_EQ(generated.status, 0) << generated.err;
  const std::string code = slurp(header);
  EXPECT_THAT(code, StartsWith("// Generated by eomgen"));
  EXPECT_THAT(code, HasSubstr(" from ur5.urdf."));
  EXPECT_THAT(code, HasSubstr("namespace ur5 {"));
  EXPECT_THAT(code, HasSubstr("static constexpr int nq = 6;"));
  EXPECT_THAT(code, HasSubstr("static constexpr int nu = 6;"));
}

}  // namespace
