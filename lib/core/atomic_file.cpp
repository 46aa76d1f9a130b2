#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <streambuf>
#include <vector>

#include "core/file_type.h"
#include "core/interrupt.h"

namespace polydual {

namespace fs = std::filesystem;

namespace {

std::error_code last_error() { return {errno, std::system_category()}; }

std::string describe(const fs::path& path, const std::string& what, std::error_code reason) {
  std::string m = path.string() + ": " + what;
  if (reason) m += ": " + reason.message();
  return m;
}

// Bytes handed to one write(2) (at least; larger blocks pass through), and
// how often the interrupt flag is polled. 256 KiB: write(2)'s cost per call
// is then negligible (80 calls for a 20 MB file) and the buffer is small next
// to a 100k-tet mesh (it is alive at the write, the end of the memory peak).
constexpr std::size_t kChunk = std::size_t(256) << 10;

// An output stream buffer over a file descriptor that reports the system's
// reason for a failed write and polls the interrupt flag between chunks. It
// throws (WriteError, Interrupted) rather than returning eof: the ostream over
// it has badbit exceptions on, so the exception reaches the writer's caller
// as it was thrown and the writer stops at once.
class FileSink : public std::streambuf {
 public:
  FileSink(int fd, const fs::path& shown) : fd_(fd), shown_(shown), buf_(kChunk) { reset(); }
  // Writes what is buffered (the caller then closes the descriptor).
  void finish() { drain(); }

 protected:
  int_type overflow(int_type c) override {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n <= 0) return 0;  // an empty write may come with s == nullptr (empty vector data())
    const auto size = static_cast<std::size_t>(n);
    if (size > static_cast<std::size_t>(epptr() - pptr())) {
      drain();
      if (size >= buf_.size()) {  // large blocks go straight to the file
        put(s, size);
        return n;
      }
    }
    std::memcpy(pptr(), s, size);
    pbump(static_cast<int>(size));
    return n;
  }
  int sync() override {
    drain();
    return 0;
  }

 private:
  void reset() { setp(buf_.data(), buf_.data() + buf_.size()); }
  void drain() {
    put(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    reset();
  }
  void put(const char* p, std::size_t n) {
    while (n > 0) {
      throw_if_interrupted();
      const ssize_t w = ::write(fd_, p, std::min(n, kChunk));
      if (w < 0) {
        if (errno == EINTR) continue;
        throw WriteError(shown_, "write failed", last_error());
      }
      p += w;
      n -= static_cast<std::size_t>(w);
    }
  }

  int fd_;
  const fs::path& shown_;
  std::vector<char> buf_;
};

// Runs write(stream) with the stream on `fd`; every byte is in the file (or
// an exception thrown) when it returns.
void stream_to(int fd, const fs::path& shown, const std::function<void(std::ostream&)>& write) {
  FileSink sink(fd, shown);
  std::ostream os(&sink);
  os.exceptions(std::ios::badbit);
  write(os);
  sink.finish();
  if (!os) throw WriteError(shown, "write failed (stream error)");
}

// A fresh name "NAME.tmp.PID" (".N" appended while taken) beside `target`.
fs::path temp_name(const fs::path& target, const char* tag, int attempt) {
  std::string suffix = ".";
  suffix.append(tag).append(".").append(std::to_string(::getpid()));
  if (attempt > 0) suffix.append(".").append(std::to_string(attempt));
  fs::path p = target;
  p += suffix;
  return p;
}

// Creates the temporary file exclusively; returns its descriptor.
int create_temp_file(const fs::path& target, const fs::path& shown, fs::path& tmp) {
  for (int attempt = 0;; ++attempt) {
    tmp = temp_name(target, "tmp", attempt);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST || attempt > 100)
      throw WriteError(shown, "cannot open for writing", last_error());
  }
}

fs::path create_temp_dir(const fs::path& target) {
  for (int attempt = 0;; ++attempt) {
    fs::path tmp = temp_name(target, "tmp", attempt);
    if (::mkdir(tmp.c_str(), 0777) == 0) return tmp;
    if (errno != EEXIST || attempt > 100)
      throw WriteError(target, "cannot create a directory beside it", last_error());
  }
}

// rename(2) variants of renameat2; false with errno = EINVAL/ENOSYS when the
// file system does not support the flag.
bool rename_with(const fs::path& from, const fs::path& to, unsigned flags) {
  return ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), flags) == 0;
}
bool unsupported(int err) { return err == EINVAL || err == ENOSYS || err == ENOTSUP; }

}  // namespace

WriteError::WriteError(const fs::path& path, const std::string& what, std::error_code reason)
    : std::runtime_error(describe(path, what, reason)), path_(path), reason_(reason) {}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write,
                           bool /*binary*/) {
  throw_if_interrupted();
  // The path itself, never what a link names: the temporary is created beside
  // `path` and renamed onto `path`, so no file elsewhere can be replaced. An
  // existing link or special file (FIFO, device, socket) is refused: opening a
  // FIFO would block, and writing a device in place is not atomic. Should the
  // path turn into a link after this check, the rename replaces the link.
  struct stat st;
  const bool existed = ::lstat(path.c_str(), &st) == 0;
  if (existed && !S_ISREG(st.st_mode)) {
    const FileType type = file_type_of_mode(st.st_mode);
    std::string what = std::string("is ") + describe_file_type(type);
    if (type == FileType::Symlink) what += " (to '" + link_target(path) + "'); polydual never writes through a link";
    else if (type != FileType::Directory) what += "; polydual writes only regular files";
    throw WriteError(path, what);
  }
  fs::path tmp;
  int fd = create_temp_file(path, path, tmp);
  ScopedTemporary registered(tmp, ScopedTemporary::Kind::File);
  try {
    if (existed && ::fchmod(fd, st.st_mode & 07777) != 0)
      throw WriteError(path, "cannot keep the permissions", last_error());
    stream_to(fd, path, write);
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) throw WriteError(path, "write failed", last_error());
    const auto commit = hold_off_watchdog();
    throw_if_interrupted();  // the last moment the old file can still be kept
    if (!rename_with(tmp, path, 0)) throw WriteError(path, "cannot replace", last_error());
    registered.release();
  } catch (...) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
}

void detail::replace_by_rename_aside(const fs::path& fresh, const fs::path& dir) {
  fs::path old;
  for (int attempt = 0;; ++attempt) {
    old = temp_name(dir, "old", attempt);
    if (!fs::exists(fs::symlink_status(old))) break;
    if (attempt > 100) throw WriteError(dir, "no free name to move the old directory aside");
  }
  if (!rename_with(dir, old, 0)) throw WriteError(dir, "cannot move the old directory aside", last_error());
  if (!rename_with(fresh, dir, 0)) {
    const std::error_code reason = last_error();
    rename_with(old, dir, 0);  // put the old one back
    throw WriteError(dir, "cannot replace", reason);
  }
  std::error_code ec;
  fs::remove_all(old, ec);  // the new tree is in place; a failure here only leaves garbage
}

void write_directory_atomically(const fs::path& dir, const std::function<void(const fs::path&)>& fill) {
  throw_if_interrupted();
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(dir, ec);
  const bool existed = fs::exists(st);
  if (fs::is_symlink(st))
    throw WriteError(dir, "is a symbolic link (to '" + link_target(dir) + "'); polydual never writes through a link");
  if (existed && !fs::is_directory(st)) throw WriteError(dir, "exists and is not a directory");
  const fs::path tmp = create_temp_dir(dir);
  ScopedTemporary registered(tmp, ScopedTemporary::Kind::Tree);
  try {
    fill(tmp);
    const auto commit = hold_off_watchdog();
    throw_if_interrupted();  // the last moment the old tree can still be kept
    if (!existed) {
      if (!rename_with(tmp, dir, RENAME_NOREPLACE) && !(unsupported(errno) && rename_with(tmp, dir, 0)))
        throw WriteError(dir, "cannot create", last_error());
    } else if (rename_with(tmp, dir, RENAME_EXCHANGE)) {
      fs::remove_all(tmp, ec);  // tmp now holds the old tree
    } else if (unsupported(errno)) {
      detail::replace_by_rename_aside(tmp, dir);
    } else {
      throw WriteError(dir, "cannot replace", last_error());
    }
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

namespace {

// Renames `from` to `to` unless `to` exists and holds something (false then).
bool rename_if_absent(const fs::path& from, const fs::path& to) {
  if (rename_with(from, to, RENAME_NOREPLACE)) return true;
  int err = errno;
  if (unsupported(err)) {
    if (fs::exists(fs::symlink_status(to))) err = EEXIST;
    else if (rename_with(from, to, 0)) return true;
    else err = errno;
  }
  std::error_code ec;
  if (err == EEXIST && fs::is_directory(fs::symlink_status(to)) && fs::is_empty(to, ec)) {
    if (rename_with(from, to, 0)) return true;  // an empty directory holds nothing to keep
    err = errno;
  }
  if (err == EEXIST || err == ENOTEMPTY) return false;
  throw WriteError(to, "cannot create", {err, std::system_category()});
}

}  // namespace

bool write_directory_if_absent(const fs::path& dir, const std::function<void(const fs::path&)>& fill) {
  throw_if_interrupted();
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir, ec)) && !(fs::is_directory(fs::symlink_status(dir)) && fs::is_empty(dir, ec)))
    return false;
  const fs::path tmp = create_temp_dir(dir);
  ScopedTemporary registered(tmp, ScopedTemporary::Kind::Tree);
  try {
    fill(tmp);
    const auto commit = hold_off_watchdog();
    throw_if_interrupted();
    const bool placed = rename_if_absent(tmp, dir);
    if (!placed) fs::remove_all(tmp, ec);
    return placed;
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace polydual
