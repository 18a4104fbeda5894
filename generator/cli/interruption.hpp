#pragma once
// Interrupted runs (Ctrl-C, SIGTERM, a closed terminal) leave no temporary file and no child
// process behind. The signals are blocked in every thread and taken by one thread of their own
// (sigwait), which may do anything a thread may: nothing runs inside a signal handler.
//
// Temporary files and directories and child processes are registered here while they exist.
// On a signal the thread takes the registry's lock (and keeps it: nothing new starts), stops the
// children and waits for them, removes the temporaries, says so on stderr and ends the process
// by the same signal, so the shell sees the conventional status (130 for SIGINT, 143 for
// SIGTERM). Whatever was already renamed into place is complete and stays.
#include <sys/types.h>

#include <mutex>
#include <signal.h>
#include <string>

namespace eomgen::tools::interruption {

/// Blocks SIGINT, SIGTERM and SIGHUP and starts the thread that handles them. A signal ignored
/// when eomgen started (nohup, a background job of a script) stays ignored. Call once, at the
/// start of main(), before any other thread or child exists.
void install();

/// While one is alive, an interruption waits. Hold one across every step that must not be cut
/// in two: creating a temporary and registering it; renaming it into place (or removing it) and
/// forgetting it; starting a child and registering it; forgetting a child and reaping it.
class Hold {
 public:
  Hold();
  ~Hold();
  Hold(const Hold&) = delete;
  Hold& operator=(const Hold&) = delete;
};

/// A temporary file (or, with `directory`, a directory and all it holds) to remove if the run
/// is interrupted, until forgotten.
void remember(const std::string& path, bool directory = false);
void forget(const std::string& path);

/// A child process to stop if the run is interrupted (with `own_group`, its whole process
/// group: the compiler's own children too), until forgotten. It must not be reaped before it is
/// forgotten, so that its pid cannot name another process meanwhile.
void remember_child(pid_t pid, bool own_group);
void forget_child(pid_t pid);

/// What a child must start with: the signal mask eomgen started with, and the signals the
/// interruption thread takes back at their default action.
sigset_t original_mask();
sigset_t handled_signals();

}  // namespace eomgen::tools::interruption
