#include "mesh_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <system_error>
#include <vector>

namespace eomgen::tools {
namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
  return s;
}

// the places a package's directory may be, in the order they are tried
std::vector<fs::path> package_candidates(const std::string& package, const fs::path& rest,
                                         const fs::path& model_directory, const std::string& ros_package_path) {
  std::vector<fs::path> out;
  const auto in = [&](const fs::path& dir) {
    if (dir.filename() == package) out.push_back(dir / rest);
    out.push_back(dir / package / rest);
  };
  for (std::size_t at = 0; at <= ros_package_path.size();) {
    const std::size_t colon = std::min(ros_package_path.find(':', at), ros_package_path.size());
    if (colon > at) in(fs::path(ros_package_path.substr(at, colon - at)).lexically_normal());
    at = colon + 1;
  }
  fs::path dir = fs::absolute(model_directory).lexically_normal();
  if (dir.has_filename() == false && dir != dir.root_path()) dir = dir.parent_path();  // a trailing '/'
  while (true) {
    in(dir);
    if (dir == dir.root_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  return out;
}

MeshFileLookup first_file(const std::vector<fs::path>& candidates) {
  for (const fs::path& p : candidates)
    if (is_file(p)) return {p, ""};
  std::string searched;
  for (std::size_t k = 0; k < candidates.size() && k < 6; ++k) searched += (k ? ", " : "") + candidates[k].string();
  if (candidates.size() > 6) searched += fmt::format(" and {} more", candidates.size() - 6);
  return {std::nullopt, fmt::format("not found (searched {})", searched)};
}

}  // namespace

MeshFileLookup find_mesh_file(const std::string& file, const fs::path& model_directory,
                              const std::string& ros_package_path) {
  const std::string extension = lower(fs::path(file).extension().string());
  if (extension != ".stl")
    return {std::nullopt, extension.empty() ? "not STL (the name has no extension; only STL files are drawn)"
                                            : fmt::format("not STL (a {} file; only STL files are drawn)", extension)};
  const std::size_t scheme = file.find("://");
  if (scheme != std::string::npos) {
    const std::string name = lower(file.substr(0, scheme));
    const std::string rest = file.substr(scheme + 3);
    if (name == "package") {
      const std::size_t slash = rest.find('/');
      if (slash == std::string::npos || slash == 0)
        return {std::nullopt, "not found (expected package://PACKAGE/PATH)"};
      return first_file(package_candidates(rest.substr(0, slash), fs::path(rest.substr(slash + 1)), model_directory,
                                           ros_package_path));
    }
    if (name == "file") {
      if (!fs::path(rest).is_absolute()) return {std::nullopt, "not found (file:// needs an absolute path)"};
      return first_file({fs::path(rest)});
    }
    return {std::nullopt, fmt::format("not read (eomgen reads package://, file:// and paths, not {}://)", name)};
  }
  const fs::path path(file);
  return first_file({path.is_absolute() ? path : model_directory / path});
}

}  // namespace eomgen::tools
