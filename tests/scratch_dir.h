// The scratch directory of a test program: <tmp>/polydual_<program>_<pid>,
// made on first use and removed with everything in it when the program
// exits normally. ctest runs each test in a process of its own, so two tests
// never share one, even under `ctest -j`, and no run leaves files behind
// (set POLYDUAL_KEEP_SCRATCH=1 to keep them for a look: the path is printed).
#pragma once
#include <errno.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace polydual::test {

class ScratchRoot {
 public:
  ScratchRoot()
      : path_(std::filesystem::temp_directory_path() /
              ("polydual_" + std::string(program_invocation_short_name) + "_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchRoot() {
    const char* keep = std::getenv("POLYDUAL_KEEP_SCRATCH");
    if (keep && std::string(keep) == "1") {
      std::fprintf(stderr, "scratch kept: %s\n", path_.c_str());
      return;
    }
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchRoot(const ScratchRoot&) = delete;
  ScratchRoot& operator=(const ScratchRoot&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The directory (made on first use); `sub` non-empty: a subdirectory of it,
// made too.
inline std::filesystem::path scratch_dir(const std::string& sub = "") {
  static const ScratchRoot root;
  if (sub.empty()) return root.path();
  const std::filesystem::path d = root.path() / sub;
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace polydual::test
