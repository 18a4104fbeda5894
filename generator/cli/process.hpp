#pragma once
// Running another program (the compiler, the compiled simulation, gnuplot) without a shell:
// arguments go to the program as they are, so no path or name can be reinterpreted as a
// command.
#include <sys/types.h>

#include <string>
#include <vector>

namespace eomgen::tools {

/// Runs argv[0] (searched on PATH) with the arguments argv[1..] and waits for it.
/// \param[in] argv        program and arguments
/// \param[in] output_log  if not empty, the program's standard output and error go to this
///                        file instead of ours
/// The program is registered with interruption.hpp while it runs: an interrupted eomgen stops it
/// (with `output_log`, its whole process group: it gets one of its own, and no standard input).
/// \return its exit status; 128 + the signal number if a signal ended it
/// \throws eomgen::Error if the program cannot be started (e.g. it is not installed)
int run_process(const std::vector<std::string>& argv, const std::string& output_log = {});

/// A program start_process started, for wait_for.
struct StartedProcess {
  pid_t pid = 0;
  std::string program;  ///< argv[0], for messages
};

/// Starts argv as run_process does, without waiting: several run at once (the translation units
/// of one program on as many cores). Every started process must be waited for with wait_for.
/// \throws eomgen::Error if the program cannot be started
StartedProcess start_process(const std::vector<std::string>& argv, const std::string& output_log = {});

/// Waits for a started process. \return its exit status; 128 + the signal number if a signal
/// ended it
int wait_for(const StartedProcess& process);

/// \return whether `program` is found on PATH (or is an executable path)
bool program_available(const std::string& program);

}  // namespace eomgen::tools
