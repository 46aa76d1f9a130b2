#include "io/file_bytes.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace polydual::io {

std::string read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "cannot open file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open file");
  // One read into a buffer of the file's size: a stream copy grows its
  // buffer by doubling (a 45 MB file: 64 MB of buffer, each doubling a copy).
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::string bytes(ec ? 0 : std::size_t(size), '\0');
  in.read(bytes.data(), std::streamsize(bytes.size()));
  bytes.resize(std::size_t(in.gcount()));
  // Whatever follows (a file that grew since its size was read).
  char buf[1 << 16];
  while (in && (in.read(buf, sizeof buf) || in.gcount() > 0)) bytes.append(buf, std::size_t(in.gcount()));
  if (in.bad()) throw InputError(path, "", "cannot read file");
  return bytes;
}

bool file_exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

}  // namespace polydual::io
