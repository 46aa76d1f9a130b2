#include "core/interrupt.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

namespace polydual {

namespace {

// The handler may only touch lock-free atomics (async-signal-safe); an int
// atomic is also safe to read from the worker threads.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free");

extern "C" void record_signal(int signal) { g_signal.store(signal, std::memory_order_relaxed); }

std::string describe(int signal) {
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : nullptr;
  return "interrupted (" + (name ? std::string(name) : "signal " + std::to_string(signal)) + ")";
}

}  // namespace

Interrupted::Interrupted(int signal) : std::runtime_error(describe(signal)), signal_(signal) {}

void install_interrupt_handlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  // SA_RESTART: system calls of the libraries we call (Gmsh, TBB, iostreams)
  // resume rather than fail with EINTR; the writers poll the flag themselves.
  // SA_RESETHAND: the second signal takes the default action (terminates).
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  for (int sig : {SIGINT, SIGTERM}) {
    // A signal ignored at startup stays ignored (the shell's `cmd &`, nohup).
    struct sigaction old;
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
}

bool interrupted() noexcept { return g_signal.load(std::memory_order_relaxed) != 0; }

int interrupt_signal() noexcept { return g_signal.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
  if (const int s = interrupt_signal()) throw Interrupted(s);
}

void request_interrupt(int signal) noexcept { g_signal.store(signal, std::memory_order_relaxed); }

void clear_interrupt() noexcept { g_signal.store(0, std::memory_order_relaxed); }

}  // namespace polydual
