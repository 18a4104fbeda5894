// `eomgen simulate` interrupted (SIGINT as Ctrl-C sends it, SIGTERM as a service manager
// does) while it compiles and while the simulation runs: it ends by that signal (the shell's
// status 130 or 143), leaves no temporary file in the output directory or the cache, stops its
// child processes, and the cache serves the next run.
#include <gmock/gmock.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_runner.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using eomgen::testing::quote;
using eomgen::testing::slurp;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

const std::string models_dir = std::string(EOMGEN_SOURCE_DIR) + "/models/";

class Interruption : public eomgen::testing::CliFixture {
 protected:
  // eomgen started directly (no shell, which may ignore SIGINT for a background command), with
  // SIGINT and SIGTERM at their defaults; its output goes to files of the test directory
  pid_t start(const std::vector<std::string>& arguments) {
    std::vector<std::string> argv{EOMGEN_EXE};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    std::vector<char*> args;
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (dir_ / "stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, (dir_ / "stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    pid_t pid = 0;
    EXPECT_EQ(posix_spawn(&pid, args[0], &actions, &attributes, args.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    return pid;
  }

  // polls `ready` every 10 ms for up to `seconds`
  static bool eventually(const std::function<bool()>& ready, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (ready()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return ready();
  }

  // the wait status of `pid`, which must end within `seconds` (else it is killed)
  static int finish(pid_t pid, double seconds) {
    int status = 0;
    const bool ended = eventually([&] { return ::waitpid(pid, &status, WNOHANG) == pid; }, seconds);
    if (!ended) {
      ADD_FAILURE() << "eomgen did not end within " << seconds << " s of the signal";
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
    }
    return status;
  }

  // whether an entry of `dir` (which may not exist yet) satisfies `test`
  static bool any_entry(const fs::path& dir, const std::function<bool(const fs::path&)>& test) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (test(entry.path())) return true;
    return false;
  }

  static std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    return names;
  }

  // the processes whose command line mentions `text` (a path unique to the test)
  static std::vector<std::string> processes_mentioning(const std::string& text) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator("/proc")) {
      const std::string pid = entry.path().filename().string();
      if (pid.find_first_not_of("0123456789") != std::string::npos || pid == std::to_string(::getpid())) continue;
      std::string cmdline = slurp(entry.path() / "cmdline");
      if (cmdline.find(text) != std::string::npos) {
        for (char& c : cmdline)
          if (c == '\0') c = ' ';
        found.push_back(pid + ": " + cmdline);
      }
    }
    return found;
  }
};

// Ctrl-C in the middle of a long simulation: the CSV being written (a temporary next to -o) is
// removed, the simulation program is stopped, eomgen dies by SIGINT
TEST_F(Interruption, SigintWhileTheSimulationRunsLeavesNothing) {
  const fs::path out = dir_ / "work" / "out";
  fs::create_directories(out);
  const std::string model = models_dir + "simple_pendulum.eom", cache = EOMGEN_TEST_CACHE_DIR;
  // the program is compiled (or found in the cache) first, so the signal comes while it runs
  const auto warm = eomgen("simulate " + quote(model) + " --t-end 0.01 --no-plot -o " +
                           quote((dir_ / "warm.csv").string()) + " --cache-dir " + quote(cache));
  ASSERT_EQ(warm.status, 0) << warm.err;

  const pid_t pid = start({"simulate", model, "--t-end", "1e6", "--sample", "1e-4", "--init", "theta=1", "-o",
                           (out / "run.csv").string(), "--plot", (out / "run.svg").string(), "--cache-dir", cache});
  // the simulation program is writing its rows into the temporary CSV
  const bool writing = eventually(
      [&] {
        return any_entry(out, [](const fs::path& p) {
          return p.filename().string().rfind(".run.csv.", 0) == 0 && fs::file_size(p) > 0;
        });
      },
      60);
  ASSERT_TRUE(writing) << slurp(dir_ / "stderr");
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  const int status = finish(pid, 10);

  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "wait status " << status;
  EXPECT_THAT(slurp(dir_ / "stderr"),
              HasSubstr("eomgen: interrupted by SIGINT; its temporary files are removed, no partial output is left\n"));
  EXPECT_THAT(entries(out), IsEmpty());
  EXPECT_THAT(processes_mentioning(out.string()), IsEmpty());  // the simulation program is gone
}

// SIGTERM while the compiler runs: the half-built program's directory leaves the cache, the
// compiler (and its own children) stop, and the next run builds the program afresh
TEST_F(Interruption, SigtermWhileCompilingLeavesTheCacheEmptyAndUsable) {
  const fs::path out = dir_ / "work" / "out", cache = dir_ / "cache";
  fs::create_directories(out);
  const std::vector<std::string> request{"simulate", models_dir + "simple_pendulum.eom", "--t-end", "0.1", "--no-plot",
                                         "-o", (out / "run.csv").string(), "--cache-dir", cache.string()};
  const pid_t pid = start(request);
  // the build directory has the compiler's log: the compiler has been started
  const bool compiling = eventually(
      [&] { return any_entry(cache, [](const fs::path& p) { return fs::exists(p / "compile.log"); }); }, 60);
  ASSERT_TRUE(compiling) << slurp(dir_ / "stderr");
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  const int status = finish(pid, 10);

  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "wait status " << status;
  EXPECT_THAT(slurp(dir_ / "stderr"), HasSubstr("eomgen: interrupted by SIGTERM; its temporary files are removed"));
  EXPECT_THAT(entries(cache), IsEmpty());
  EXPECT_THAT(entries(out), IsEmpty());
  EXPECT_THAT(processes_mentioning(cache.string()), IsEmpty());  // neither the driver nor cc1plus

  std::string again = "simulate";
  for (std::size_t i = 1; i < request.size(); ++i) again += " " + quote(request[i]);
  const auto run = eomgen(again);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("compiling the simulation of simple_pendulum"));
  EXPECT_THAT(slurp(out / "run.csv"), ::testing::StartsWith("t,theta,theta_dot,"));
  EXPECT_THAT(entries(out), ::testing::ElementsAre("run.csv"));
}

}  // namespace
