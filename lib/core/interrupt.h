// Interruption by the user (Ctrl-C, SIGTERM): the signal handlers only record
// the signal; the writers and long computations poll the record at points
// where stopping is clean (between output chunks, between sweeps) and throw
// Interrupted, so every temporary is removed on the way out and the command
// exits with 128 + signal. SIGKILL cannot be caught and is out of reach.
#pragma once
#include <stdexcept>

namespace polydual {

// Thrown by throw_if_interrupted(); signal() is SIGINT or SIGTERM.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }
  // The conventional exit status of a process stopped by the signal.
  int exit_status() const { return 128 + signal_; }

 private:
  int signal_;
};

// Installs the SIGINT and SIGTERM handlers (for the command's main). The first
// signal is recorded; the handler then reverts to the default action, so a
// second Ctrl-C stops a computation that does not poll at once. A signal that
// is ignored when the process starts (a shell's background job) stays ignored.
void install_interrupt_handlers();

// True once SIGINT or SIGTERM arrived. Cheap (one relaxed atomic load): fit
// for inner loops of the optimiser. Safe from any thread.
bool interrupted() noexcept;
// The recorded signal, 0 if none.
int interrupt_signal() noexcept;
// Throws Interrupted if a signal was recorded.
void throw_if_interrupted();

// Records `signal` as the handler would (programmatic cancellation, tests).
void request_interrupt(int signal) noexcept;
// Forgets a recorded signal (tests; a long-running host between jobs).
void clear_interrupt() noexcept;

}  // namespace polydual
