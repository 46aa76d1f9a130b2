#include "core/interrupt.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace polydual {

namespace fs = std::filesystem;

namespace {

// The handler may only touch lock-free atomics and write(2) (async-signal-
// safe); an int atomic is also safe to read from the worker threads.
std::atomic<int> g_signal{0};
std::atomic<int> g_wake_fd{-1};  // the watchdog's pipe, -1 without a watchdog
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free");

extern "C" void record_signal(int signal) {
  int expected = 0;
  g_signal.compare_exchange_strong(expected, signal, std::memory_order_relaxed);  // the first one stays
  const int fd = g_wake_fd.load(std::memory_order_relaxed);
  if (fd >= 0) {
    const int saved = errno;
    const char byte = char(signal);
    [[maybe_unused]] const ssize_t n = ::write(fd, &byte, 1);
    errno = saved;
  }
}

std::string describe(int signal) {
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : nullptr;
  return "interrupted (" + (name ? std::string(name) : "signal " + std::to_string(signal)) + ")";
}

void install(int flags) {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = flags;
  for (int sig : {SIGINT, SIGTERM}) {
    // A signal ignored at startup stays ignored (the shell's `cmd &`, nohup).
    struct sigaction old;
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
}

// The registered temporaries, in registration order (a case directory before
// the files in it); one lock for the registry and for hold_off_watchdog.
struct Registry {
  std::recursive_mutex mutex;
  std::vector<std::pair<fs::path, ScopedTemporary::Kind>> entries;
};
Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: the watchdog may use it during exit
  return *r;
}

// Removes every registered temporary, newest first (files inside a created
// directory before the directory). Called with the registry locked.
void remove_temporaries(Registry& r) {
  for (auto it = r.entries.rbegin(); it != r.entries.rend(); ++it) {
    std::error_code ec;
    switch (it->second) {
      case ScopedTemporary::Kind::File: ::unlink(it->first.c_str()); break;
      case ScopedTemporary::Kind::Tree: fs::remove_all(it->first, ec); break;
      case ScopedTemporary::Kind::EmptyDir: ::rmdir(it->first.c_str()); break;
    }
  }
}

[[noreturn]] void end_process(int signal) {
  Registry& r = registry();
  r.mutex.lock();  // waits for a commit in progress; never unlocked: the process ends here
  remove_temporaries(r);
  static const char kMessage[] = "polydual: interrupted\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  ::_exit(128 + signal);
}

// Reads the signals the handler forwards; ends the process at the second one
// or when the grace after the first has run out.
void watch(int fd, double grace_seconds) {
  using Clock = std::chrono::steady_clock;
  int signals = 0, first = 0;
  Clock::time_point deadline{};
  for (;;) {
    int timeout_ms = -1;
    if (signals > 0) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) end_process(first);
      timeout_ms = int(left);
    }
    struct pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) continue;  // timeout (checked above) or EINTR
    char buf[16];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) continue;
    if (signals == 0) {
      first = buf[0];
      deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace_seconds));
    }
    signals += int(n);
    if (signals >= 2) end_process(first);
  }
}

}  // namespace

Interrupted::Interrupted(int signal) : std::runtime_error(describe(signal)), signal_(signal) {}

// SA_RESTART: system calls of the libraries we call (Gmsh, TBB, iostreams)
// resume rather than fail with EINTR; the writers poll the flag themselves.
// SA_RESETHAND (without a watchdog): the second signal takes the default
// action (terminates).
void install_interrupt_handlers() { install(SA_RESTART | SA_RESETHAND); }

void start_interrupt_watchdog(double grace_seconds) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return install_interrupt_handlers();  // no watchdog: still interruptible
  ::fcntl(fds[1], F_SETFL, O_NONBLOCK);  // the handler never blocks on a full pipe
  g_wake_fd.store(fds[1], std::memory_order_relaxed);
  std::thread(watch, fds[0], grace_seconds).detach();
  install(SA_RESTART);
}

ScopedTemporary::ScopedTemporary(fs::path path, Kind kind) : path_(std::move(path)) {
  Registry& r = registry();
  std::lock_guard<std::recursive_mutex> lock(r.mutex);
  r.entries.emplace_back(path_, kind);
}

void ScopedTemporary::release() {
  if (!registered_) return;
  registered_ = false;
  Registry& r = registry();
  std::lock_guard<std::recursive_mutex> lock(r.mutex);
  for (auto it = r.entries.rbegin(); it != r.entries.rend(); ++it)
    if (it->first == path_) {
      r.entries.erase(std::next(it).base());
      break;
    }
}

std::unique_lock<std::recursive_mutex> hold_off_watchdog() {
  return std::unique_lock<std::recursive_mutex>(registry().mutex);
}

bool interrupted() noexcept { return g_signal.load(std::memory_order_relaxed) != 0; }

int interrupt_signal() noexcept { return g_signal.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
  if (const int s = interrupt_signal()) throw Interrupted(s);
}

void request_interrupt(int signal) noexcept { g_signal.store(signal, std::memory_order_relaxed); }

void clear_interrupt() noexcept { g_signal.store(0, std::memory_order_relaxed); }

}  // namespace polydual
