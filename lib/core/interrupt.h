// Interruption by the user (Ctrl-C, SIGTERM): the signal handlers only record
// the signal; the writers and long computations poll the record at points
// where stopping is clean (between output chunks, between sweeps) and throw
// Interrupted, so every temporary is removed on the way out and the command
// exits with 128 + signal. SIGKILL cannot be caught and is out of reach.
//
// A run that does not reach a poll point (Gmsh meshing, a system call that
// blocks) is ended by the watchdog: see start_interrupt_watchdog.
#pragma once
#include <filesystem>
#include <mutex>
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

// Installs the handlers (as above, except that every signal is recorded: the
// watchdog takes the second) and starts the watchdog thread: after the first
// signal the run has `grace_seconds` to stop by itself at a poll point; a
// second signal, or the grace running out, removes every registered
// temporary (ScopedTemporary) and ends the process at once with status
// 128 + signal, printing "polydual: interrupted". For the command's main,
// once, before any other thread starts.
void start_interrupt_watchdog(double grace_seconds);

// A temporary output the watchdog removes if it ends the process: a file, a
// directory tree, or a directory created for an output (removed only if
// empty). Registered for the object's life; release() once the temporary
// became the output (renamed) or was removed.
class ScopedTemporary {
 public:
  enum class Kind { File, Tree, EmptyDir };
  ScopedTemporary(std::filesystem::path path, Kind kind);
  ~ScopedTemporary() { release(); }
  ScopedTemporary(const ScopedTemporary&) = delete;
  ScopedTemporary& operator=(const ScopedTemporary&) = delete;
  void release();

 private:
  std::filesystem::path path_;
  bool registered_ = true;
};

// Holds the watchdog off while an output is committed: the caller checks the
// flag (throw_if_interrupted) and renames under the lock, so the process never
// ends between the two and no output appears after a recorded signal.
std::unique_lock<std::recursive_mutex> hold_off_watchdog();

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
