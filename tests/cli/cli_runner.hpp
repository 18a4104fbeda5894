#pragma once
// Running the built eomgen program (EOMGEN_EXE) in a per-test temporary directory and
// capturing what a user sees: exit status, standard output and standard error.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace eomgen::testing {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out, err;
};

/// `s` in single quotes for the shell (test paths contain no single quote of their own)
inline std::string quote(const std::string& s) { return "'" + s + "'"; }

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// A fresh directory per test (kept when the test fails, for a look at what was written).
class CliFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("eomgen_" + std::string(info->test_suite_name()) + "_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "work");
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // writes a model file into the work directory; returns its path
  std::string model(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / "work" / name;
    std::ofstream(path) << text;
    return path.string();
  }

  // runs eomgen with `arguments` (already quoted for the shell)
  Outcome eomgen(const std::string& arguments) {
    const fs::path out = dir_ / "stdout", err = dir_ / "stderr";
    const std::string command =
        quote(EOMGEN_EXE) + " " + arguments + " > " + quote(out.string()) + " 2> " + quote(err.string());
    const int raw = std::system(command.c_str());
    Outcome run;
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    run.out = slurp(out);
    run.err = slurp(err);
    return run;
  }

  fs::path dir_;
};

}  // namespace eomgen::testing
