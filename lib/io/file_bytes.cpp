#include "io/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>

#include "core/error.h"
#include "core/file_type.h"

namespace polydual::io {
namespace {

constexpr std::uint64_t kFirstChunk = std::uint64_t(1) << 16;  // 64 KiB: every format's header fits
constexpr std::uint64_t kMaxChunk = std::uint64_t(1) << 26;    // 64 MiB

std::string errno_text(int err) { return std::strerror(err); }

[[noreturn]] void refuse(const std::string& path, const std::string& why) { throw InputError(path, "", why); }

std::string only_regular(FileType type) {
  return std::string(describe_file_type(type)) + "; polydual reads only regular files";
}

// Opens a regular file without blocking; its size in `size`.
int open_regular(const std::string& path, std::uint64_t& size) {
  require_regular_file(path);
  // O_NONBLOCK: should the path have become a FIFO since it was checked, the
  // open returns at once instead of waiting for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) refuse(path, "cannot open file (" + errno_text(errno) + ")");
  struct stat st;
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    refuse(path, "cannot open file (" + errno_text(err) + ")");
  }
  if (!S_ISREG(st.st_mode)) {  // replaced since it was checked
    ::close(fd);
    refuse(path, "is " + only_regular(file_type_of_mode(st.st_mode)));
  }
  size = static_cast<std::uint64_t>(st.st_size);
  return fd;
}

// pread until `n` bytes or the end of the file; the number read.
std::size_t read_at(int fd, char* to, std::size_t n, std::uint64_t offset, const std::string& path) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t r = ::pread(fd, to + done, n - done, static_cast<off_t>(offset + done));
    if (r == 0) break;
    if (r < 0) {
      if (errno == EINTR) continue;
      throw InputError(path, "byte " + std::to_string(offset + done), "cannot read file (" + errno_text(errno) + ")");
    }
    done += static_cast<std::size_t>(r);
  }
  return done;
}

}  // namespace

void require_regular_file(const std::string& path) {
  int err = 0;
  FileType type = file_type_no_follow(path, &err);
  if (type == FileType::Missing) refuse(path, "cannot open file (" + errno_text(err ? err : ENOENT) + ")");
  if (type == FileType::Regular) return;
  if (type != FileType::Symlink) refuse(path, "is " + only_regular(type));
  const std::string to = " (to '" + link_target(path) + "')";
  type = file_type_followed(path);
  if (type == FileType::Regular) return;
  if (type != FileType::Missing) refuse(path, "is a symbolic link" + to + " to " + only_regular(type));
  // The target cannot be reached: missing (a dangling link) or a loop.
  if (::access(path.c_str(), F_OK) != 0 && errno != ENOENT)
    refuse(path, "cannot open file (" + errno_text(errno) + ")" + to);
  refuse(path, "is a dangling symbolic link" + to);
}

InputFile::InputFile(const std::string& path) : path_(path) {
  fd_ = open_regular(path, size_);
  // Uninitialised: its pages become resident only as they are loaded, so the
  // memory follows what the reader consumed, not what the file's size claims.
  storage_.reset(new (std::nothrow) char[std::max<std::uint64_t>(size_, 1)]);
  if (!storage_) {
    ::close(fd_);
    refuse(path, "file of " + std::to_string(size_) + " bytes is too large to read");
  }
  data_ = storage_.get();
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string_view InputFile::load_to(std::uint64_t end) {
  if (end > size_) {
    check_not_longer();
    end = size_;
  }
  if (end > loaded_) {
    const std::uint64_t ahead = std::clamp<std::uint64_t>(loaded_, kFirstChunk, kMaxChunk);
    read_into(std::min(size_, std::max(end, loaded_ + ahead)));
  }
  return loaded();
}

void InputFile::read_into(std::uint64_t end) {
  const std::size_t got = read_at(fd_, data_ + loaded_, end - loaded_, loaded_, path_);
  loaded_ += got;
  if (loaded_ < end) size_ = loaded_;  // the file was shortened since it was opened
}

// A reader asked past the size the file had at open: it is complete unless
// something was appended meanwhile, which would be read only in part.
void InputFile::check_not_longer() {
  if (checked_end_ || loaded_ < size_) return;
  checked_end_ = true;
  char c;
  if (read_at(fd_, &c, 1, size_, path_) != 0)
    throw InputError(path_, "byte " + std::to_string(size_),
                     "the file grew while it was read (is it still being written?)");
}

std::string InputFile::tail(std::size_t n) const {
  const std::uint64_t from = size_ > n ? size_ - n : 0;
  std::string out(static_cast<std::size_t>(size_ - from), '\0');
  out.resize(read_at(fd_, out.data(), out.size(), from, path_));
  return out;
}

std::string read_file_bytes(const std::string& path) {
  std::uint64_t size = 0;
  const int fd = open_regular(path, size);
  // One read into a buffer of the file's size (a stream copy would double
  // its buffer, copying each time), then whatever was appended meanwhile.
  std::string bytes;
  try {
    bytes.resize(static_cast<std::size_t>(size));
    bytes.resize(read_at(fd, bytes.data(), bytes.size(), 0, path));
    char buf[1 << 16];
    while (std::size_t n = read_at(fd, buf, sizeof buf, bytes.size(), path)) bytes.append(buf, n);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return bytes;
}

std::size_t line_of(std::string_view bytes, std::size_t pos) {
  pos = std::min(pos, bytes.size());
  return 1 + static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + static_cast<long>(pos), '\n'));
}

void fail_nul_byte(const std::string& source, std::string_view bytes, std::size_t pos) {
  throw InputError(source, "line " + std::to_string(line_of(bytes, pos)), kNulInText);
}

}  // namespace polydual::io
