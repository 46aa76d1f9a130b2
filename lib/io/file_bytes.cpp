#include "io/file_bytes.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace polydual::io {

std::string read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "cannot open file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read file");
  return std::move(s).str();
}

bool file_exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

}  // namespace polydual::io
