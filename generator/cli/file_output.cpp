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
// it names gets the content (as any program writing through the link would do). A link whose
// file does not exist yet is followed too (weakly_canonical alone would stop at it).
std::string resolve_links(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path resolved(path);
  for (int hop = 0; hop < 40 && fs::is_symlink(fs::symlink_status(resolved, error)); ++hop) {
    const fs::path target = fs::read_symlink(resolved, error);
    if (error) return path;
    resolved = target.is_absolute() ? target : resolved.parent_path() / target;
  }
  if (resolved == fs::path(path)) return path;
  const fs::path canonical = fs::weakly_canonical(resolved, error);
  return error ? path : canonical.string();
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

namespace {

// whether `a` and `b` name one file: the same existing file (through links, hard ones too), or
// the same file to be (the same path once symbolic links and "." and ".." are resolved)
bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  return written_file(a) == written_file(b);
}

void check_output_file(const OutputFile& output, const std::string& model_path) {
  namespace fs = std::filesystem;
  const std::string& path = output.path;
  std::error_code ec;
  if (fs::exists(path, ec) && fs::equivalent(path, model_path, ec) && !ec)
    throw UsageError(fmt::format("{}: '{}' is the model file '{}' (the same file); writing it would destroy the "
                                 "model, so choose another output file",
                                 output.option, path, model_path));
  if (fs::is_directory(path, ec))
    throw UsageError(fmt::format("{}: '{}' is a directory; give the name of a file", output.option, path));
  // the directory a rename into place needs (of the file a symbolic link names)
  const fs::path target(resolve_links(path));
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, ec))
    throw UsageError(fmt::format("{}: cannot write '{}': the directory '{}' does not exist", output.option, path,
                                 directory.string()));
  if (::access(directory.c_str(), W_OK) != 0 && !is_special(target.string()))
    throw UsageError(fmt::format("{}: cannot write '{}': no permission to create files in '{}'", output.option, path,
                                 directory.string()));
}

}  // namespace

std::string written_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path absolute = fs::absolute(resolve_links(path), ec);
  if (ec) return path;
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return (ec ? absolute : canonical).string();
}

void check_output_files(const std::vector<OutputFile>& outputs, const std::string& model_path,
                        const std::vector<std::string>& other_inputs, const std::string& what) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    check_output_file(outputs[i], model_path);
    for (const std::string& input : other_inputs)
      if (same_file(outputs[i].path, input))
        throw UsageError(fmt::format("{}: '{}' is '{}', one of {} this run reads; writing it would destroy it, so "
                                     "choose another output file",
                                     outputs[i].option, outputs[i].path, input, what));
    for (std::size_t k = 0; k < i; ++k)
      if (!outputs[k].path.empty() && same_file(outputs[k].path, outputs[i].path))
        throw UsageError(fmt::format("{}: '{}' is the same file as {} '{}'; each output needs a file of its own",
                                     outputs[i].option, outputs[i].path, outputs[k].option, outputs[k].path));
  }
}

}  // namespace eomgen::tools
