// Output paths as the commands take them: what gnuplot cannot be given exactly is refused
// before any work and the rest reaches it byte for byte; outputs that cannot or must not be
// written (a directory, a missing directory, two outputs in one file) are refused before any
// work; a plot that fails after its table was written keeps the table and says so (status 3);
// JSON stays whole and valid for a model named after a file name that is not UTF-8.
//
// Sweeps of `linearize` stand for the plots here (no compilation); simulate_command_test has the
// same cases for `simulate`.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::testing::Outcome;
using eomgen::testing::slurp;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using ::testing::UnorderedElementsAre;

const std::string pendulum = std::string(EOMGEN_SOURCE_DIR) + "/models/simple_pendulum.eom";

/// any text in single quotes for the shell (a quote: close, escape, reopen)
std::string shell(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

class OutputPaths : public eomgen::testing::CliFixture {
 protected:
  std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    return names;
  }
  // a gnuplot on PATH that runs `script` (sh) instead of the real one
  void fake_gnuplot(const std::string& script) {
    const fs::path bin = dir_ / "bin";
    fs::create_directories(bin);
    std::ofstream(bin / "gnuplot") << "#!/bin/sh\n" << script << "\n";
    fs::permissions(bin / "gnuplot", fs::perms::owner_all);
    saved_path_ = std::getenv("PATH");
    ::setenv("PATH", (bin.string() + ":" + saved_path_).c_str(), 1);
  }
  void TearDown() override {
    if (!saved_path_.empty()) ::setenv("PATH", saved_path_.c_str(), 1);
    CliFixture::TearDown();
  }
  std::string saved_path_;
};

// a line break ends a gnuplot command inside any quotes: a path gnuplot would get with one is
// refused (status 2) before the model is derived or compiled, whichever option names it
TEST_F(OutputPaths, PathsWithALineBreakThatGnuplotWouldGetAreRefusedBeforeAnyWork) {
  const fs::path work = dir_ / "work";
  const struct {
    std::string arguments, message;
  } cases[] = {
      {"simulate " + shell(pendulum) + " --t-end 1 --plot " + shell((work / "a\nb.svg").string()),
       "eomgen: error: --plot: '" + (work / "a\\nb.svg").string() +
           "' has a line break, which ends a command of gnuplot whatever the quoting; choose a path without one\n"},
      // gnuplot reads the CSV: with a plot, -o must suit gnuplot too
      {"simulate " + shell(pendulum) + " --t-end 1 -o " + shell((work / "a\rb.csv").string()) + " --plot " +
           shell((work / "ok.svg").string()),
       "eomgen: error: -o: '" + (work / "a\\rb.csv").string() + "' has a line break"},
      {"linearize " + shell(pendulum) + " --sweep l=0.5:1:0.5 --plot " + shell((work / "x\ny.svg").string()),
       "eomgen: error: --plot: '" + (work / "x\\ny.svg").string() + "' has a line break"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.arguments);
    const Outcome run = eomgen(c.arguments);
    EXPECT_EQ(run.status, 2);
    EXPECT_THAT(run.err, ::testing::StartsWith(c.message));
    EXPECT_THAT(run.err, Not(HasSubstr("compiling")));
    EXPECT_EQ(run.out, "");
    EXPECT_THAT(entries(work), IsEmpty());
  }
  // a relative path is made absolute with the working directory, whose name can have one too
  const fs::path odd = work / "dir\nname";
  fs::create_directories(odd);
  const std::string command = "cd " + shell(odd.string()) + " && " + shell(EOMGEN_EXE) + " linearize " +
                              shell(pendulum) + " --sweep l=0.5:1:0.5 --plot p.svg > /dev/null 2> " +
                              shell((dir_ / "err").string());
  const int raw = std::system(command.c_str());
  EXPECT_EQ(WEXITSTATUS(raw), 2);
  EXPECT_EQ(slurp(dir_ / "err"), "eomgen: error: --plot: 'p.svg' (as gnuplot gets it: '" + (work / "dir\\nname/p.svg").string() +
                                     "') has a line break, which ends a command of gnuplot whatever the quoting; "
                                     "choose a path without one\n");
  EXPECT_THAT(entries(odd), IsEmpty());
  // and a symbolic link can name a file in such a directory
  fs::create_symlink(odd / "p.svg", work / "link.svg");
  const Outcome linked = eomgen("linearize " + shell(pendulum) + " --sweep l=0.5:1:0.5 --plot " +
                                shell((work / "link.svg").string()));
  EXPECT_EQ(linked.status, 2);
  EXPECT_EQ(linked.err, "eomgen: error: --plot: '" + (work / "link.svg").string() + "' (as gnuplot gets it: '" +
                            (work / "dir\\nname/p.svg").string() +
                            "') has a line break, which ends a command of gnuplot whatever the quoting; choose a "
                            "path without one\n");
  EXPECT_THAT(entries(odd), IsEmpty());
}

// every other byte reaches gnuplot as it is: quotes, a backslash, $, @, #, a tab, a byte that is
// not UTF-8 (gnuplot's single quotes carry them); the files appear at exactly those names
TEST_F(OutputPaths, EveryOtherByteOfAPathReachesGnuplotExactly) {
  const fs::path out = dir_ / "work" / "q'\"\\$@# \t\xff;x";
  fs::create_directories(out);
  const Outcome run = eomgen("linearize " + shell(pendulum) + " --sweep l=0.5:1:0.25 -f csv -o " +
                             shell((out / "s.csv").string()) + " --plot " + shell((out / "s'1.svg").string()));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("plot: " + (out / "s'1.svg").string() + "\n"));
  EXPECT_THAT(entries(out), UnorderedElementsAre("s.csv", "s'1.svg"));
  EXPECT_THAT(slurp(out / "s'1.svg"), HasSubstr("<svg"));
  EXPECT_THAT(slurp(out / "s.csv"), ::testing::StartsWith("l,verdict,re1,im1,re2,im2\n0.5,"));
}

// the table is complete when the plot fails: it is kept, the message says so and why, and the
// status (3) tells a script that only the plot is missing; no temporary file remains
TEST_F(OutputPaths, APlotThatFailsAfterTheTableKeepsTheTableAndSaysSo) {
  const fs::path work = dir_ / "work";
  const Outcome reference = eomgen("linearize " + shell(pendulum) + " --sweep l=0.5:1:0.25 -f csv");
  ASSERT_EQ(reference.status, 0) << reference.err;

  fake_gnuplot("echo 'gnuplot: cannot do it, on purpose' >&2\nexit 1");
  const Outcome run = eomgen("linearize " + shell(pendulum) + " --sweep l=0.5:1:0.25 -f csv -o " +
                             shell((work / "s.csv").string()) + " --plot " + shell((work / "s.svg").string()));
  EXPECT_EQ(run.status, 3);
  EXPECT_EQ(run.err, "eomgen: error: the plot '" + (work / "s.svg").string() + "' was not written (the sweep's csv '" +
                         (work / "s.csv").string() +
                         "' is complete and kept): gnuplot failed (exit status 1):\ngnuplot: cannot do it, on "
                         "purpose\n\n");
  EXPECT_EQ(slurp(work / "s.csv"), reference.out);
  EXPECT_THAT(entries(work), ElementsAre("s.csv"));

  // printed rather than written: the message says the printed sweep is the complete part
  const Outcome printed =
      eomgen("linearize " + shell(pendulum) + " --sweep l=0.5:1:0.25 -f csv --plot " + shell((work / "p.svg").string()));
  EXPECT_EQ(printed.status, 3);
  EXPECT_EQ(printed.out, reference.out);
  EXPECT_THAT(printed.err, HasSubstr("eomgen: error: the plot '" + (work / "p.svg").string() +
                                     "' was not written (the sweep printed above is complete and kept): gnuplot "
                                     "failed (exit status 1)"));

  // a gnuplot that "succeeds" without writing anything is a failure too, not an empty plot
  fake_gnuplot("exit 0");
  const Outcome silent = eomgen("linearize " + shell(pendulum) + " --sweep l=0.5:1:0.25 -f csv -o " +
                                shell((work / "t.csv").string()) + " --plot " + shell((work / "t.svg").string()));
  EXPECT_EQ(silent.status, 3);
  EXPECT_THAT(silent.err, HasSubstr("(the sweep's csv '" + (work / "t.csv").string() +
                                    "' is complete and kept): gnuplot ended with status 0 but wrote no image"));
  EXPECT_THAT(entries(work), UnorderedElementsAre("s.csv", "t.csv"));
}

// outputs that cannot or must not be written are refused (status 2) before any work, and
// nothing is written: a directory, a file in a directory that does not exist, the plot in the
// same file as the CSV or table (by name, through "." or a symbolic link)
TEST_F(OutputPaths, OutputsThatCannotOrMustNotBeWrittenAreRefusedBeforeAnyWork) {
  const fs::path work = dir_ / "work";
  const std::string m = shell(pendulum), d = (work / "dir").string(), csv = (work / "r.csv").string(),
                    svg = (work / "r.svg").string(), link = (work / "link.svg").string();
  fs::create_directories(d);
  fs::create_symlink("r.svg", link);
  const struct {
    std::string arguments, message;
  } cases[] = {
      {"derive " + m + " -o " + shell(d), "-o: '" + d + "' is a directory; give the name of a file"},
      {"generate " + m + " -o " + shell(d), "-o: '" + d + "' is a directory; give the name of a file"},
      {"linearize " + m + " -o " + shell(d), "-o: '" + d + "' is a directory; give the name of a file"},
      {"simulate " + m + " --t-end 1 --no-plot -o " + shell(d), "-o: '" + d + "' is a directory; give the name of a file"},
      {"simulate " + m + " --t-end 1 -o " + shell(csv) + " --plot " + shell(d + "/"),
       "--plot: '" + d + "/' is a directory; give the name of a file"},
      {"generate " + m + " -o " + shell(d + "/none/x.hpp"),
       "-o: cannot write '" + d + "/none/x.hpp': the directory '" + d + "/none' does not exist"},
      {"simulate " + m + " --t-end 1 -o " + shell(csv) + " --plot " + shell(d + "/none/p.svg"),
       "--plot: cannot write '" + d + "/none/p.svg': the directory '" + d + "/none' does not exist"},
      {"simulate " + m + " --t-end 1 -o " + shell(svg) + " --plot " + shell(work.string() + "/./r.svg"),
       "--plot: '" + work.string() + "/./r.svg' is the same file as -o '" + svg +
           "'; each output needs a file of its own"},
      {"simulate " + m + " --t-end 1 -o " + shell(svg) + " --plot " + shell(link),
       "--plot: '" + link + "' is the same file as -o '" + svg + "'"},
      {"linearize " + m + " --sweep l=0.5:1:0.5 -f csv -o " + shell(link) + " --plot " + shell(svg),
       "--plot: '" + svg + "' is the same file as -o '" + link + "'"},
      // gnuplot reads the CSV back: not from a device or a pipe
      {"simulate " + m + " --t-end 1 -o /dev/null --plot " + shell(svg),
       "-o: '/dev/null' is not a regular file, which gnuplot could read the CSV back from for the plot; pass "
       "--no-plot, or write the CSV to a file"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.arguments);
    const Outcome run = eomgen(c.arguments);
    EXPECT_EQ(run.status, 2);
    EXPECT_THAT(run.err, ::testing::StartsWith("eomgen: error: " + c.message));
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1);  // that one line, nothing after it
    EXPECT_THAT(run.err, Not(HasSubstr("compiling")));
    EXPECT_EQ(run.out, "");
    EXPECT_THAT(entries(work), UnorderedElementsAre("dir", "link.svg"));
    EXPECT_THAT(entries(d), IsEmpty());
  }
}

// a model without a `model` line is named after its file; a file name that is not UTF-8 (the
// byte 0xff) gives a name JSON cannot hold as it is: the byte is written as U+FFFD, the document
// is whole and valid, and the plot's title (SVG, XML) is valid UTF-8 the same way
TEST_F(OutputPaths, AModelNamedByAFileNameThatIsNotUtf8GivesWholeValidJsonAndPlots) {
  std::string text = slurp(pendulum);
  const std::size_t line = text.find("\nmodel ");
  ASSERT_NE(line, std::string::npos);
  text.erase(line + 1, text.find('\n', line + 1) - line);
  const std::string path = model("p\xff.eom", text);
  const std::string replaced = "p_";  // a model named after its file gets an identifier

  for (const std::string& request : {"eval " + shell(path) + " --at theta=0.5 -f json",
                                    "linearize " + shell(path) + " --at theta=0.5 -f json",
                                    "linearize " + shell(path) + " --sweep l=0.5:1:0.5 -f json"}) {
    SCOPED_TRACE(request);
    const Outcome run = eomgen(request);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    const nlohmann::json j = nlohmann::json::parse(run.out);  // throws unless whole and valid
    EXPECT_EQ(j.at("model"), replaced);
    EXPECT_EQ(run.out.find('\xff'), std::string::npos);
  }
  const Outcome eval = eomgen("eval " + shell(path) + " --at theta=0.5 -f json");
  EXPECT_EQ(nlohmann::json::parse(eval.out).at("state").at("theta"), 0.5);

  const fs::path svg = dir_ / "work" / "p.svg";
  const Outcome plot = eomgen("linearize " + shell(path) + " --sweep l=0.5:1:0.5 --plot " + shell(svg.string()));
  ASSERT_EQ(plot.status, 0) << plot.err;
  const std::string image = slurp(svg);
  EXPECT_THAT(image, HasSubstr(replaced + ": eigenvalues against l"));
  EXPECT_EQ(image.find('\xff'), std::string::npos);
}

}  // namespace
