// Every command line that README.md and docs/*.md show in a ```sh block runs as written and
// exits 0, so the documentation cannot drift from the program. One test per block, named after
// its file and line; the commands of a block run in order, in one fresh directory that looks
// like the repository root (models/, scripts/, ... link to the sources, build/ to this build),
// with `eomgen` on the PATH as the README assumes after `cmake --install`.
//
// A command that cannot run inside the test suite is listed in `not_run` below with the reason
// and where it does run; an entry that no longer matches a documented command fails, so the
// list cannot go stale either.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::testing::quote;
using eomgen::testing::slurp;

struct NotRun {
  const char* command;
  const char* reason;
};

// Commands the suite cannot run, with the reason; each must still be documented verbatim.
const NotRun not_run[] = {
    {"scripts/run-example.sh", "the main job: CI runs it as written (.ci/run), and "
                               "scripts/check-fresh-debian.sh runs it in a pristine Debian 12 root"},
    {"scripts/test.sh", "this test suite itself: CI runs it as written, and scripts/check-fresh-debian.sh "
                        "runs it in a pristine Debian 12 root"},
    {"scripts/check-fresh-debian.sh", "builds a Debian root and the whole project in it (about 30 min, as root)"},
    {"ctest --test-dir build -L browser", "the browser tests are part of this suite (label browser); "
                                          "docs/animation.md's other commands run one of them as written"},
    {"cmake -S . -B build && cmake --build build -j2 && ctest --test-dir build",
     "configures, builds and runs this suite: scripts/test.sh does the same, and CI runs that"},
    {"cmake -S . -B build-asan -DEOMGEN_SANITIZE=ON",
     "a second configuration and build of everything; CI's sanitizer phase builds it"},
    {"bench/compare_peers.sh", "the peer benchmark: 20-30 min, installs MuJoCo and SymPy"},
    {"bench/compare_peers.sh > report.md", "the peer benchmark: 20-30 min, installs MuJoCo and SymPy"},
    {"PEERS_QUICK=1 bench/compare_peers.sh", "installs MuJoCo and SymPy; a benchmark, not a test"},
    {"scripts/fuzz.sh 60 2", "installs clang 14 and builds the fuzzer in a second, instrumented build folder; "
                             "CI's fuzz phase runs it, with as many workers as cores (.ci/run)"},
    {"scripts/fuzz.sh 1800 2", "the issue's 30-minute fuzzing run: CI runs the same script for 60 s (.ci/run)"},
    {"/usr/bin/python3 bench/python/python_bench.py --eomgen build/generator/eomgen --out report.md",
     "the Python modules' benchmark: minutes of timing on a quiet machine, a benchmark, not a test"},
    {"/usr/bin/python3 bench/python/python_bench.py --eomgen build/generator/eomgen --quick",
     "its smoke run is the test Python.benchmark_smoke_run (tests/python/CMakeLists.txt), with the "
     "suite's eomgen and cache"},
    {"ROUNDS=41 bench/peers/mpc_derivatives.sh",
     "the derivatives' benchmark: compiles ten programs against MuJoCo and times them (minutes), a benchmark, "
     "not a test"},
    {"bench/model_times.sh build/generator/eomgen",
     "a benchmark, not a test: times commands and compiles a simulation three times (minutes)"},
};

struct Block {
  std::string file;  // relative to the source root
  int line = 0;      // of the opening fence
  std::vector<std::string> commands;
};

// gtest prints a parameter that fails; without this it would dump the bytes of the struct
void PrintTo(const Block& b, std::ostream* os) { *os << b.file << ":" << b.line; }

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// the command without a trailing "# comment" (a '#' after white space, outside quotes)
std::string without_comment(const std::string& line) {
  bool single = false, dbl = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '\'' && !dbl) single = !single;
    if (c == '"' && !single) dbl = !dbl;
    if (c == '#' && !single && !dbl && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t'))
      return trim(line.substr(0, i));
  }
  return trim(line);
}

std::vector<Block> blocks_of(const fs::path& root, const std::string& relative) {
  std::vector<Block> out;
  std::ifstream in(root / relative);
  std::string line;
  int number = 0;
  Block* open = nullptr;
  bool in_other_fence = false;
  std::string pending;
  while (std::getline(in, line)) {
    ++number;
    const std::string t = trim(line);
    if (open == nullptr && !in_other_fence && t.rfind("```", 0) == 0) {
      if (t == "```sh" || t == "```bash" || t == "```shell") {
        out.push_back(Block{relative, number, {}});
        open = &out.back();
      } else {
        in_other_fence = true;
      }
      continue;
    }
    if (in_other_fence) {
      if (t == "```") in_other_fence = false;
      continue;
    }
    if (open == nullptr) continue;
    if (t == "```") {
      open = nullptr;
      continue;
    }
    const std::string command = without_comment(line);
    if (command.empty()) continue;
    if (command.back() == '\\') {
      pending += command.substr(0, command.size() - 1) + " ";
      continue;
    }
    open->commands.push_back(pending + command);
    pending.clear();
  }
  return out;
}

std::vector<std::string> documents() {
  std::vector<std::string> files{"README.md"};
  std::vector<std::string> docs;
  for (const auto& entry : fs::directory_iterator(fs::path(EOMGEN_SOURCE_DIR) / "docs"))
    if (entry.path().extension() == ".md") docs.push_back("docs/" + entry.path().filename().string());
  std::sort(docs.begin(), docs.end());
  files.insert(files.end(), docs.begin(), docs.end());
  return files;
}

std::vector<Block> all_blocks() {
  std::vector<Block> out;
  for (const std::string& file : documents())
    for (Block& b : blocks_of(EOMGEN_SOURCE_DIR, file)) out.push_back(std::move(b));
  return out;
}

const NotRun* not_run_entry(const std::string& command) {
  for (const NotRun& n : not_run)
    if (command == n.command) return &n;
  return nullptr;
}

std::string test_name(const ::testing::TestParamInfo<Block>& info) {
  std::string name = fs::path(info.param.file).stem().string() + "_line" + std::to_string(info.param.line);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class DocumentedCommands : public ::testing::TestWithParam<Block> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("eomgen_docs_" + std::to_string(::getpid()) + "_" + test_name({GetParam(), 0}));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // the repository root as the documents assume it, without letting a command write into it
    for (const auto& entry : fs::directory_iterator(EOMGEN_SOURCE_DIR)) {
      const std::string name = entry.path().filename().string();
      if (name == "build" || name == ".git") continue;
      fs::create_directory_symlink(entry.path(), dir_ / name);
    }
    fs::create_directory_symlink(EOMGEN_BUILD_DIR, dir_ / "build");
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  fs::path dir_;
};

TEST_P(DocumentedCommands, RunsAsWrittenAndExitsZero) {
  const Block& block = GetParam();
  ASSERT_FALSE(block.commands.empty()) << block.file << ":" << block.line << ": an empty sh block";
  for (const std::string& command : block.commands) {
    if (const NotRun* n = not_run_entry(command)) {
      // not run here, but what it names must exist
      const std::string program = command.substr(0, command.find(' '));
      if (program.find('/') != std::string::npos && program.find('=') == std::string::npos) {
        EXPECT_TRUE(fs::exists(fs::path(EOMGEN_SOURCE_DIR) / program)) << command << ": " << program << " does not exist";
      }
      std::cout << "not run here: " << command << " (" << n->reason << ")\n";
      continue;
    }
    const fs::path out = dir_ / "output.txt";
    // python3 is the interpreter the Python modules were configured for (the first on PATH may
    // lack NumPy), as on a machine where scripts/install-deps.sh installed Debian's
    const std::string script = "cd " + quote(dir_.string()) + " && export PATH=" + quote(EOMGEN_BIN_DIR) + ":" +
                               quote(EOMGEN_PYTHON_BIN_DIR) + ":\"$PATH\" EOMGEN_BUILD_DIR=" + quote(EOMGEN_BUILD_DIR) +
                               " EOMGEN_CACHE_DIR=" + quote(EOMGEN_TEST_CACHE_DIR) + " && set -o pipefail && " +
                               command;
    const std::string shell = "bash -c " + quote(script) + " > " + quote(out.string()) + " 2>&1 < /dev/null";
    const int raw = std::system(shell.c_str());
    const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    EXPECT_EQ(status, 0) << block.file << ":" << block.line << ": `" << command << "` exited with " << status
                         << "; it printed:\n"
                         << slurp(out);
  }
}

INSTANTIATE_TEST_SUITE_P(Docs, DocumentedCommands, ::testing::ValuesIn(all_blocks()), test_name);

TEST(DocumentedCommandsList, EveryCommandNotRunIsStillDocumented) {
  std::vector<std::string> documented;
  for (const Block& b : all_blocks()) documented.insert(documented.end(), b.commands.begin(), b.commands.end());
  for (const NotRun& n : not_run)
    EXPECT_NE(std::find(documented.begin(), documented.end(), n.command), documented.end())
        << "'" << n.command << "' is listed as not run but no document shows it any more";
}

TEST(DocumentedCommandsList, FindsTheReadmesCommands) {
  // the extraction itself: the README's first block is the two commands, comments stripped
  const std::vector<Block> readme = blocks_of(EOMGEN_SOURCE_DIR, "README.md");
  ASSERT_FALSE(readme.empty());
  EXPECT_EQ(readme.front().commands, (std::vector<std::string>{"scripts/run-example.sh", "scripts/test.sh"}));
  EXPECT_EQ(without_comment("eomgen check a.eom   # note"), "eomgen check a.eom");
  EXPECT_EQ(without_comment("echo 'a # b'"), "echo 'a # b'");
}

}  // namespace
