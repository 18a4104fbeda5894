#include "interruption.hpp"

#include <pthread.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace eomgen::tools::interruption {

namespace {

struct Temporary {
  std::string path;
  bool directory;
};

struct Child {
  pid_t pid;
  bool own_group;
};

// never destroyed: the interruption thread may still use it while main() returns
struct Registry {
  std::recursive_mutex mutex;
  std::vector<Temporary> temporaries;
  std::vector<Child> children;
  sigset_t original_mask;
  sigset_t handled;
};

Registry& registry() {
  static Registry* r = [] {
    auto* created = new Registry;
    sigemptyset(&created->original_mask);
    sigemptyset(&created->handled);
    return created;
  }();
  return *r;
}

void say(const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

// whether the child has ended, without reaping it (the thread that started it reaps it)
bool ended(pid_t pid) {
  siginfo_t info{};
  if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0) return errno == ECHILD;
  return info.si_pid != 0;
}

// SIGTERM to each child (its group if it has one), up to two seconds to end, then SIGKILL
void stop_children(const std::vector<Child>& children) {
  const auto send = [](const Child& c, int sig) { ::kill(c.own_group ? -c.pid : c.pid, sig); };
  for (const Child& c : children) send(c, SIGTERM);
  for (int wait = 0; wait < 200; ++wait) {
    if (std::all_of(children.begin(), children.end(), [](const Child& c) { return ended(c.pid); })) return;
    ::usleep(10000);
  }
  for (const Child& c : children) send(c, SIGKILL);
  for (const Child& c : children)
    while (!ended(c.pid)) ::usleep(10000);
}

[[noreturn]] void end_by(int sig) {
  Registry& r = registry();
  r.mutex.lock();  // never unlocked: nothing starts, is renamed into place or reaped any more
  stop_children(r.children);
  for (const Temporary& t : r.temporaries) {
    std::error_code ec;
    if (t.directory)
      std::filesystem::remove_all(t.path, ec);
    else
      ::unlink(t.path.c_str());
  }
  say(std::string("\neomgen: interrupted by ") + (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP") +
      (r.temporaries.empty() ? "" : "; its temporary files are removed, no partial output is left") + "\n");
  // die by the signal itself, as the shell expects of an interrupted program
  ::signal(sig, SIG_DFL);
  sigset_t only;
  sigemptyset(&only);
  sigaddset(&only, sig);
  ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);
}

}  // namespace

void install() {
  Registry& r = registry();
  ::pthread_sigmask(SIG_SETMASK, nullptr, &r.original_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (::sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&r.handled, sig);
  }
  bool any = false;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) any = any || sigismember(&r.handled, sig) == 1;
  if (!any) return;
  ::pthread_sigmask(SIG_BLOCK, &r.handled, nullptr);
  std::thread([] {
    const sigset_t handled = registry().handled;
    for (;;) {
      int sig = 0;
      if (::sigwait(&handled, &sig) == 0) end_by(sig);
    }
  }).detach();
}

Hold::Hold() { registry().mutex.lock(); }
Hold::~Hold() { registry().mutex.unlock(); }

void remember(const std::string& path, bool directory) {
  Hold hold;
  registry().temporaries.push_back({path, directory});
}

void forget(const std::string& path) {
  Hold hold;
  auto& t = registry().temporaries;
  t.erase(std::remove_if(t.begin(), t.end(), [&](const Temporary& x) { return x.path == path; }), t.end());
}

void remember_child(pid_t pid, bool own_group) {
  Hold hold;
  registry().children.push_back({pid, own_group});
}

void forget_child(pid_t pid) {
  Hold hold;
  auto& c = registry().children;
  c.erase(std::remove_if(c.begin(), c.end(), [&](const Child& x) { return x.pid == pid; }), c.end());
}

sigset_t original_mask() { return registry().original_mask; }
sigset_t handled_signals() { return registry().handled; }

}  // namespace eomgen::tools::interruption
