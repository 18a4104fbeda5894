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

}  // namespace
