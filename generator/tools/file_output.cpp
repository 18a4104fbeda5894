#include "file_output.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "eomgen/error.hpp"

namespace eomgen::tools {

namespace {

// Creates a new empty file next to `path` (O_EXCL: never someone else's) and returns its
// descriptor and name; the caller closes or unlinks it.
int create_temporary(const std::string& path, std::string& temporary) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  for (int attempt = 0;; ++attempt) {
    temporary = (directory / fmt::format(".{}.{}-{}.tmp", target.filename().string(), ::getpid(), attempt)).string();
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);  // 0666 & ~umask
    if (fd >= 0) return fd;
    if (errno != EEXIST || attempt >= 100)
      throw Error(fmt::format("writing '{}': cannot create a file in '{}': {}", path, directory.string(),
                              std::strerror(errno)));
  }
}

}  // namespace

void write_atomically(const std::string& path, const std::string& content) {
  std::string temporary;
  int fd = create_temporary(path, temporary);
  const auto fail = [&](const std::string& what) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    ::unlink(temporary.c_str());
    throw Error(fmt::format("writing '{}': {}: {}", path, what, reason));
  };
  for (std::size_t done = 0; done < content.size();) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("write failed");
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("fsync failed");
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) fail("close failed");
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail("cannot replace the file");
}

PendingFile::PendingFile(std::string target) : target_(std::move(target)) {
  ::close(create_temporary(target_, temporary_));
}

PendingFile::~PendingFile() {
  if (!committed_) ::unlink(temporary_.c_str());
}

void PendingFile::commit() {
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0)
    throw Error(fmt::format("writing '{}': cannot replace the file: {}", target_, std::strerror(errno)));
  committed_ = true;
}

}  // namespace eomgen::tools
