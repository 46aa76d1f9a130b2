#include "io/output_guard.h"

#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace polydual {

namespace fs = std::filesystem;

namespace {

bool exists_no_follow(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

// True when `a` and `b` name the same existing file (st_dev + st_ino).
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// True when the existing file `p` is `dir` or lies below it (its real path,
// every symbolic link and ".." resolved, has `dir` as an ancestor).
bool inside(const fs::path& p, const fs::path& dir) {
  std::error_code ec;
  const fs::path real = fs::canonical(p, ec);
  if (ec || !fs::is_directory(dir, ec)) return false;
  for (fs::path q = real; !q.empty(); q = q.parent_path()) {
    if (same_file(q, dir)) return true;
    if (q == q.root_path()) break;
  }
  return false;
}

void refuse(const std::string& out, const std::string& why) {
  throw UsageError("output '" + out + "' " + why);
}

void check_not_an_input(std::span<const std::string> inputs, const std::string& out, OutputKind kind) {
  for (const std::string& in : inputs) {
    if (same_file(in, out)) refuse(out, "is the input '" + in + "'; choose another output name");
    // Replacing OUT/constant/polyMesh would delete an input inside it.
    if (kind == OutputKind::FoamCase && inside(in, fs::path(out) / "constant" / "polyMesh"))
      refuse(out, "holds the input '" + in + "' in constant/polyMesh, which the case replaces");
  }
}

void check_file_target(const std::string& out, bool force, const std::string& extension) {
  std::error_code ec;
  if (!exists_no_follow(out)) {
    const fs::path parent = fs::path(out).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
      refuse(out, "cannot be created: '" + parent.string() + "' is not a directory");
    return;
  }
  const fs::file_status st = fs::status(out, ec);
  if (!fs::exists(st)) refuse(out, "is a dangling symbolic link");
  if (fs::is_directory(st)) refuse(out, "is a directory; a file is written here");
  if (fs::is_character_file(st) || fs::is_fifo(st)) return;  // /dev/null, a pipe
  if (!fs::is_regular_file(st)) refuse(out, "exists and is not a regular file");
  if (!force && !extension.empty() && fs::path(out).extension() != extension)
    refuse(out, "exists and is not a " + extension + " file; it would be replaced by one (--force to do so)");
}

}  // namespace

void check_case_directory(const std::string& case_dir, bool force) {
  std::error_code ec;
  const fs::path dir(case_dir);
  if (!exists_no_follow(dir)) return;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) refuse(case_dir, "is a dangling symbolic link");
  if (!fs::is_directory(st)) refuse(case_dir, "exists and is not a directory; an OpenFOAM case is written here");
  for (const char* sub : {"constant", "constant/polyMesh", "system"}) {
    const fs::path p = dir / sub;
    if (exists_no_follow(p) && !fs::is_directory(fs::status(p, ec)))
      refuse(case_dir, std::string("has a '") + sub + "' that is not a directory");
  }
  const bool is_case = fs::is_directory(dir / "constant", ec) || fs::is_directory(dir / "system", ec);
  if (is_case || force) return;
  if (!fs::is_empty(dir, ec) || ec)
    refuse(case_dir,
           "is a directory that is neither empty nor an OpenFOAM case (no constant/ or system/); "
           "--force writes constant/polyMesh and system/ into it, leaving its other files");
}

void check_output_target(std::span<const std::string> inputs, const std::string& out, OutputKind kind,
                         bool force, const std::string& extension) {
  if (out.empty()) throw UsageError("empty output name");
  check_not_an_input(inputs, out, kind);
  if (kind == OutputKind::File) check_file_target(out, force, extension);
  else check_case_directory(out, force);
}

}  // namespace polydual
