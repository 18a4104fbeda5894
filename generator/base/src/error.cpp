#include "eomgen/base/error.hpp"

#include <fmt/format.h>

namespace eomgen {
namespace {

// __FILE__ is the path the compiler was given, and with a shared compiler cache it may be the
// path of another checkout that compiled the same source: name the file from the repository
// root, so the message is the same in every checkout and build
std::string from_repository_root(const char* file) {
  const std::string path = std::string("/") + file;
  for (const char* root : {"/tests/generator/", "/generator/", "/tests/"}) {
    const std::size_t at = path.rfind(root);
    if (at != std::string::npos) return path.substr(at + 1);
  }
  return file;
}

}  // namespace

InternalError::InternalError(const char* file, int line, const std::string& message)
    : std::logic_error(fmt::format("internal error at {}:{}: {}; this is a bug in eomgen, please report it",
                                   from_repository_root(file), line, message)),
      file_(from_repository_root(file)),
      line_(line),
      message_(message) {}

namespace detail {

void internal_error(const char* file, int line, const std::string& message) {
  throw InternalError(file, line, message);
}

void demand_failed(const char* file, int line, const char* condition, const std::string& message) {
  throw InternalError(file, line, fmt::format("{} (failed: {})", message, condition));
}

}  // namespace detail
}  // namespace eomgen
