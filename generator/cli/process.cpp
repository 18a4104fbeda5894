#include "process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "eomgen/base/error.hpp"
#include "interruption.hpp"

extern char** environ;

namespace eomgen::tools {

int run_process(const std::vector<std::string>& argv, const std::string& output_log) {
  return wait_for(start_process(argv, output_log));
}

StartedProcess start_process(const std::vector<std::string>& argv, const std::string& output_log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  // the signals eomgen blocks for its interruption thread are the child's as they were for eomgen
  const sigset_t mask = interruption::original_mask(), defaults = interruption::handled_signals();
  posix_spawnattr_setsigmask(&attributes, &mask);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  short flags = POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF;
  // a program whose output goes to a log (the compiler, gnuplot) has no use for the terminal:
  // it gets a process group of its own, which an interruption stops as a whole (the compiler's
  // own children too), and no standard input
  const bool own_group = !output_log.empty();
  if (own_group) {
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawnattr_setpgroup(&attributes, 0);
    flags |= POSIX_SPAWN_SETPGROUP;
  }
  posix_spawnattr_setflags(&attributes, flags);
  pid_t pid = 0;
  int spawned = 0;
  {
    interruption::Hold hold;  // started and registered at once: an interruption stops it
    spawned = posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), environ);
    if (spawned == 0) interruption::remember_child(pid, own_group);
  }
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) throw Error(fmt::format("cannot run '{}': {}", argv[0], std::strerror(spawned)));
  return {pid, argv[0]};
}

int wait_for(const StartedProcess& process) {
  const pid_t pid = process.pid;
  // waited for without reaping, then forgotten and reaped at once: until then its pid is its own
  siginfo_t ended{};
  while (::waitid(P_PID, static_cast<id_t>(pid), &ended, WEXITED | WNOWAIT) != 0)
    if (errno != EINTR) throw Error(fmt::format("waiting for '{}': {}", process.program, std::strerror(errno)));
  int status = 0;
  {
    interruption::Hold hold;
    interruption::forget_child(pid);
    while (::waitpid(pid, &status, 0) < 0)
      if (errno != EINTR) throw Error(fmt::format("waiting for '{}': {}", process.program, std::strerror(errno)));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

bool program_available(const std::string& program) {
  if (program.find('/') != std::string::npos) return ::access(program.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (::access(((dir.empty() ? std::string(".") : dir) + "/" + program).c_str(), X_OK) == 0) return true;
  return false;
}

}  // namespace eomgen::tools
