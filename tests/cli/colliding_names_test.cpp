// A model named with every name that once broke generated code (tests/cli/models/
// colliding_names.eom: names the old mangling merged, the generated struct's members and
// locals, macros of the C, POSIX and Eigen headers, keywords, look-alikes of escapes): its
// header compiles under -Wall -Wextra -Werror -pedantic with -std=c++17 and -std=gnu++17 after
// the headers that define those macros, gives eomgen eval's numbers with its parameters set by
// their fields' documented names, and `eomgen simulate` compiles and runs it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "eomgen_build_config.hpp"  // the compiler eomgen simulate uses (build/generator/cli/)

namespace {

namespace fs = std::filesystem;
using eomgen::testing::Outcome;
using eomgen::testing::quote;
using eomgen::testing::slurp;

const std::string fixture = std::string(EOMGEN_SOURCE_DIR) + "/tests/cli/models/colliding_names.eom";

// The state of every comparison, as eomgen's --at.
const char* const state = "errno=0.3,__theta=0.4,errno_dot=-0.2,__theta_dot=0.5,stdin=1.5,_u_=-0.7";

// Includes the headers whose macros once broke the header first, sets the parameters of the
// issue by their fields' names (docs/model-language.md, "Names in generated code") and the
// others through fields(), and prints every parameter as NAME=VALUE, then M, F, T, V, the
// outputs and the forward dynamics' qdd at `state`.
const char* const program = R"(#include <cassert>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

#include "model.hpp"

int main() {
  using Model = eomgen_models::NULL_::Model;
  Model::Parameters<double> p;
  p.x_1_y_ = 0.80;  // x__y
  p.x_y = 0.85;
  p.v_0_x_ = 0.90;  // _x
  p.v_x = 0.95;
  p.x_1_ = 1.00;    // x_
  p.x_1_1_ = 1.05;  // x__
  p.fields_ = 1.10;
  p.np_ = 1.15;
  p.EOF_ = 1.20;
  p.NULL_ = 1.25;
  p.INFINITY_ = 1.30;
  p.NAN_ = 1.35;
  p.M_PI_ = 1.40;
  p.INT_MAX_ = 1.45;
  p.SIZE_MAX_ = 1.50;
  p.EDOM_ = 1.55;
  p.RAND_MAX_ = 1.60;
  p.linux_ = 1.65;
  p.unix_ = 1.70;
  const auto fields = p.fields();
  for (std::size_t i = 19; i < fields.size(); ++i) *fields[i] = 1 + 0.001 * static_cast<double>(i);
  for (std::size_t i = 0; i < fields.size(); ++i) std::printf("%s=%.17g\n", Model::parameter_names[i], *fields[i]);

  Model::Vector<double> q, qd, F, qdd;
  Model::Inputs<double> u;
  q << 0.3, 0.4;
  qd << -0.2, 0.5;
  u << 1.5, -0.7;
  Model::MassMatrix<double> M;
  Model::OutputVector<double> y;
  const Model::Constants<double> c(p);
  Model::mass_matrix_and_forcing(0.0, q, qd, u, c, M, F);
  Model::outputs(0.0, q, qd, u, c, y);
  const bool regular = Model::forward_dynamics(0.0, q, qd, u, c, qdd);
  std::printf("M %.17g %.17g %.17g %.17g\n", M(0, 0), M(0, 1), M(1, 0), M(1, 1));
  std::printf("F %.17g %.17g\n", F(0), F(1));
  std::printf("T %.17g\nV %.17g\n", Model::kinetic_energy(0.0, q, qd, c), Model::potential_energy(0.0, q, c));
  std::printf("y %.17g %.17g %.17g %.17g\n", y(0), y(1), y(2), y(3));
  std::printf("qdd %.17g %.17g %d\n", qdd(0), qdd(1), regular ? 1 : 0);
}
)";

void expect_close(double actual, double expected, const std::string& what) {
  EXPECT_NEAR(actual, expected, 1e-12 * (1 + std::abs(expected))) << what;
}

class CollidingNames : public eomgen::testing::CliFixture {
 protected:
  // runs `command` (quoted for the shell), its output into the test's directory
  Outcome shell(const std::string& command) {
    const fs::path out = dir_ / "shell.out";
    const int raw = std::system((command + " > " + quote(out.string()) + " 2>&1").c_str());
    return Outcome{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), ""};
  }
};

TEST_F(CollidingNames, HeaderCompilesStrictlyUnderBothStandardsAndGivesEvalsNumbers) {
  const fs::path header = dir_ / "model.hpp", source = dir_ / "program.cpp";
  const Outcome generated = eomgen("generate " + quote(fixture) + " -o " + quote(header.string()));
  ASSERT_EQ(generated.status, 0) << generated.err;
  std::ofstream(source) << program;
  namespace config = eomgen::tools::build_config;
  for (const std::string standard : {"c++17", "gnu++17"}) {
    SCOPED_TRACE(standard);
    const fs::path binary = dir_ / ("program_" + standard);
    const Outcome compiled =
        shell(quote(config::cxx_compiler) + " -std=" + standard + " -Wall -Wextra -Werror -pedantic -I" +
              quote(config::eigen_include_dir) + " " + quote(source.string()) + " -o " + quote(binary.string()));
    ASSERT_EQ(compiled.status, 0) << compiled.out;
    const Outcome run = shell(quote(binary.string()));
    ASSERT_EQ(run.status, 0) << run.out;

    // the parameters as the program set them, given to eval by their names in the model
    std::istringstream lines(run.out);
    std::string set, line;
    std::map<std::string, std::vector<double>> printed;
    while (std::getline(lines, line)) {
      const std::size_t equals = line.find('=');
      if (equals != std::string::npos) {
        set += " --set " + quote(line);
        continue;
      }
      std::istringstream words(line);
      std::string key;
      words >> key;
      for (double v; words >> v;) printed[key].push_back(v);
    }
    EXPECT_NE(set.find("--set 'x__y=0.80000000000000004'"), std::string::npos);
    EXPECT_NE(set.find("--set 'unix=1.7'"), std::string::npos);
    const Outcome eval = eomgen("eval " + quote(fixture) + " --at " + state + set + " -f json");
    ASSERT_EQ(eval.status, 0) << eval.err;
    const nlohmann::json j = nlohmann::json::parse(eval.out);
    ASSERT_EQ(j["parameters"].size(), 201u);
    ASSERT_EQ(printed["M"].size(), 4u);
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) expect_close(printed["M"][2 * r + c], j["M"][r][c], "M");
    for (int r = 0; r < 2; ++r) expect_close(printed["F"].at(r), j["F"][r], "F");
    expect_close(printed["T"].at(0), j["T"], "T");
    expect_close(printed["V"].at(0), j["V"], "V");
    const char* outputs[] = {"stdout", "assert_1", "assert_2", "assert_3"};
    for (int k = 0; k < 4; ++k) expect_close(printed["y"].at(k), j["outputs"][outputs[k]], outputs[k]);
    for (int r = 0; r < 2; ++r) expect_close(printed["qdd"].at(r), j["qdd"][r], "qdd");
    EXPECT_EQ(printed["qdd"].at(2), 1);
    // every parameter moves a number: the potential holds those the physics does not use
    EXPECT_GT(std::abs(printed["V"].at(0)), 1.0);
  }
}

TEST_F(CollidingNames, SimulateCompilesTheSimulationProgramAndSetsParametersByTheirNames) {
  if (!EOMGEN_SIMULATION_TESTS) GTEST_SKIP() << "EOMGEN_SIMULATION_TESTS is off";
  const std::string set = "x__y=1.7,_x=0.8,linux=0.3,EOF=2.5,np=0.9,int=1.5,w0=0.25";
  const fs::path csv = dir_ / "run.csv";
  const Outcome run = eomgen("simulate " + quote(fixture) +
                             " --t-end 0.001 --dt 1e-4 --method rk4 --no-plot --init errno=0.3,__theta=0.4,"
                             "errno_dot=-0.2,__theta_dot=0.5 --input stdin=1.5,_u_=-0.7 --set " +
                             set + " -o " + quote(csv.string()) + " --cache-dir " + quote(EOMGEN_TEST_CACHE_DIR));
  ASSERT_EQ(run.status, 0) << run.err;
  const Outcome eval = eomgen("eval " + quote(fixture) + " --at " + state + " --set " + set + " -f json");
  ASSERT_EQ(eval.status, 0) << eval.err;
  const nlohmann::json j = nlohmann::json::parse(eval.out);

  std::istringstream text(slurp(csv));
  std::string header, first, last;
  std::getline(text, header);
  std::getline(text, first);
  for (std::string line; std::getline(text, line);) last = line;
  EXPECT_EQ(header, "t,errno,__theta,errno_dot,__theta_dot,stdin,_u_,T,V,T+V,stdout,assert_1,assert_2,assert_3");
  auto cells = [](const std::string& row) {
    std::vector<double> out;
    std::istringstream in(row);
    for (std::string cell; std::getline(in, cell, ',');) out.push_back(std::stod(cell));
    return out;
  };
  const std::vector<double> start = cells(first), end = cells(last);
  ASSERT_EQ(start.size(), 14u);
  ASSERT_EQ(end.size(), 14u);
  expect_close(start[7], j["T"], "T");
  expect_close(start[8], j["V"], "V");
  expect_close(start[10], j["outputs"]["stdout"], "stdout");
  // after 1 ms the rates have moved by qdd dt, to first order
  EXPECT_DOUBLE_EQ(end[0], 0.001);
  for (int k = 0; k < 2; ++k) {
    const double qdd = j["qdd"][k], rate_change = end[3 + k] - start[3 + k];
    EXPECT_NEAR(rate_change, qdd * 0.001, 0.01 * std::abs(qdd * 0.001)) << k;
  }
}

}  // namespace
