#pragma once
// Output files that appear whole or not at all: a temporary file in the target's directory,
// renamed over the target once complete (rename is atomic within a file system).
#include <string>

namespace eomgen::tools {

/// Writes `content` to `path` through a temporary file renamed over it. A symbolic link is
/// followed (the link stays); a device or FIFO (/dev/null, a pipe) is written in place.
/// \throws eomgen::Error if the file cannot be written; the target is then untouched
void write_atomically(const std::string& path, const std::string& content);

/// Refuses an output that is an input of the run: `output` naming the same file as `input`
/// (through a symbolic or a hard link too), which writing would destroy.
/// \throws UsageError naming `option`; nothing when `output` is empty or does not exist yet
void refuse_to_overwrite_input(const std::string& output, const std::string& input, const std::string& option);

/// A temporary file next to `target`, for a file another program writes (the simulation's
/// CSV, gnuplot's plot): commit() renames it over the target; otherwise it is removed.
class PendingFile {
 public:
  /// \throws eomgen::Error if the temporary file cannot be created
  explicit PendingFile(std::string target);
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;
  ~PendingFile();

  /// where the other program writes
  const std::string& path() const { return temporary_; }
  /// \throws eomgen::Error if the rename fails
  void commit();

 private:
  std::string target_;
  std::string temporary_;
  bool committed_ = false;
};

}  // namespace eomgen::tools
