#pragma once
// Programs eomgen compiles from generated code (`simulate`'s simulation program, `python`'s
// module), built once per content into a cache directory and reused: where the sources they are
// compiled with are, and the build itself.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace eomgen::tools {

/// The cache directory: \p option (--cache-dir) if given, else $EOMGEN_CACHE_DIR, else
/// $XDG_CACHE_HOME/eomgen, else ~/.cache/eomgen.
/// \throws eomgen::Error if none of them is set
std::filesystem::path cache_root(const std::string& option);

/// A directory of sources that generated code is compiled with: next to an installed eomgen (a
/// path relative to its binary's directory), else in the source tree; \p marker is a file it
/// must hold.
std::optional<std::filesystem::path> find_sources(const std::filesystem::path& installed,
                                                  const std::filesystem::path& source,
                                                  const std::filesystem::path& marker);

/// The runtime headers (the directory holding eomrt/): $EOMGEN_RUNTIME_INCLUDE_DIR, else next to
/// an installed eomgen, else the source tree. \throws eomgen::Error if none holds them
std::filesystem::path runtime_include_dir();

/// The headers (.hpp) directly in \p dir, sorted.
std::vector<std::filesystem::path> headers_in(const std::filesystem::path& dir);

/// The configured compiler and flags (those eomgen was built with, without debug information),
/// in C++17, never with fast math (it would break the NaN checks that make failures loud, and
/// the reproducibility of the results): the start of every command that compiles generated code.
std::vector<std::string> compiler_invocation();

/// A file's whole content.
std::string read_file(const std::filesystem::path& path);

/// One program to build in the cache.
struct CachedBuild {
  std::string what;      ///< for messages: "the simulation of cart_pole"
  std::string key_name;  ///< the cache entry's name before its hash: "cart_pole", "cart_pole-python"
  /// the files written into the build directory (name, content)
  std::vector<std::pair<std::string, std::string>> files;
  /// directories whose headers the build reads: their contents are part of the key
  std::vector<std::filesystem::path> header_dirs;
  /// the compiler's command line for a build in the given directory
  std::function<std::vector<std::string>(const std::filesystem::path& directory)> command;
  /// if set, commands run at the same time before `command` (the translation units of one
  /// program, compiled on as many cores as there are; `command` then links them)
  std::function<std::vector<std::vector<std::string>>(const std::filesystem::path& directory)> units;
  std::string product;  ///< the file the command writes into the directory
};

/// The product of \p build: the cached one when the cache holds a build of the same content
/// (everything the key hashes: eomgen's version, the files, the headers, the command), else
/// built in a private directory and moved into place whole, so a concurrent or interrupted run
/// never leaves a half-built entry. Says on stderr which it does.
/// \throws eomgen::Error when the compiler fails (its output included) or the cache is unwritable
std::filesystem::path build_cached(const CachedBuild& build, const std::filesystem::path& cache);

}  // namespace eomgen::tools
