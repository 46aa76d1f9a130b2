#include "core/file_type.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <vector>

namespace polydual {

FileType file_type_of_mode(mode_t mode) {
  if (S_ISREG(mode)) return FileType::Regular;
  if (S_ISDIR(mode)) return FileType::Directory;
  if (S_ISLNK(mode)) return FileType::Symlink;
  if (S_ISFIFO(mode)) return FileType::Fifo;
  if (S_ISCHR(mode)) return FileType::CharDevice;
  if (S_ISBLK(mode)) return FileType::BlockDevice;
  if (S_ISSOCK(mode)) return FileType::Socket;
  return FileType::Unknown;
}

FileType file_type_no_follow(const std::string& path, int* error) {
  struct stat st;
  if (error) *error = 0;
  if (::lstat(path.c_str(), &st) == 0) return file_type_of_mode(st.st_mode);
  if (error && errno != ENOENT) *error = errno;
  return FileType::Missing;
}

FileType file_type_followed(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 ? file_type_of_mode(st.st_mode) : FileType::Missing;
}

const char* describe_file_type(FileType type) {
  switch (type) {
    case FileType::Missing: return "missing";
    case FileType::Regular: return "a regular file";
    case FileType::Directory: return "a directory";
    case FileType::Symlink: return "a symbolic link";
    case FileType::Fifo: return "a FIFO (named pipe)";
    case FileType::CharDevice: return "a character device";
    case FileType::BlockDevice: return "a block device";
    case FileType::Socket: return "a socket";
    case FileType::Unknown: break;
  }
  return "not a regular file";
}

std::string link_target(const std::string& path) {
  std::vector<char> buf(4096);
  const ssize_t n = ::readlink(path.c_str(), buf.data(), buf.size());
  return n > 0 ? std::string(buf.data(), std::size_t(n)) : std::string();
}

}  // namespace polydual
