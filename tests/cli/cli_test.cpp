// Runs the built eomgen program (EOMGEN_EXE) on model files written to a temporary directory and
// checks what a user sees: exit status, standard output and standard error, files written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli/cli_runner.hpp"
#include "eomrt/integrators.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;
using ::testing::StartsWith;

const char* const double_pendulum = R"(# two point masses on massless rods, relative angles
model double_pendulum "Planar double pendulum"
parameter m1 = 1.0 [kg]
parameter m2 = 1.0 [kg]
parameter l1 = 1.0 [m]
parameter l2 = 1.0 [m]
parameter g = 9.81 [m/s^2]
coordinate q1, q2
frame b = rotate(a, 3, q1)
frame c = rotate(b, 3, q2)
point p1 = w + l1*b.1
point p2 = p1 + l2*c.1
particle bob1(mass = m1, at = p1)
particle bob2(mass = m2, at = p2)
gravity = g*a.1
output tip = position(p2)
)";

// a.1 down, as in the double pendulum; the rod is a holonomic constraint
const char* const cartesian_pendulum = R"(model cartesian_pendulum "Point mass on a rod"
parameter m = 2.0 [kg]
parameter l = 1.5 [m]
parameter g = 9.81 [m/s^2]
coordinate x, y
point p = w + [x, y, 0] in a
particle bob(mass = m, at = p)
gravity = g*a.1
constraint rod: x^2 + y^2 = l^2
)";

const char* const chain = R"(model chain "n uniform rods pinned end to end"
const n = 2
parameter m = 1.0 [kg]
parameter l = 0.5 [m]
parameter g = 9.81 [m/s^2]
gravity = g*a.1
frame b0 = a
point o0 = w
for i in 1..n
  coordinate q{i}
  frame b{i} = rotate(b{i-1}, 3, q{i})
  point c{i} = o{i-1} + l/2*b{i}.1
  point o{i} = o{i-1} + l*b{i}.1
  body rod{i}(mass = m, centre = c{i}, frame = b{i}, inertia = diag(m*l^2/1200, m*l^2/12, m*l^2/12))
end
)";

// line 4, column 18 names an undeclared 'mm'
const char* const misspelt = R"(parameter m = 1.0 [kg]
coordinate x
point p = w + x*a.1
particle bob(mass = mm, at = p)
)";

using eomgen::testing::Outcome;
using eomgen::testing::quote;
using eomgen::testing::slurp;
using Cli = eomgen::testing::CliFixture;

TEST_F(Cli, VersionAndHelp) {
  const Outcome version = eomgen("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.out, "eomgen 0.1.0\n");
  const Outcome help = eomgen("--help");
  EXPECT_EQ(help.status, 0);
  for (const char* word : {"check", "derive", "eval", "--version"}) EXPECT_THAT(help.out, HasSubstr(word));
  const Outcome derive = eomgen("derive --help");
  EXPECT_EQ(derive.status, 0);
  for (const char* word : {"MODEL", "--format", "--only", "--intermediates", "--output", "--define"})
    EXPECT_THAT(derive.out, HasSubstr(word));
  const Outcome eval = eomgen("eval --help");
  EXPECT_EQ(eval.status, 0);
  for (const char* word : {"--at", "--set", "--format", "--define"}) EXPECT_THAT(eval.out, HasSubstr(word));
  EXPECT_EQ(eomgen("check --help").status, 0);
  EXPECT_TRUE(eomgen("--help").err.empty());
}

// `simulate --method` offers the integrator registry: every row, its description, and the
// fixed-step and adaptive names in the help of the options that belong to each kind
TEST_F(Cli, SimulateHelpListsTheRegisteredIntegrators) {
  const Outcome help = eomgen("simulate --help");
  ASSERT_EQ(help.status, 0) << help.err;
  std::string names, fixed_step, adaptive;
  for (const eomrt::IntegratorInfo& info : eomrt::integrators) {
    SCOPED_TRACE(info.name);
    // a line of its own: the name, then its description
    const std::string name = info.name, description = info.description;
    std::istringstream lines(help.out);
    bool listed = false;
    for (std::string line; std::getline(lines, line);) {
      const std::string text = line.substr(std::min(line.find_first_not_of(' '), line.size()));
      listed = listed || (text.rfind(name + " ", 0) == 0 && text.size() > description.size() &&
                          text.compare(text.size() - description.size(), description.size(), description) == 0);
    }
    EXPECT_TRUE(listed);
    names += (names.empty() ? "" : ",") + name;
    std::string& kind = info.adaptive ? adaptive : fixed_step;
    kind += (kind.empty() ? "" : "/") + name;
  }
  EXPECT_THAT(help.out, HasSubstr("--method TEXT:{" + names + "}"));
  EXPECT_THAT(help.out, HasSubstr("Step of " + fixed_step + " [s]"));
  EXPECT_THAT(help.out, HasSubstr("Relative tolerance of " + adaptive + " "));
  EXPECT_THAT(help.out, HasSubstr(std::string("default: ") + eomrt::to_string(eomrt::default_integrator) + ", or " +
                                  eomrt::to_string(eomrt::default_fixed_step_integrator) + " when --dt is given"));
}

// a name outside the registry is refused by the command line, with the choices
TEST_F(Cli, SimulateRefusesAnUnregisteredMethod) {
  const Outcome run = eomgen("simulate " + quote(model("dp.eom", double_pendulum)) + " --t-end 1 --method rk45");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "eomgen: error: --method: rk45 not in {euler,rk4,dp5}\nRun with --help for more information.\n");
}

// nan and inf parse as numbers: they must still be refused before anything is compiled
TEST_F(Cli, SimulateRefusesTimesStepsAndTolerancesThatAreNotFinitePositiveNumbers) {
  const std::string dp = quote(model("dp.eom", double_pendulum));
  for (const std::string option : {"--t-end", "--dt", "--rtol", "--atol", "--sample"})
    for (const std::string value : {"nan", "inf", "-inf", "0", "-1", "1e400", "x"}) {
      const std::string t_end = option == "--t-end" ? "" : " --t-end 1";
      const Outcome run = eomgen("simulate " + dp + t_end + " " + option + " " + value + " --no-plot");
      EXPECT_EQ(run.status, 2) << option << " " << value;
      EXPECT_THAT(run.err, StartsWith("eomgen: error: " + option + ": expected a ")) << run.err;
      EXPECT_THAT(run.err, Not(HasSubstr("compiling")));
    }
}

TEST_F(Cli, GenerateRefusesANamespaceThatIsNoPlainIdentifier) {
  const std::string dp = quote(model("dp.eom", double_pendulum));
  for (const std::string name : {"a::b", "my-models", "int", "NULL", "_x", "x__y", "Eigen", "2d", "''"}) {
    const fs::path header = dir_ / "dp.hpp";
    const Outcome run = eomgen("generate " + dp + " --namespace " + name + " -o " + quote(header.string()));
    EXPECT_EQ(run.status, 2) << name;
    EXPECT_THAT(run.err, StartsWith("eomgen: error: --namespace: expected a C++ identifier")) << run.err;
    EXPECT_FALSE(fs::exists(header));
  }
  const Outcome run = eomgen("generate " + dp + " --namespace my_models");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("namespace my_models {"));
}

// every other number of the command line: NAME=VALUE lists and a sweep's range refuse nan, inf
// and values beyond a double with status 2, naming the option and the value, before any work
TEST_F(Cli, EveryNumberOfTheCommandLineIsFiniteOrRefusedBeforeAnyWork) {
  const std::string dp = quote(model("dp.eom", double_pendulum));
  const std::pair<std::string, std::string> requests[] = {
      {"eval " + dp + " --at q1=", "--at"},          {"eval " + dp + " --set g=", "--set"},
      {"linearize " + dp + " --at q1=", "--at"},     {"linearize " + dp + " --set l=", "--set"},
      {"simulate " + dp + " --t-end 1 --no-plot --init q1_dot=", "--init"},
      {"simulate " + dp + " --t-end 1 --no-plot --input u=", "--input"},
      {"simulate " + dp + " --t-end 1 --no-plot --set m=", "--set"},
      {"check " + dp + " -D n=", "--define"},         {"derive " + dp + " --define n=", "--define"},
  };
  for (const auto& [request, option] : requests)
    for (const std::string value : {"nan", "-nan", "NaN", "inf", "-inf", "infinity", "1e400", "-1e400", "1e-400"}) {
      SCOPED_TRACE(request + value);
      const Outcome run = eomgen(request + value);
      EXPECT_EQ(run.status, 2);
      const std::string item = request.substr(request.rfind(' ') + 1) + value;
      const bool range = value.find("e") != std::string::npos && value.find("n") == std::string::npos;
      EXPECT_EQ(run.err, "eomgen: error: " + option + ": '" + value + "' in '" + item + "'" +
                             (range ? " is beyond the range of a double (magnitudes from 2.2e-308 to 1.8e308, or 0)\n"
                                    : " is not a finite number\n"));
      EXPECT_EQ(run.out, "");
    }
  for (const std::string range : {"g=nan:10:1", "g=0:inf:1", "g=0:10:-nan", "g=1e400:1:1", "q1=0:1:1e-400"}) {
    const Outcome run = eomgen("linearize " + dp + " --sweep " + range);
    EXPECT_EQ(run.status, 2) << range;
    EXPECT_EQ(run.err, "eomgen: error: --sweep: expected NAME=FROM:TO:STEP with finite numbers, got '" + range + "'\n");
    EXPECT_EQ(run.out, "");
  }
}

TEST_F(Cli, CheckSummarizesTheModel) {
  const Outcome run = eomgen("check " + quote(model("dp.eom", double_pendulum)));
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("Model: double_pendulum\nDescription: Planar double pendulum\n"));
  EXPECT_THAT(run.out, HasSubstr("Coordinates (n = 2): q1, q2\n"));
  EXPECT_THAT(run.out, HasSubstr("Degrees of freedom (n - m): 2\n"));
  EXPECT_THAT(run.out, HasSubstr("Particles (2): bob1, bob2\n"));
  EXPECT_THAT(run.out, HasSubstr("  g = 9.81 [m/s^2]\n"));
  EXPECT_THAT(run.out, HasSubstr("Outputs (1): tip (3 components)\n"));
  const Outcome constrained = eomgen("check " + quote(model("cp.eom", cartesian_pendulum)));
  EXPECT_EQ(constrained.status, 0) << constrained.err;
  EXPECT_THAT(constrained.out, HasSubstr("Constraints (m = 1):\n  holonomic (1): rod\n  nonholonomic (0): none\n"));
  EXPECT_THAT(constrained.out, HasSubstr("Degrees of freedom (n - m): 1\n"));
  EXPECT_THAT(constrained.out, Not(HasSubstr("Independent speeds")));
}

TEST_F(Cli, CheckListsTheDeclaredIndependentSpeeds) {
  const std::string text = std::string(cartesian_pendulum) + "independent y\n";
  const Outcome run = eomgen("check " + quote(model("cp_independent.eom", text)));
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("Degrees of freedom (n - m): 1\nIndependent speeds (1): y_dot\n"));
}

// the rod written twice: the second is redundant, kept, with a note on standard error and the
// exit status of the rod written once
TEST_F(Cli, ARedundantConstraintIsANoteOnStandardErrorOnly) {
  const std::string once = model("once.eom", cartesian_pendulum);
  const std::string twice =
      model("twice.eom", std::string(cartesian_pendulum) + "constraint rod_again: x^2 + y^2 = l^2\n");
  const std::string note = twice +
                           ":10:12: note: constraint 'rod_again' is redundant: at a generic state its row of Xi is a "
                           "multiple of that of 'rod'; kept, the solves take independent rows at each state and give "
                           "a row they leave out the multiplier 0 (docs/conventions.md, Redundant constraints)\n";
  for (const std::string& command : {std::string("check"), std::string("derive"), std::string("eval --at x=1.5")}) {
    SCOPED_TRACE(command);
    const std::string verb = command.substr(0, command.find(' '));
    const std::string rest = command.size() > verb.size() ? command.substr(verb.size()) : "";
    const Outcome expected = eomgen(verb + " " + quote(once) + rest);
    const Outcome run = eomgen(verb + " " + quote(twice) + rest);
    ASSERT_EQ(expected.status, 0) << expected.err;
    EXPECT_TRUE(expected.err.empty()) << expected.err;
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, note);
    EXPECT_THAT(run.out, HasSubstr("rod_again"));
  }
}

TEST_F(Cli, DefineOverridesAConstant) {
  const std::string path = model("chain.eom", chain);
  EXPECT_THAT(eomgen("check " + quote(path)).out, HasSubstr("Coordinates (n = 2): q1, q2\n"));
  const Outcome run = eomgen("check " + quote(path) + " --define n=3");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("Coordinates (n = 3): q1, q2, q3\n"));
  EXPECT_THAT(run.out, HasSubstr("Bodies (3): rod1, rod2, rod3\n"));
}

TEST_F(Cli, DerivePrintsTheEquationsTheSameWayEveryRun) {
  const std::string path = model("dp.eom", double_pendulum);
  const Outcome run = eomgen("derive " + quote(path));
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("  M[1,1] = m1*l1^2 + m2*l1^2 + 2*m2*l1*l2*cos(q2) + m2*l2^2\n"));
  EXPECT_THAT(run.out, HasSubstr("  tip_1 = l1*cos(q1) + l2*cos(q1 + q2)\n"));
  // separate processes: GiNaC's own term order would change with address-space randomization
  EXPECT_EQ(eomgen("derive " + quote(path)).out, run.out);
  EXPECT_EQ(eomgen("show " + quote(path)).out, run.out);

  const Outcome only = eomgen("derive " + quote(path) + " --only M,T");
  EXPECT_THAT(only.out, HasSubstr("M[2,2] = m2*l2^2"));
  EXPECT_THAT(only.out, Not(HasSubstr("F[1]")));
  EXPECT_THAT(eomgen("derive " + quote(path) + " --intermediates").out, HasSubstr("\nwhere ("));
  const Outcome latex = eomgen("derive " + quote(path) + " --format latex");
  EXPECT_THAT(latex.out, StartsWith("\\documentclass"));
  EXPECT_THAT(latex.out, HasSubstr("\\end{document}\n"));
  EXPECT_THAT(eomgen("derive " + quote(path) + " -f markdown").out, StartsWith("# Equations of motion: double_pendulum\n"));
}

TEST_F(Cli, OutputFileIsWrittenWholeOrNotAtAll) {
  const std::string good = model("dp.eom", double_pendulum), bad = model("bad.eom", misspelt);
  const fs::path target = dir_ / "work" / "equations.txt";
  const Outcome written = eomgen("derive " + quote(good) + " -o " + quote(target.string()));
  EXPECT_EQ(written.status, 0) << written.err;
  EXPECT_TRUE(written.out.empty());
  EXPECT_EQ(slurp(target), eomgen("derive " + quote(good)).out);

  // a failing run leaves an existing file untouched and creates none
  const Outcome failed = eomgen("derive " + quote(bad) + " -o " + quote(target.string()));
  EXPECT_EQ(failed.status, 1);
  EXPECT_EQ(slurp(target), eomgen("derive " + quote(good)).out);
  const fs::path fresh = dir_ / "work" / "never.txt";
  EXPECT_EQ(eomgen("derive " + quote(bad) + " -o " + quote(fresh.string())).status, 1);
  EXPECT_FALSE(fs::exists(fresh));
  // an unwritable target (a directory) is refused before the derivation and leaves no
  // temporary file behind
  fs::create_directories(dir_ / "work" / "adir");
  const Outcome to_directory = eomgen("derive " + quote(good) + " -o " + quote((dir_ / "work" / "adir").string()));
  EXPECT_EQ(to_directory.status, 2);
  EXPECT_EQ(to_directory.err, "eomgen: error: -o: '" + (dir_ / "work" / "adir").string() +
                                  "' is a directory; give the name of a file\n");
  for (const auto& entry : fs::directory_iterator(dir_ / "work"))
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(".tmp"))) << "left behind";
}

TEST_F(Cli, OutputThroughASymlinkOrIntoAFifoKeepsThem) {
  // renaming the finished file over the target would replace a link with a file, and a device
  // or pipe (-o /dev/null) with a regular file
  const std::string good = model("dp.eom", double_pendulum);
  const std::string expected = eomgen("derive " + quote(good)).out;
  const fs::path file = dir_ / "real.txt", link = dir_ / "link.txt";
  std::ofstream(file) << "old";
  fs::create_symlink(file, link);
  ASSERT_EQ(eomgen("derive " + quote(good) + " -o " + quote(link.string())).status, 0);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(slurp(file), expected);

  // the read end opened first (non-blocking), so eomgen's open for writing succeeds and its few
  // kilobytes fit the pipe's buffer: no thread, and no hang if the pipe were replaced
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int read_end = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(read_end, 0);
  const Outcome piped = eomgen("derive " + quote(good) + " -o " + quote(fifo.string()));
  std::string received;
  char buffer[4096];
  for (ssize_t n; (n = ::read(read_end, buffer, sizeof buffer)) > 0;) received.append(buffer, static_cast<std::size_t>(n));
  ::close(read_end);
  EXPECT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(received, expected);
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
}

TEST_F(Cli, ModelErrorsExitOneWithFileLineColumn) {
  const std::string path = model("bad.eom", misspelt);
  const Outcome run = eomgen("derive " + quote(path));
  EXPECT_EQ(run.status, 1);
  EXPECT_TRUE(run.out.empty());
  EXPECT_THAT(run.err, StartsWith(path + ":4:"));
  EXPECT_THAT(run.err, MatchesRegex(".*bad\\.eom:4:[0-9]+: error: .*'mm'.*\n"));
  EXPECT_EQ(eomgen("check " + quote(path)).status, 1);
  EXPECT_EQ(eomgen("eval " + quote(path)).status, 1);
}

TEST_F(Cli, UsageErrorsExitTwo) {
  const std::string path = model("dp.eom", double_pendulum);
  for (const std::string& arguments :
       {std::string(""), std::string("frobnicate"), std::string("derive"), "derive " + quote(path) + " --format pdf",
        "derive " + quote(path) + " --only M,Q", "derive " + quote(path) + " --intermediates --expand",
        "eval " + quote(path) + " --at q1", "eval " + quote(path) + " --at q1=abc",
        "eval " + quote(path) + " --at q1=1,q1=2", "eval " + quote(path) + " --set g", "eval " + quote(path) + " -f latex",
        "check " + quote(path) + " --define n", "check " + quote((dir_ / "missing.eom").string()),
        "check " + quote(path) + " --unknown-flag"}) {
    const Outcome run = eomgen(arguments);
    EXPECT_EQ(run.status, 2) << arguments << "\n" << run.err;
    EXPECT_THAT(run.err, StartsWith("eomgen: error: ")) << arguments;
    EXPECT_TRUE(run.out.empty()) << arguments;
  }
}

TEST_F(Cli, EvalJsonIsParseableAndSolvesTheKktSystem) {
  const double m = 2.0, l = 1.5, g = 9.8, theta = 0.6, omega = -0.9;
  const double x = l * std::cos(theta), y = l * std::sin(theta);
  const double xd = -l * std::sin(theta) * omega, yd = l * std::cos(theta) * omega;
  char at[256];
  std::snprintf(at, sizeof at, "x=%.17g,y=%.17g,x_dot=%.17g,y_dot=%.17g", x, y, xd, yd);
  const Outcome run = eomgen("eval " + quote(model("cp.eom", cartesian_pendulum)) + " --at " + at + " --set g=9.8 --format json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["coordinates"], nlohmann::json({"x", "y"}));
  EXPECT_EQ(j["constraints"], nlohmann::json({"rod"}));
  for (const char* key : {"M", "F", "Xi", "Xi_t", "b", "T", "V", "qdd", "lambda", "outputs"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["M"], nlohmann::json({{m, 0.0}, {0.0, m}}));
  EXPECT_EQ(j["F"], nlohmann::json({m * g, 0.0}));
  EXPECT_EQ(j["parameters"]["g"].get<double>(), 9.8);
  // full precision: the JSON reads back to the doubles given
  EXPECT_EQ(j["state"]["x"].get<double>(), x);
  EXPECT_EQ(j["state"]["y_dot"].get<double>(), yd);
  // lambda = -(rod tension) / (2 l); the tension is m (g cos(theta) + l omega^2)
  EXPECT_NEAR(j["lambda"][0].get<double>(), -m * (g * std::cos(theta) + l * omega * omega) / (2 * l), 1e-12);
  EXPECT_NEAR(j["Xi"][0][0].get<double>(), 2 * x, 1e-15);
  EXPECT_NEAR(j["V"].get<double>(), -m * g * x, 1e-12);
}

// the functions for controllers: printed only when named, and reported by eval with their keys
TEST_F(Cli, DeriveAndEvalShowTheFunctionsForControllers) {
  const std::string path = model("dp.eom", double_pendulum);
  const Outcome derived = eomgen("derive " + quote(path) + " --only C,g,J,regressor");
  ASSERT_EQ(derived.status, 0) << derived.err;
  for (const char* text : {"Coriolis matrix C (2 x 2)", "  C[2,2] = 0\n", "Gravity forces g = dV/dq (2 x 1)",
                           "Jacobian of output tip (3 x 2): J = dy/dq", "  J_tip[1,2] = -l2*sin(q1 + q2)\n",
                           "Bias of output tip", "Regressor Y (2 x 20)", "bob2.m"})
    EXPECT_THAT(derived.out, HasSubstr(text));
  EXPECT_THAT(derived.out, Not(HasSubstr("M[1,1]")));
  EXPECT_THAT(eomgen("derive " + quote(path)).out, Not(HasSubstr("Coriolis")));  // only when named
  EXPECT_THAT(eomgen("derive " + quote(path) + " --only tau -f latex").out, HasSubstr("\\tau_{1} &="));

  const double q1 = 0.1, q2 = 0.2, g = 9.81;
  const Outcome run = eomgen("eval " + quote(path) + " --at q1=0.1,q2=0.2,q1_dot=0.3 -f json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  // V = -(m1 + m2) g l1 cos(q1) - m2 g l2 cos(q1 + q2), unit masses and lengths
  EXPECT_NEAR(j["G"][0].get<double>(), 2 * g * std::sin(q1) + g * std::sin(q1 + q2), 1e-12);
  EXPECT_NEAR(j["G"][1].get<double>(), g * std::sin(q1 + q2), 1e-12);
  EXPECT_EQ(j["C"].size(), 2u);
  // tip = (l1 cos(q1) + l2 cos(q1 + q2), l1 sin(q1) + l2 sin(q1 + q2), 0)
  EXPECT_NEAR(j["output_jacobians"]["tip"]["J"][1][0].get<double>(), std::cos(q1) + std::cos(q1 + q2), 1e-12);
  EXPECT_EQ(j["output_jacobians"]["tip"]["Jdot_qd"].size(), 3u);
  EXPECT_EQ(j["Y"][0].size(), 20u);
  EXPECT_EQ(j["pi"]["bob1.m"].get<double>(), 1.0);
  EXPECT_THAT(eomgen("eval " + quote(path)).out, HasSubstr("G = dV/dq"));
}

TEST_F(Cli, EvalTextAndEvaluationErrors) {
  const std::string path = model("dp.eom", double_pendulum);
  const Outcome run = eomgen("eval " + quote(path) + " --at q1=0.1,q2=0.2,q1_dot=0.3,t=0");
  EXPECT_EQ(run.status, 0) << run.err;
  for (const char* word : {"M (2 x 2):", "F (2 x 1):", "T = ", "V = ", "tip_1 = ", "q1_ddot = ", "q2_ddot = "})
    EXPECT_THAT(run.out, HasSubstr(word));
  const Outcome unknown = eomgen("eval " + quote(path) + " --at q9=1");
  EXPECT_EQ(unknown.status, 1);
  EXPECT_THAT(unknown.err, StartsWith("eomgen: error: "));
  EXPECT_THAT(unknown.err, HasSubstr("'q9'"));
  EXPECT_THAT(unknown.err, HasSubstr("q1_dot"));
  EXPECT_EQ(eomgen("eval " + quote(path) + " --set q1=1").status, 1);  // not a parameter
}

TEST_F(Cli, SetOnANameThatIsNoParameterSaysWhereItsValueGoes) {
  const auto error_of = [&](const std::string& model_file, const std::string& args) {
    const Outcome run = eomgen("eval " + quote(model_file) + " " + args);
    EXPECT_EQ(run.status, 1) << args;
    return run.err;
  };
  const std::string cart_pole = std::string(EOMGEN_SOURCE_DIR) + "/models/cart_pole.eom";
  EXPECT_EQ(error_of(cart_pole, "--set u=1"),
            "eomgen: error: --set: 'u' is an input of cart_pole, not a parameter: give its value with --at u=VALUE\n");
  EXPECT_EQ(error_of(cart_pole, "--set x=1"),
            "eomgen: error: --set: 'x' is a coordinate of cart_pole, not a parameter: give its value with --at x=VALUE\n");
  EXPECT_EQ(error_of(cart_pole, "--set t=1"),
            "eomgen: error: --set: 't' is the time, not a parameter: give it with --at t=VALUE\n");
  EXPECT_EQ(error_of(std::string(EOMGEN_SOURCE_DIR) + "/models/planar_chain.eom", "--set n=3"),
            "eomgen: error: --set: 'n' is a const of planar_chain, fixed when the model is read, not a parameter: "
            "change it with --define n=VALUE\n");
  const std::string derived = model("derived.eom",
                                    "parameter L = 2 [m]\nparameter d = L/2 [m]\nparameter m = 1 [kg]\n"
                                    "coordinate x\npoint p = w + (x + d)*a.1\nparticle bob(mass = m, at = p)\n");
  EXPECT_EQ(error_of(derived, "--set d=1"),
            "eomgen: error: --set: 'd' is defined from other parameters of derived, and follows them: expected one "
            "of those it is defined from: L\n");
  // eval reports what they come to with the parameters it was given
  const Outcome follows = eomgen("eval " + quote(derived) + " --set L=6 -f json");
  EXPECT_EQ(follows.status, 0) << follows.err;
  EXPECT_THAT(follows.out, HasSubstr("\n  \"parameters\": {\"L\":6.0,\"m\":1.0},\n  \"derived_parameters\": {\"d\":3.0},\n"));
}

TEST_F(Cli, EveryShippedModelChecksAndDerivesTheSameBytesEveryRun) {
  const fs::path models = fs::path(EOMGEN_SOURCE_DIR) / "models";
  ASSERT_TRUE(fs::exists(models)) << "no models/ directory at " << models;
  for (const auto& entry : fs::directory_iterator(models)) {
    if (entry.path().extension() != ".eom") continue;
    const std::string path = quote(entry.path().string());
    const Outcome check = eomgen("check " + path);
    EXPECT_EQ(check.status, 0) << entry.path() << "\n" << check.err;
    const Outcome derive = eomgen("derive " + path);
    EXPECT_EQ(derive.status, 0) << entry.path() << "\n" << derive.err;
    EXPECT_THAT(derive.out, HasSubstr("M[1,1] = ")) << entry.path();
    // byte-identical in another process (another address-space layout)
    EXPECT_EQ(eomgen("derive " + path).out, derive.out) << entry.path();
    const Outcome shared = eomgen("derive " + path + " --intermediates --format latex");
    EXPECT_EQ(eomgen("derive " + path + " --intermediates --format latex").out, shared.out) << entry.path();
  }
}

TEST_F(Cli, GenerateStatsPrintsOperationCountsAndTimes) {
  const std::string dp = model("dp.eom", double_pendulum);
  const Outcome stats = eomgen("generate --stats -o " + quote((dir_ / "dp.hpp").string()) + " " + quote(dp));
  ASSERT_EQ(stats.status, 0) << stats.err;
  EXPECT_THAT(stats.out, HasSubstr("mass_matrix_and_forcing"));
  EXPECT_THAT(stats.out, ::testing::ContainsRegex("time \\[ms\\]: parse [0-9.]+, derive [0-9.]+, emit [0-9.]+\n"));
  // the header itself does not depend on --stats
  EXPECT_EQ(slurp(dir_ / "dp.hpp"), eomgen("generate " + quote(dp)).out);
  // a tree has forward_dynamics among the counts; a constrained model says why it has none
  EXPECT_THAT(stats.out, ::testing::ContainsRegex("\nforward_dynamics +[0-9]+"));
  const std::string cp = model("cp.eom", cartesian_pendulum);
  const Outcome constrained = eomgen("generate --stats -o " + quote((dir_ / "cp.hpp").string()) + " " + quote(cp));
  ASSERT_EQ(constrained.status, 0) << constrained.err;
  EXPECT_THAT(constrained.out, HasSubstr("no forward_dynamics: the model has constraints\n"));
  // which derivation of M and F the header has, with the estimates of all three
  EXPECT_THAT(stats.out, ::testing::ContainsRegex("\nM and F: (local frames|inertial|composite body and Newton-Euler) "
                                                  "\\(estimated operations: local frames [0-9]+, inertial [0-9]+, "
                                                  "composite body and Newton-Euler [0-9]+\\)\n"));
  // a tree with constraints has the recursions' estimate too (its M and F are the tree's)
  EXPECT_THAT(constrained.out, ::testing::ContainsRegex("composite body and Newton-Euler [0-9]+\\)\n"));
}

// GiNaC orders terms differently between processes (a - b in one, -(b - a) in another); the
// operation estimates, and so which derivation of M and F a header gets, must not follow it.
// Before the estimate counted a value and its negation as one, the heavy top's varied by 4 and
// the universal chain of 2 links flipped between the local form and the recursions.
TEST_F(Cli, OperationEstimatesAndTheFormTheyChooseAreTheSameInEveryProcess) {
  const std::string models = std::string(EOMGEN_SOURCE_DIR) + "/models/";
  for (const std::string& arguments : {quote(models + "heavy_top.eom"), quote(models + "universal_chain.eom") + " -D n=2"}) {
    std::string first_line, first_header;
    for (int run = 0; run < 6; ++run) {
      const Outcome generated = eomgen("generate --stats " + arguments);
      ASSERT_EQ(generated.status, 0) << generated.err;
      const std::size_t at = generated.err.find("M and F: ");
      ASSERT_NE(at, std::string::npos) << generated.err;
      const std::string line = generated.err.substr(at, generated.err.find('\n', at) - at);
      if (run == 0) {
        first_line = line;
        first_header = generated.out;
      }
      EXPECT_EQ(line, first_line) << arguments << ", run " << run;
      EXPECT_TRUE(generated.out == first_header) << arguments << ", run " << run << ": another header";
    }
  }
}

TEST_F(Cli, GenerateLinearizationAddsTheFunctionsOnlyWhenAsked) {
  const std::string dp = model("dp.eom", double_pendulum), cp = model("cp.eom", cartesian_pendulum);
  const Outcome plain = eomgen("generate " + quote(dp));
  const Outcome linearized = eomgen("generate --linearization " + quote(dp));
  ASSERT_EQ(linearized.status, 0) << linearized.err;
  EXPECT_THAT(plain.out, Not(HasSubstr("linearization")));
  // only the model's terms: the solves are the runtime's (eomrt/linearization.hpp)
  EXPECT_THAT(linearized.out, HasSubstr("static void linearization_terms("));
  EXPECT_THAT(linearized.out, HasSubstr("eomrt::second_order_linearization<Model>"));
  EXPECT_THAT(linearized.out, Not(HasSubstr("static bool linearization")));
  EXPECT_EQ(eomgen("generate --linearization " + quote(dp)).out, linearized.out);  // byte-identical
  // a constrained model gets the KKT form, with the multipliers among the terms' arguments
  const Outcome constrained = eomgen("generate --linearization " + quote(cp));
  ASSERT_EQ(constrained.status, 0) << constrained.err;
  EXPECT_THAT(constrained.out, HasSubstr("const Eigen::MatrixBase<DerivedLambda>& lambda"));
  EXPECT_THAT(constrained.out, HasSubstr("static_assert(fits<std::decay_t<Out4>>(nc, nq), \"S_qd: expected nc x nq\");"));
  EXPECT_THAT(constrained.out, Not(HasSubstr("second_order_linearization")));
}

TEST_F(Cli, LinearizePrintsTheMatricesEigenvaluesAndVerdicts) {
  const std::string pendulum = quote(std::string(EOMGEN_SOURCE_DIR) + "/models/simple_pendulum.eom");
  const Outcome inverted = eomgen("linearize " + pendulum + " --at theta=3.141592653589793");
  ASSERT_EQ(inverted.status, 0) << inverted.err;
  EXPECT_THAT(inverted.out, HasSubstr("State kept: [theta, theta_dot]"));
  EXPECT_THAT(inverted.out, HasSubstr("[ 19.62  0 ]"));  // g / l = 9.81 / 0.5
  EXPECT_THAT(inverted.out, HasSubstr("Eigenvalues of A: 4.42944691807002"));
  EXPECT_THAT(inverted.out, HasSubstr("Lyapunov's indirect method (Theorem A.22): unstable"));
  const Outcome hanging = eomgen("linearize " + pendulum + " --set l=2.4525");
  ASSERT_EQ(hanging.status, 0) << hanging.err;
  EXPECT_THAT(hanging.out, HasSubstr("0 + 2i, 0 - 2i"));  // sqrt(9.81 / 2.4525) = 2
  EXPECT_THAT(hanging.out, HasSubstr("no conclusion"));
  const Outcome moving = eomgen("linearize " + pendulum + " --at theta=1");
  EXPECT_THAT(moving.out, HasSubstr("not an equilibrium"));
  EXPECT_THAT(moving.out, HasSubstr("Stability: not assessed"));
  const Outcome latex = eomgen("linearize " + pendulum + " -f latex");
  EXPECT_THAT(latex.out, HasSubstr("A = \\begin{bmatrix}\n  0 & 1 \\\\\n  -19.62 & 0\n\\end{bmatrix}"));
  EXPECT_THAT(latex.out, HasSubstr("B = \\text{(empty, 2 \\times 0)}"));  // no inputs: no rows of nothing
  const Outcome cart = eomgen("linearize " + quote(std::string(EOMGEN_SOURCE_DIR) + "/models/cart_pole.eom") +
                              " --drop-cyclic");
  EXPECT_THAT(cart.out, HasSubstr("dropped as cyclic: x"));
  const std::string cartesian = quote(std::string(EOMGEN_SOURCE_DIR) + "/models/cartesian_pendulum.eom");
  const Outcome constrained = eomgen("linearize " + cartesian + " --at y=-0.5");
  ASSERT_EQ(constrained.status, 0) << constrained.err;
  EXPECT_THAT(constrained.out, HasSubstr("State kept: [x, x_dot]"));
  EXPECT_THAT(constrained.out, HasSubstr("Determined by the constraints (not states): y, y_dot"));
  // the reduced second-order form in x: m x'' + (m g / l) x = 0 (m = 1, l = 0.5)
  EXPECT_THAT(constrained.out, HasSubstr("Second-order form M dqdd + D dqd + K dq = B_u du in x (reduced"));
  EXPECT_THAT(constrained.out, HasSubstr("K (stiffness) (1 x 1):\n  [ 19.62 ]"));
  const Outcome off = eomgen("linearize " + cartesian);  // the bob on the pivot: off the rod
  EXPECT_EQ(off.status, 1);
  EXPECT_THAT(off.err, HasSubstr("satisfies the constraint 'rod_length'"));
  EXPECT_EQ(eomgen("linearize " + pendulum + " --at nope=1").status, 1);
  const Outcome found = eomgen("linearize " + pendulum + " --at theta=2.9 --equilibrium");
  ASSERT_EQ(found.status, 0) << found.err;
  EXPECT_THAT(found.out, HasSubstr("Equilibrium found from the guess by Newton's method in "));
  EXPECT_THAT(found.out, HasSubstr("theta = 3.14159265358979"));
  EXPECT_THAT(found.out, HasSubstr("Theorem A.22): unstable"));
}

}  // namespace
