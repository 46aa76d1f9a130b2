#include "core/atomic_file.h"

#include <stdexcept>
#include <unistd.h>

namespace polydual {

namespace fs = std::filesystem;

static fs::path temp_beside(const fs::path& path) {
  fs::path p = path;
  p += ".tmp." + std::to_string(::getpid());
  return p;
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write,
                           bool binary) {
  const fs::path tmp = temp_beside(path);
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
      if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
      write(out);
      out.flush();
      if (!out) throw std::runtime_error(path.string() + ": write failed");
    }
    fs::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void write_directory_atomically(const fs::path& dir,
                                const std::function<void(const fs::path&)>& fill) {
  const fs::path tmp = temp_beside(dir);
  std::error_code ec;
  fs::remove_all(tmp, ec);
  try {
    fs::create_directories(tmp);
    fill(tmp);
    if (fs::exists(dir)) fs::remove_all(dir);
    fs::rename(tmp, dir);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace polydual
