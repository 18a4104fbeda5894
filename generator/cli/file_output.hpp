#pragma once
// Output files that appear whole or not at all: a temporary file in the target's directory,
// renamed over the target once complete (rename is atomic within a file system).
#include <string>
#include <vector>

namespace eomgen::tools {

/// Writes `content` to `path` through a temporary file renamed over it. A symbolic link is
/// followed (the link stays); a device or FIFO (/dev/null, a pipe) is written in place.
/// \throws eomgen::Error if the file cannot be written; the target is then untouched
void write_atomically(const std::string& path, const std::string& content);

/// An output file of a run and the option that names it ("-o", "--plot").
struct OutputFile {
  std::string option;
  std::string path;  ///< empty: not written (standard output, or no plot)
};

/// The file a write to `path` replaces, absolute, with symbolic links followed (also a link whose
/// file does not exist yet) and "." and ".." resolved.
std::string written_file(const std::string& path);

/// Checks a run's output files before anything runs, so that no work is lost to a path that
/// cannot be written and no file to one that should not be: an output must not be the model
/// file (through a symbolic or a hard link too), a directory, or in a directory that does not
/// exist, and no two outputs may be the same file (the plot would replace the CSV). Nor may an
/// output be one of `other_inputs`, further files the run reads (`what` says what they are).
/// \throws UsageError naming the option
void check_output_files(const std::vector<OutputFile>& outputs, const std::string& model_path,
                        const std::vector<std::string>& other_inputs = {}, const std::string& what = {});

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
