// Atomic output: every file is written to a temporary beside its target and
// renamed over it only when complete, so a failure or an interruption never
// leaves a half-written output, never damages the previous one, and never
// leaves the temporary behind (SIGKILL and power loss excepted).
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace polydual {

// An output could not be written: "PATH: WHAT: REASON", REASON being the
// system's (strerror) when there is one ("No space left on device").
class WriteError : public std::runtime_error {
 public:
  WriteError(const std::filesystem::path& path, const std::string& what, std::error_code reason = {});
  const std::filesystem::path& path() const { return path_; }
  std::error_code reason() const { return reason_; }

 private:
  std::filesystem::path path_;
  std::error_code reason_;
};

// Calls write(stream) on a temporary file `path`.tmp.PID and renames it over
// `path` when write returns and every byte reached the file; an existing
// `path` keeps its permission bits. A `path` that is a symbolic link (to
// anything), a directory, a FIFO, a device or a socket is refused
// (WriteError): nothing but a regular file at `path` itself is ever replaced. The stream throws at the first failed write (WriteError
// with the system's reason) and, between chunks of about 1 MiB, when the user
// interrupted (Interrupted, see core/interrupt.h). On any exception (these, or
// one thrown by `write`) the temporary is removed, `path` is left as it was,
// and the exception propagates. `binary` is accepted for the callers' clarity:
// POSIX files have no text mode.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary = false);

// Replaces the directory `dir` as a whole: fill(tmp) writes into a fresh
// temporary directory `dir`.tmp.PID beside it, which is then swapped in (one
// renameat2 RENAME_EXCHANGE, or rename the old aside / the new in / the old
// away where the file system cannot exchange) and the old tree removed. On any
// failure either the old or the new tree is at `dir`, complete, and no
// temporary remains. Everything under an existing `dir` is deleted: pass only a
// directory that polydual owns (OUT/constant/polyMesh), never a user's folder.
// A `dir` that exists and is not a directory is refused (WriteError).
void write_directory_atomically(const std::filesystem::path& dir,
                                const std::function<void(const std::filesystem::path&)>& fill);

// Writes a new directory `dir` the same way (fill(tmp), then one rename) only
// if `dir` does not exist or is an empty directory; returns false, writing
// nothing, when it exists. For adding what a user may already have (a case's
// system/) without ever touching theirs.
bool write_directory_if_absent(const std::filesystem::path& dir,
                               const std::function<void(const std::filesystem::path&)>& fill);

namespace detail {
// The swap of write_directory_atomically without renameat2 (file systems that
// cannot exchange): `fresh` replaces the existing directory `dir`; exposed for
// the tests.
void replace_by_rename_aside(const std::filesystem::path& fresh, const std::filesystem::path& dir);
}  // namespace detail

}  // namespace polydual
