// A model whose derived parameters are named like what the generated code declares beside them
// (the Constants' member `derived`, a constant `k0`, a temporary `w0`, the argument `p`, the
// keyword `int`): its header compiles strictly, its Constants compute every derived parameter
// from the parameters, in order, and the functions give eomgen eval's numbers, also after a
// parameter they are defined from changes.
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

const char* const model_text = R"(model derived_names
parameter L = 2
parameter m = 1.5
parameter g = 9.81
parameter derived = 0.45*L
parameter k0 = derived/3 + m
parameter w0 = k0*k0 + sin(L)
parameter p = derived + w0
parameter int = p/L
coordinate theta
frame b = rotate(a, 3, theta)
point c = w + derived*b.1 + int*b.2
particle bob(mass = m + k0, at = c)
gravity = -g*a.2
output arm = p*sin(theta)
)";

// sets L through fields(), prints the derived parameters, then M, F and the output
const char* const program = R"(#include <cstdio>

#include "model.hpp"

int main() {
  using Model = eomgen_models::derived_names::Model;
  Model::Parameters<double> parameters;
  *parameters.fields()[0] = 2.5;  // L
  const Model::Constants<double> c(parameters);
  const Model::DerivedParameters<double>& d = c.derived_parameters();
  std::printf("derived %.17g %.17g %.17g %.17g %.17g\n", d.derived_, d.k0, d.w0, d.p_, d.int_);
  Model::Vector<double> q, qd, F;
  Model::Inputs<double> u;
  q << 0.3;
  qd << -0.2;
  Model::MassMatrix<double> M;
  Model::OutputVector<double> y;
  Model::mass_matrix_and_forcing(0.0, q, qd, u, c, M, F);
  Model::outputs(0.0, q, qd, u, c, y);
  std::printf("M %.17g\nF %.17g\ny %.17g\n", M(0, 0), F(0), y(0));
}
)";

class DerivedParametersHeader : public eomgen::testing::CliFixture {
 protected:
  Outcome shell(const std::string& command) {
    const fs::path out = dir_ / "shell.out";
    const int raw = std::system((command + " > " + quote(out.string()) + " 2>&1").c_str());
    return Outcome{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), ""};
  }
};

void expect_close(double actual, double expected, const std::string& what) {
  EXPECT_NEAR(actual, expected, 1e-12 * (1 + std::abs(expected))) << what;
}

TEST_F(DerivedParametersHeader, CompilesStrictlyAndItsConstantsGiveEvalsDerivedParametersAndEquations) {
  const std::string path = model("derived_names.eom", model_text);
  const fs::path header = dir_ / "model.hpp", source = dir_ / "program.cpp", binary = dir_ / "program";
  const Outcome generated = eomgen("generate " + quote(path) + " -o " + quote(header.string()));
  ASSERT_EQ(generated.status, 0) << generated.err;
  std::ofstream(source) << program;
  namespace config = eomgen::tools::build_config;
  const Outcome compiled = shell(quote(config::cxx_compiler) + " -std=c++17 -Wall -Wextra -Wshadow -Werror -pedantic -I" +
                                 quote(config::eigen_include_dir) + " " + quote(source.string()) + " -o " +
                                 quote(binary.string()));
  ASSERT_EQ(compiled.status, 0) << compiled.out;
  const Outcome run = shell(quote(binary.string()));
  ASSERT_EQ(run.status, 0) << run.out;
  std::map<std::string, std::vector<double>> printed;
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    for (double v; words >> v;) printed[key].push_back(v);
  }
  const Outcome eval = eomgen("eval " + quote(path) + " --at theta=0.3,theta_dot=-0.2 --set L=2.5 -f json");
  ASSERT_EQ(eval.status, 0) << eval.err;
  const nlohmann::json j = nlohmann::json::parse(eval.out);
  // by hand: derived = 0.45 L, k0 = derived/3 + m, w0 = k0^2 + sin L, p = derived + w0, int = p/L
  const double derived = 0.45 * 2.5, k0 = derived / 3 + 1.5, w0 = k0 * k0 + std::sin(2.5), p = derived + w0,
               int_ = p / 2.5;
  const std::vector<std::pair<const char*, double>> expected{
      {"derived", derived}, {"k0", k0}, {"w0", w0}, {"p", p}, {"int", int_}};
  ASSERT_EQ(printed["derived"].size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    expect_close(printed["derived"][k], expected[k].second, expected[k].first);
    expect_close(j["derived_parameters"][expected[k].first], expected[k].second, expected[k].first);
  }
  // a particle of mass m + k0 at (derived, int) in b: M = (m + k0)(derived^2 + int^2)
  expect_close(printed["M"].at(0), (1.5 + k0) * (derived * derived + int_ * int_), "M by hand");
  expect_close(printed["M"].at(0), j["M"][0][0], "M");
  expect_close(printed["F"].at(0), j["F"][0], "F");
  expect_close(printed["y"].at(0), p * std::sin(0.3), "arm");
}

}  // namespace
