#include "file_output.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "eomgen/base/error.hpp"
#include "interruption.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

namespace {

// Creates a new empty file next to `path` (O_EXCL: never someone else's) and returns its
// descriptor and name, registered for removal if the run is interrupted; the caller closes it
// and renames or removes it (discard_temporary).
int create_temporary(const std::string& path, std::string& temporary) {
  namespace fs = std::filesystem;
  interruption::Hold hold;
  const fs::path target(path);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  for (int attempt = 0;; ++attempt) {
    temporary = (directory / fmt::format(".{}.{}-{}.tmp", target.filename().string(), ::getpid(), attempt)).string();
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);  // 0666 & ~umask
    if (fd >= 0) {
      interruption::remember(temporary);
      return fd;
    }
    if (errno != EEXIST || attempt >= 100)
      throw Error(fmt::format("writing '{}': cannot create a file in '{}': {}", path, directory.string(),
                              std::strerror(errno)));
  }
}

// The file a rename should replace: a symbolic link is followed, so the link stays and the file
// it names gets the content (as any program writing through the link would do).
std::string resolve_links(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::is_symlink(fs::symlink_status(path, error))) return path;
  const fs::path resolved = fs::weakly_canonical(path, error);
  return error ? path : resolved.string();
}

// A device, FIFO or socket (`-o /dev/null`, `-o /dev/stdout`, a pipe): renaming a file over it
// would replace the special file itself, so it is written in place instead; there is nothing
// to be atomic about for a stream.
bool is_special(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  return !error && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
}

void write_all(int fd, const char* data, std::size_t size, const std::function<void(const char*)>& fail) {
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("write failed");
    done += static_cast<std::size_t>(n);
  }
}

void write_in_place(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw Error(fmt::format("writing '{}': cannot open it: {}", path, std::strerror(errno)));
  write_all(fd, content.data(), content.size(), [&](const char* what) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    throw Error(fmt::format("writing '{}': {}: {}", path, what, reason));
  });
  if (::close(fd) != 0) throw Error(fmt::format("writing '{}': close failed: {}", path, std::strerror(errno)));
}

void discard_temporary(const std::string& temporary) {
  interruption::Hold hold;
  ::unlink(temporary.c_str());
  interruption::forget(temporary);
}

// rename(2) of a registered temporary over `target`, as one step for an interruption
bool rename_temporary(const std::string& temporary, const std::string& target) {
  interruption::Hold hold;
  if (std::rename(temporary.c_str(), target.c_str()) != 0) return false;
  interruption::forget(temporary);
  return true;
}

}  // namespace

void write_atomically(const std::string& requested, const std::string& content) {
  const std::string path = resolve_links(requested);
  if (is_special(path)) return write_in_place(path, content);
  std::string temporary;
  int fd = create_temporary(path, temporary);
  const auto fail = [&](const std::string& what) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    discard_temporary(temporary);
    throw Error(fmt::format("writing '{}': {}: {}", requested, what, reason));
  };
  write_all(fd, content.data(), content.size(), fail);
  if (::fsync(fd) != 0) fail("fsync failed");
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) fail("close failed");
  if (!rename_temporary(temporary, path)) fail("cannot replace the file");
}

PendingFile::PendingFile(std::string target) : target_(resolve_links(target)) {
  ::close(create_temporary(target_, temporary_));
}

PendingFile::~PendingFile() {
  if (!committed_) discard_temporary(temporary_);
}

void PendingFile::commit() {
  if (is_special(target_)) {
    std::ifstream in(temporary_, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    write_in_place(target_, content.str());
    discard_temporary(temporary_);
    committed_ = true;
    return;
  }
  if (!rename_temporary(temporary_, target_))
    throw Error(fmt::format("writing '{}': cannot replace the file: {}", target_, std::strerror(errno)));
  committed_ = true;
}

void refuse_to_overwrite_input(const std::string& output, const std::string& input, const std::string& option) {
  namespace fs = std::filesystem;
  if (output.empty()) return;
  std::error_code ec;
  if (!fs::exists(output, ec) || !fs::equivalent(output, input, ec) || ec) return;
  throw UsageError(fmt::format("{}: '{}' is the model file '{}' (the same file); writing it would destroy the model, "
                               "so choose another output file",
                               option, output, input));
}

}  // namespace eomgen::tools
