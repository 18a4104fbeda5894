#include "cached_build.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "eomgen/base/content_hash.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/base/version.hpp"
#include "eomgen_build_config.hpp"
#include "file_output.hpp"
#include "interruption.hpp"
#include "process.hpp"

namespace eomgen::tools {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path cache_root(const std::string& option) {
  if (!option.empty()) return option;
  if (const char* dir = std::getenv("EOMGEN_CACHE_DIR"); dir && *dir) return dir;
  if (const char* dir = std::getenv("XDG_CACHE_HOME"); dir && *dir) return fs::path(dir) / "eomgen";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "eomgen";
  throw Error("no cache directory: set EOMGEN_CACHE_DIR or HOME, or pass --cache-dir");
}

std::optional<fs::path> find_sources(const fs::path& installed, const fs::path& source, const fs::path& marker) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && fs::exists(exe.parent_path() / installed / marker, ec)) return exe.parent_path() / installed;
  if (fs::exists(source / marker, ec)) return source;
  return std::nullopt;
}

fs::path runtime_include_dir() {
  if (const char* dir = std::getenv("EOMGEN_RUNTIME_INCLUDE_DIR"); dir && *dir) return dir;
  const std::optional<fs::path> found = find_sources(build_config::installed_runtime_include_dir,
                                                     build_config::source_runtime_include_dir, "eomrt/simulate.hpp");
  if (found) return *found;
  throw Error(fmt::format("the eomrt runtime headers are neither next to eomgen nor in '{}'; set "
                          "EOMGEN_RUNTIME_INCLUDE_DIR to the directory that holds eomrt/",
                          build_config::source_runtime_include_dir));
}

std::vector<fs::path> headers_in(const fs::path& dir) {
  std::vector<fs::path> headers;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".hpp") headers.push_back(entry.path());
  std::sort(headers.begin(), headers.end());
  return headers;
}

std::vector<std::string> compiler_invocation() {
  std::vector<std::string> cmd{build_config::cxx_compiler};
  std::istringstream flags(build_config::cxx_flags);
  for (std::string flag; flags >> flag;) cmd.push_back(flag);
  for (const char* extra : {"-std=c++17", "-fno-fast-math"}) cmd.push_back(extra);
  return cmd;
}

namespace {

// the key of a build: a hash of everything it is built from, so a stale build is never reused;
// the command as it reads for a placeholder directory, so the key does not depend on where
std::string cache_key(const CachedBuild& build) {
  std::string material = fmt::format("eomgen {}\n", version);
  for (const auto& [name, content] : build.files) material += name + "\n" + content;
  for (const fs::path& dir : build.header_dirs)
    for (const fs::path& h : headers_in(dir)) material += h.filename().string() + "\n" + read_file(h);
  if (build.units)
    for (const std::vector<std::string>& unit : build.units("BUILD"))
      for (const std::string& part : unit) material += part + "\n";
  for (const std::string& part : build.command("BUILD")) material += part + "\n";
  return fmt::format("{}-{:016x}", build.key_name, content_hash(material));
}

}  // namespace

fs::path build_cached(const CachedBuild& build, const fs::path& cache) {
  const std::string key = cache_key(build);
  const fs::path directory = cache / key;
  const fs::path product = directory / build.product;
  std::error_code ec;
  if (fs::exists(product, ec)) {
    std::cerr << fmt::format("eomgen: using the cached build {}\n", directory.string());
    return product;
  }

  // built in a private directory, renamed into place when complete: a concurrent run or an
  // interrupted build never leaves a half-built program under the key
  fs::create_directories(cache, ec);
  if (ec) throw Error(fmt::format("cannot create the cache directory '{}': {}", cache.string(), ec.message()));
  const fs::path building = cache / fmt::format(".{}.{}.tmp", key, ::getpid());
  const auto discard_building = [&] {
    interruption::Hold hold;
    fs::remove_all(building, ec);
    interruption::forget(building.string());
  };
  {
    interruption::Hold hold;  // an interrupted run removes it, with the compiler's output
    fs::remove_all(building, ec);
    fs::create_directories(building, ec);
    if (ec) throw Error(fmt::format("cannot create '{}': {}", building.string(), ec.message()));
    interruption::remember(building.string(), true);
  }
  for (const auto& [name, content] : build.files) write_atomically((building / name).string(), content);
  const std::vector<std::string> cmd = build.command(building);
  std::cerr << fmt::format("eomgen: compiling {} with {} ...\n", build.what, cmd.front());
  const auto start = std::chrono::steady_clock::now();
  const auto failed = [&](int status, const fs::path& log) {
    const std::string output = read_file(log);
    discard_building();
    throw Error(fmt::format("compiling {} failed (exit status {}); this is a bug in eomgen or a broken compiler "
                            "setup. Compiler output:\n{}",
                            build.what, status, output.substr(0, 4000)));
  };
  if (build.units) {
    // all started before any is waited for; every started one is waited for, even when a later
    // one cannot start, so that no compiler outlives the build directory
    std::vector<std::pair<StartedProcess, fs::path>> running;
    std::optional<Error> not_started;
    const std::vector<std::vector<std::string>> units = build.units(building);
    for (std::size_t k = 0; k < units.size() && !not_started; ++k) {
      const fs::path log = building / (k == 0 ? std::string("compile.log") : fmt::format("compile-{}.log", k + 1));
      try {
        running.emplace_back(start_process(units[k], log.string()), log);
      } catch (const Error& e) {
        not_started = e;
      }
    }
    std::optional<std::pair<int, fs::path>> first_failure;
    for (const auto& [process, log] : running) {
      const int status = wait_for(process);
      if (status != 0 && !first_failure) first_failure.emplace(status, log);
    }
    if (not_started) {
      discard_building();
      throw *not_started;
    }
    if (first_failure) failed(first_failure->first, first_failure->second);
  }
  const fs::path log = building / (build.units ? "link.log" : "compile.log");
  const int status = run_process(cmd, log.string());
  if (status != 0) failed(status, log);
  std::cerr << fmt::format("eomgen: compiled in {:.1f} s, cached in {}\n",
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                           directory.string());
  {
    interruption::Hold hold;  // in place whole, or removed
    fs::rename(building, directory, ec);
    if (!ec) interruption::forget(building.string());
  }
  if (ec) {
    discard_building();  // another run finished the same build first: use its
    if (!fs::exists(product))
      throw Error(fmt::format("cannot move the build into '{}' ({}); delete that directory and run again",
                              directory.string(), ec.message()));
  }
  return product;
}

}  // namespace eomgen::tools
