// `eomgen simulate` as a user runs it: the CSV's columns and numbers (against an independent
// integration in this file), the plot, the build cache, a blow-up that must fail loudly
// without leaving files behind, constrained models, and malformed requests.
//
// The compiled simulations are cached in EOMGEN_TEST_CACHE_DIR (in the build tree), shared by
// the tests of this file; every key is content-based, so a stale entry is never reused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "eomrt/integrators.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::testing::Outcome;
using eomgen::testing::quote;
using eomgen::testing::slurp;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

const std::string models_dir = std::string(EOMGEN_SOURCE_DIR) + "/models/";

/// A CSV file: its header and its rows of numbers.
struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;

  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Csv read_csv(const fs::path& path) {
  Csv csv;
  std::istringstream text(slurp(path));
  std::string line;
  std::getline(text, line);
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) csv.columns.push_back(name);
  while (std::getline(text, line)) {
    std::istringstream cells(line);
    std::vector<double> row;
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    EXPECT_EQ(row.size(), csv.columns.size()) << line;
    csv.rows.push_back(row);
  }
  return csv;
}

/// theta'' = -g/l sin(theta) by classical RK4 with a tiny step: the reference the CSV must match
double pendulum_angle(double theta, double omega, double g_over_l, double t_end) {
  const int n = 200000;
  const double h = t_end / n;
  const auto f = [g_over_l](double th) { return -g_over_l * std::sin(th); };
  for (int i = 0; i < n; ++i) {
    const double k1t = omega, k1w = f(theta);
    const double k2t = omega + h / 2 * k1w, k2w = f(theta + h / 2 * k1t);
    const double k3t = omega + h / 2 * k2w, k3w = f(theta + h / 2 * k2t);
    const double k4t = omega + h * k3w, k4w = f(theta + h * k3t);
    theta += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    omega += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return theta;
}

class Simulate : public eomgen::testing::CliFixture {
 protected:
  // every run shares the test cache; arguments already quoted for the shell
  Outcome simulate(const std::string& arguments) {
    return eomgen("simulate " + arguments + " --cache-dir " + quote(EOMGEN_TEST_CACHE_DIR));
  }
  // the files in the work directory, to prove nothing half-written was left there
  std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    return names;
  }
};

// the output directory has a space and a quote in its name: paths reach the compiler, the
// simulation and gnuplot as arguments, never through a shell or unescaped into a script
TEST_F(Simulate, PendulumCsvMatchesAnIndependentIntegrationAndIsPlotted) {
  const fs::path out = dir_ / "work" / "out dir 'q'";
  fs::create_directories(out);
  const std::string csv = (out / "swing.csv").string(), svg = (out / "swing.svg").string();
  std::string args = quote(models_dir + "simple_pendulum.eom") + " --t-end 2 --init theta=1.2,theta_dot=-0.5" +
                     " --sample 0.01 --rtol 1e-10 --set l=0.8 -o ";
  // the path has a single quote: close, escape, reopen for the shell
  const auto shell = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  args += shell(csv) + " --plot " + shell(svg);
  const Outcome run = simulate(args);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("CSV:  " + csv));
  EXPECT_THAT(run.out, HasSubstr("plot: " + svg));
  EXPECT_THAT(run.out, HasSubstr("simulated simple_pendulum from t = 0 to 2 s with dp5"));

  const Csv table = read_csv(csv);
  ASSERT_GE(table.columns.size(), 6u);
  EXPECT_EQ(std::vector<std::string>(table.columns.begin(), table.columns.begin() + 6),
            (std::vector<std::string>{"t", "theta", "theta_dot", "T", "V", "T+V"}));
  ASSERT_EQ(table.rows.size(), 201u);
  EXPECT_EQ(table.rows.front()[1], 1.2);
  EXPECT_EQ(table.rows.front()[2], -0.5);
  EXPECT_EQ(table.rows.back()[0], 2.0);
  EXPECT_NEAR(table.rows.back()[1], pendulum_angle(1.2, -0.5, 9.81 / 0.8, 2.0), 1e-8);
  const std::size_t e = table.column("T+V");
  for (const auto& row : table.rows) EXPECT_NEAR(row[e], table.rows.front()[e], 1e-8 * std::abs(table.rows.front()[e]));

  const std::string image = slurp(svg);
  EXPECT_THAT(image, HasSubstr("<svg"));
  EXPECT_THAT(image, HasSubstr("theta"));  // the legend names the coordinate
  EXPECT_THAT(files_in(out), ::testing::UnorderedElementsAre("swing.csv", "swing.svg"));
}

TEST_F(Simulate, SecondRunReusesTheCompiledSimulation) {
  const std::string model = quote(models_dir + "simple_pendulum.eom");
  const std::string out = " -o " + quote((dir_ / "work" / "a.csv").string()) + " --no-plot";
  const Outcome first = simulate(model + " --t-end 0.5 --init theta=0.3 --method rk4 --dt 0.02" + out);
  ASSERT_EQ(first.status, 0) << first.err;
  // parameters, initial state and step are arguments of the program, not part of its build (the
  // method is: the program holds only the one it runs)
  const Outcome second = simulate(model + " --t-end 1 --init theta=0.1 --set g=3.7 --method rk4 --dt 0.01" + out);
  ASSERT_EQ(second.status, 0) << second.err;
  EXPECT_THAT(second.err, HasSubstr("using the cached build"));
  EXPECT_THAT(second.err, Not(HasSubstr("compiling")));
  const Csv table = read_csv(dir_ / "work" / "a.csv");
  EXPECT_EQ(table.rows.size(), 101u);  // 1 s at the default ~1000 rows, rounded to whole 10 ms steps
  EXPECT_NEAR(table.rows.back()[1], pendulum_angle(0.1, 0.0, 3.7 / 0.5, 1.0), 1e-8);  // rk4, h = 10 ms
}

// every method of the integrator registry is accepted by name, reaches the simulation program
// and is named in its summary; the fixed-step ones take a step, the adaptive ones tolerances
TEST_F(Simulate, EveryRegisteredMethodRunsByItsName) {
  const std::string model = quote(models_dir + "simple_pendulum.eom") + " --t-end 0.5 --init theta=0.3 --no-plot -o " +
                            quote((dir_ / "work" / "m.csv").string());
  for (const eomrt::IntegratorInfo& info : eomrt::integrators) {
    SCOPED_TRACE(info.name);
    const Outcome run = simulate(model + " --method " + info.name + (info.adaptive ? " --rtol 1e-9" : " --dt 0.001"));
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_THAT(run.out, HasSubstr(std::string("with ") + info.name + (info.adaptive ? " (rtol 1e-09" : " (dt 0.001)")));
    const Csv table = read_csv(dir_ / "work" / "m.csv");
    EXPECT_EQ(table.rows.back()[0], 0.5);
    // theta'' = -g/l sin(theta): every method near the reference, Euler within its O(h)
    EXPECT_NEAR(table.rows.back()[1], pendulum_angle(0.3, 0.0, 9.81 / 0.5, 0.5), info.order == 1 ? 1e-2 : 1e-7);
  }
}

// the same request writes the same bytes in every process (numbers included)
TEST_F(Simulate, SameRequestWritesIdenticalCsvBytesInThreeProcesses) {
  const std::string model = quote(models_dir + "cart_pole.eom") + " --t-end 2 --init theta=3,x_dot=0.4 --no-plot";
  std::string first;
  for (int run = 1; run <= 3; ++run) {
    const fs::path csv = dir_ / "work" / ("run" + std::to_string(run) + ".csv");
    const Outcome o = simulate(model + " -o " + quote(csv.string()));
    ASSERT_EQ(o.status, 0) << o.err;
    if (run == 1) {
      first = slurp(csv);
      EXPECT_GT(read_csv(csv).rows.size(), 100u);
    } else {
      EXPECT_EQ(slurp(csv), first) << "run " << run;
    }
  }
}

TEST_F(Simulate, ChangedModelIsCompiledAgain) {
  std::string text = slurp(models_dir + "simple_pendulum.eom");
  const std::string from = "parameter l = 0.5", to = "parameter l = 0.25";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), to);
  // the unique value keeps this model's key away from every other test's cache entry
  text.replace(text.find("parameter m = 1.0"), 17, "parameter m = 1.23456789");
  const std::string path = model("pendulum.eom", text);
  const std::string out = " -o " + quote((dir_ / "work" / "b.csv").string()) + " --no-plot --t-end 0.1";
  const Outcome first = simulate(quote(path) + out);
  ASSERT_EQ(first.status, 0) << first.err;
  const Outcome again = simulate(quote(path) + out);
  EXPECT_THAT(again.err, HasSubstr("using the cached build"));
}

// the position x^2 a.1 makes M = 4 m x^2, singular at x = 0, which the mass reaches at
// t = sqrt(2 / g) = 0.4515 s falling from x = 1 (s = x^2 = 1 - g t^2 / 2, x_dot -> infinity)
TEST_F(Simulate, BlowUpIsALoudErrorWithTheTimeAndLeavesNoFiles) {
  const std::string path = model("squashed.eom", R"(model squashed "a coordinate that stops being one at x = 0"
parameter m = 1.0 [kg]
parameter g = 9.81 [m/s^2]
coordinate x
point p = w + x^2*a.1
particle bob(mass = m, at = p)
gravity = -g*a.1
)");
  for (const char* method : {"dp5", "rk4"}) {
    SCOPED_TRACE(method);
    const Outcome run = simulate(quote(path) + " --t-end 2 --init x=1 --method " + method + " -o " +
                                 quote((dir_ / "work" / "s.csv").string()) + " --plot " +
                                 quote((dir_ / "work" / "s.png").string()));
    EXPECT_EQ(run.status, 1);
    // dp5's step underflows at the singularity; rk4's fixed steps carry the state past it until
    // it overflows a few steps later
    EXPECT_THAT(run.err, ::testing::ContainsRegex("error: the simulation stopped at t = 0\\.4[5-9]"));
    EXPECT_THAT(run.err, HasSubstr("last good state"));
    EXPECT_THAT(run.err, HasSubstr("x_dot = "));
    EXPECT_THAT(run.err, HasSubstr("no CSV or plot was written"));
    EXPECT_THAT(run.err, Not(HasSubstr("nan")));
    EXPECT_THAT(files_in(dir_ / "work"), ::testing::ElementsAre("squashed.eom"));
  }
}

TEST_F(Simulate, CartesianPendulumReportsMultipliersAndResidualsWithEitherSolver) {
  for (const char* solver : {"kkt", "null-space"}) {
    SCOPED_TRACE(solver);
    const fs::path csv = dir_ / "work" / (std::string(solver) + ".csv");
    const fs::path png = dir_ / "work" / (std::string(solver) + ".png");
    const Outcome run = simulate(quote(models_dir + "cartesian_pendulum.eom") +
                                 " --t-end 3 --init x=0.3,y=-0.4 --solver " + solver + " -o " + quote(csv.string()) +
                                 " --plot " + quote(png.string()));
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_THAT(run.out, HasSubstr("constraint residuals"));
    const Csv table = read_csv(csv);
    const std::size_t lambda = table.column("lambda_rod_length"), phi = table.column("phi_rod_length");
    const std::size_t rate = table.column("rate_residual_rod_length"), angle = table.column("angle");
    table.column("length_error");
    for (const auto& row : table.rows) {
      EXPECT_LT(std::abs(row[phi]), 1e-12);
      EXPECT_LT(std::abs(row[rate]), 1e-12);
    }
    // released at rest: the rod tension is m g cos(angle) = -2 l lambda (the model's comment)
    const auto& start = table.rows.front();
    EXPECT_NEAR(-2 * 0.5 * start[lambda], 1.0 * 9.81 * std::cos(start[angle]), 1e-9);
    EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
  }
}

// a constrained model's program is two translation units compiled at once: the start (the
// assembly, instantiated only there) and the rest, which declares it extern; an unconstrained
// model's is one
TEST_F(Simulate, AConstrainedModelsProgramIsCompiledAsTwoUnitsAtOnce) {
  const fs::path cache = dir_ / "cache";
  const auto entry_of = [&](const std::string& stem) {
    for (const auto& e : fs::directory_iterator(cache))
      if (e.path().filename().string().rfind(stem + "-", 0) == 0) return e.path();
    return fs::path();
  };
  const Outcome constrained = eomgen("simulate " + quote(models_dir + "cartesian_pendulum.eom") +
                                     " --t-end 0.1 --init x=0.3,y=-0.4 --no-plot -o " +
                                     quote((dir_ / "c.csv").string()) + " --cache-dir " + quote(cache.string()));
  ASSERT_EQ(constrained.status, 0) << constrained.err;
  const fs::path split = entry_of("cartesian_pendulum");
  ASSERT_FALSE(split.empty());
  EXPECT_TRUE(fs::exists(split / "start.o") && fs::exists(split / "driver.o"));
  EXPECT_THAT(slurp(split / "start.cpp"),
              HasSubstr("template bool eomgen::simulation_program::assemble_start<"
                        "eomgen_models::cartesian_pendulum::Model>"));
  EXPECT_THAT(slurp(split / "driver.cpp"), HasSubstr("extern template bool eomgen::simulation_program::assemble_start<"));
  const Outcome free = eomgen("simulate " + quote(models_dir + "simple_pendulum.eom") + " --t-end 0.1 --no-plot -o " +
                              quote((dir_ / "s.csv").string()) + " --cache-dir " + quote(cache.string()));
  ASSERT_EQ(free.status, 0) << free.err;
  const fs::path whole = entry_of("simple_pendulum");
  ASSERT_FALSE(whole.empty());
  EXPECT_FALSE(fs::exists(whole / "start.cpp"));
  EXPECT_THAT(slurp(whole / "driver.cpp"), Not(HasSubstr("extern template")));
}

// gnuplot runs a data file named "<cmd" as a shell command: a CSV by that name (relative, in
// the working directory) must reach gnuplot as an absolute path and nothing may run
TEST_F(Simulate, FileNamesThatGnuplotWouldRunAreOnlyFileNames) {
  const fs::path work = dir_ / "work";
  const std::string command = "cd " + quote(work.string()) + " && " + quote(EOMGEN_EXE) + " simulate " +
                              quote(models_dir + "simple_pendulum.eom") +
                              " --t-end 0.1 -o '<touch pwned;.csv' --plot '|touch pwned2;.svg' --cache-dir " +
                              quote(EOMGEN_TEST_CACHE_DIR) + " > /dev/null 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0);
  EXPECT_FALSE(fs::exists(work / "pwned"));
  EXPECT_FALSE(fs::exists(work / "pwned2"));
  EXPECT_TRUE(fs::exists(work / "<touch pwned;.csv"));
  EXPECT_TRUE(fs::exists(work / "|touch pwned2;.svg"));
}

// the CSV is complete when the plot fails (here a gnuplot that refuses): it is kept, the message
// says so and why, the status is 3 (only the plot is missing), and no temporary file remains
TEST_F(Simulate, APlotThatFailsAfterTheCsvKeepsTheCsvAndSaysSo) {
  const fs::path work = dir_ / "work", bin = dir_ / "bin";
  const std::string request = quote(models_dir + "simple_pendulum.eom") + " --t-end 0.5 --init theta=0.4 -o ";
  const Outcome reference = simulate(request + quote((work / "reference.csv").string()) + " --no-plot");
  ASSERT_EQ(reference.status, 0) << reference.err;

  fs::create_directories(bin);
  std::ofstream(bin / "gnuplot") << "#!/bin/sh\necho 'gnuplot: cannot do it, on purpose' >&2\nexit 1\n";
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  const std::string path = std::getenv("PATH");
  ::setenv("PATH", (bin.string() + ":" + path).c_str(), 1);
  const Outcome run = simulate(request + quote((work / "run.csv").string()) + " --plot " + quote((work / "run.svg").string()));
  ::setenv("PATH", path.c_str(), 1);

  EXPECT_EQ(run.status, 3);
  EXPECT_THAT(run.out, HasSubstr("CSV:  " + (work / "run.csv").string() + "\n"));
  EXPECT_THAT(run.out, Not(HasSubstr("plot:")));
  EXPECT_THAT(run.err, ::testing::EndsWith("eomgen: error: the plot '" + (work / "run.svg").string() +
                                           "' was not written (the CSV '" + (work / "run.csv").string() +
                                           "' is complete and kept): gnuplot failed (exit status 1):\n"
                                           "gnuplot: cannot do it, on purpose\n\n"));
  EXPECT_EQ(slurp(work / "run.csv"), slurp(work / "reference.csv"));
  EXPECT_THAT(files_in(work), ::testing::UnorderedElementsAre("reference.csv", "run.csv"));
}

// all coordinates 0 put the Cartesian pendulum's bob on the pivot, where its rod constraint has
// no gradient: no start near there exists, and the error names the constraint and the option
TEST_F(Simulate, InitialStateOffTheConstraintsIsExplained) {
  const Outcome run = simulate(quote(models_dir + "cartesian_pendulum.eom") + " --t-end 1 --no-plot -o " +
                               quote((dir_ / "work" / "c.csv").string()));
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.err, HasSubstr("no start near the request satisfies the constraint 'rod_length'"));
  EXPECT_THAT(run.err, HasSubstr("phi = -0.25"));
  EXPECT_THAT(run.err, HasSubstr("--init"));
  EXPECT_THAT(files_in(dir_ / "work"), ::testing::IsEmpty());
}

// the four-bar given its crank angle and rate starts there, on the closure nearest the guess,
// and says what it solved; given rates that contradict the loop move, and it says by how much
TEST_F(Simulate, AFourBarStartsAtTheGivenCrankAngleAndSaysWhatItSolved) {
  const std::string four_bar = quote(std::string(EOMGEN_SOURCE_DIR) + "/tests/cli/models/four_bar.eom");
  const fs::path csv = dir_ / "work" / "fb.csv";
  const Outcome run = simulate(four_bar + " --t-end 0.01 --no-plot --init q1=0.5,q1_dot=1 --guess q2=-1,q3=-2 -o " +
                               quote(csv.string()));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("note: the start was brought onto the constraints"));
  EXPECT_THAT(run.err, HasSubstr("  q2 = -1.0510571925373"));
  EXPECT_THAT(run.err, Not(HasSubstr("  q1 = ")));  // given, kept
  const Csv table = read_csv(csv);
  const auto& start = table.rows.front();
  // kept, but for the rounding of the runtime's projection at the first sample
  EXPECT_NEAR(start[table.column("q1")], 0.5, 1e-13);
  EXPECT_NEAR(start[table.column("q1_dot")], 1.0, 1e-13);
  EXPECT_NEAR(start[table.column("q3")], -2.009857, 1e-6);

  const Outcome moved = simulate(four_bar + " --t-end 0.01 --no-plot --init q1=0.5,q2=0.71059732708969514,"
                                 "q3=1.6693970778594451,q1_dot=1,q2_dot=0,q3_dot=0 -o " + quote(csv.string()));
  ASSERT_EQ(moved.status, 0) << moved.err;
  EXPECT_THAT(moved.err, HasSubstr("the given rates admit no consistent start: they moved too"));
  EXPECT_THAT(moved.err, HasSubstr("q2_dot = "));
}

TEST_F(Simulate, MalformedRequestsAreUsageErrorsBeforeAnythingIsBuilt) {
  const std::string model = quote(models_dir + "simple_pendulum.eom") + " --no-plot";
  const struct {
    std::string args, message;
  } cases[] = {
      {" --t-end 1 --set mass=2", "'mass' is not a parameter of simple_pendulum; its parameters: m, l, g"},
      {" --t-end 1 --set theta=1",
       "--set: 'theta' is a coordinate of simple_pendulum, not a parameter: give its value with --init theta=VALUE"},
      {" --t-end 1 --set theta_dot=1",
       "--set: 'theta_dot' is a rate of simple_pendulum, not a parameter: give its value with --init theta_dot=VALUE"},
      {" --t-end 1 --set t=1",
       "--set: 't' is the time, not a parameter: the run starts at t = 0 and ends at --t-end"},
      {" --t-end 1 --init phi=1", "'phi' is not a coordinate or rate of simple_pendulum; expected one of theta or theta_dot"},
      {" --t-end 1 --input u=1", "'u' is not an input of simple_pendulum; its inputs: none"},
      {" --t-end 1 --method dp5 --dt 0.01", "dp5 chooses its own steps"},
      {" --t-end 1 --method rk4 --rtol 1e-6", "rk4 takes fixed steps"},
      {" --t-end 1 --set g=abc", "is not a finite number"},
      {" --t-end -1", "--t-end"},
      {"", "--t-end is required"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const Outcome run = simulate(model + c.args);
    EXPECT_EQ(run.status, 2);
    EXPECT_THAT(run.err, HasSubstr(c.message));
    EXPECT_THAT(run.err, Not(HasSubstr("compiling")));
  }
  const Outcome pdf = simulate(quote(models_dir + "simple_pendulum.eom") + " --t-end 1 --plot x.pdf");
  EXPECT_EQ(pdf.status, 2);
  EXPECT_THAT(pdf.err, HasSubstr("expected a .svg or .png file"));
  EXPECT_THAT(files_in(dir_ / "work"), ::testing::IsEmpty());
}

}  // namespace
