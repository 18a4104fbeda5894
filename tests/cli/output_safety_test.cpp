// An output file that is the model file itself, by its own name or through a symbolic or a
// hard link, is refused before anything runs, and the model is left as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::testing::quote;
using eomgen::testing::slurp;
using ::testing::HasSubstr;
using ::testing::Not;

class OutputSafety : public eomgen::testing::CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    original_ = slurp(fs::path(EOMGEN_SOURCE_DIR) / "models" / "simple_pendulum.eom");
    model_ = model("pendulum.eom", original_);
    fs::create_symlink(model_, dir_ / "work" / "link.svg");
    fs::create_hard_link(model_, dir_ / "work" / "hard.csv");
  }
  std::string original_, model_;
};

TEST_F(OutputSafety, NoCommandWritesOverItsModel) {
  const std::string m = quote(model_), link = quote((dir_ / "work" / "link.svg").string()),
                    hard = quote((dir_ / "work" / "hard.csv").string());
  const std::pair<std::string, std::string> requests[] = {
      {"derive " + m + " -o " + m, "-o: "},
      {"generate " + m + " -o " + link, "-o: "},
      {"linearize " + m + " -o " + hard, "-o: "},
      {"linearize " + m + " --sweep l=0.5:1:0.5 --plot " + link, "--plot: "},
      {"simulate " + m + " --t-end 1 -o " + hard + " --no-plot", "-o: "},
      {"simulate " + m + " --t-end 1 -o " + quote((dir_ / "run.csv").string()) + " --plot " + link, "--plot: "},
  };
  for (const auto& [arguments, option] : requests) {
    SCOPED_TRACE(arguments);
    const auto run = eomgen(arguments);
    EXPECT_EQ(run.status, 2);
    EXPECT_THAT(run.err, HasSubstr("eomgen: error: " + option));
    EXPECT_THAT(run.err, HasSubstr("is the model file"));
    EXPECT_EQ(slurp(model_), original_);
    EXPECT_TRUE(fs::is_symlink(dir_ / "work" / "link.svg"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "run.csv"));
}

// simulate also reads the headers it compiles the program from and runs programs from its cache:
// an output that is one of those headers (by name or through a link) or lies in the cache is
// refused before anything runs, and the headers stay as they were
TEST_F(OutputSafety, NoSimulationWritesOverItsProgramsSourcesOrIntoItsCache) {
  const std::string m = quote(model_), cache = (dir_ / "cache").string();
  const fs::path runtime_header = fs::path(EOMGEN_SOURCE_DIR) / "runtime" / "include" / "eomrt" / "simulate.hpp";
  const fs::path program_header =
      fs::path(EOMGEN_SOURCE_DIR) / "generator" / "cli" / "simulation_program" / "run_settings.hpp";
  const std::string runtime_text = slurp(runtime_header), program_text = slurp(program_header);
  fs::create_directories(dir_ / "cache" / "old");
  fs::create_symlink(program_header, dir_ / "work" / "settings.svg");
  const std::string settings = (dir_ / "work" / "settings.svg").string();
  const std::pair<std::string, std::string> requests[] = {
      {"-o " + quote(runtime_header.string()) + " --no-plot",
       "-o: '" + runtime_header.string() + "' is '" + runtime_header.string() +
           "', one of the sources of the simulation program this run reads; writing it would destroy it, so choose "
           "another output file\n"},
      {"-o " + quote((dir_ / "run.csv").string()) + " --plot " + quote(settings),
       "--plot: '" + settings + "' is '" + program_header.string() + "', one of the sources of the simulation program"},
      {"-o " + quote(cache + "/old/run.csv") + " --no-plot",
       "-o: '" + cache + "/old/run.csv' is in the cache directory '" + cache +
           "', whose compiled programs eomgen runs; choose a file outside it\n"},
  };
  for (const auto& [arguments, message] : requests) {
    SCOPED_TRACE(arguments);
    const auto run = eomgen("simulate " + m + " --t-end 1 --cache-dir " + quote(cache) + " " + arguments);
    EXPECT_EQ(run.status, 2);
    EXPECT_THAT(run.err, ::testing::StartsWith("eomgen: error: " + message));
    EXPECT_THAT(run.err, Not(HasSubstr("compiling")));
  }
  EXPECT_EQ(slurp(runtime_header), runtime_text);
  EXPECT_EQ(slurp(program_header), program_text);
  EXPECT_TRUE(fs::is_empty(dir_ / "cache" / "old"));
  EXPECT_FALSE(fs::exists(dir_ / "run.csv"));
}

}  // namespace
