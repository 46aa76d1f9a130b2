#include "io/output_guard.h"

#include <limits.h>
#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "core/file_type.h"

namespace polydual {

namespace fs = std::filesystem;

namespace {

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
  constexpr std::size_t kShown = 100;  // a name longer than this is shown by its start
  throw UsageError("output '" + (out.size() > kShown ? out.substr(0, kShown) + "..." : out) + "' " + why);
}

void check_not_an_input(std::span<const std::string> inputs, const std::string& out, OutputKind kind) {
  for (const std::string& in : inputs) {
    if (same_file(in, out)) refuse(out, "is the input '" + in + "'; choose another output name");
    // Replacing OUT/constant/polyMesh would delete an input inside it.
    if (kind == OutputKind::FoamCase && inside(in, fs::path(out) / "constant" / "polyMesh"))
      refuse(out, "holds the input '" + in + "' in constant/polyMesh, which the case replaces");
  }
}

// The name's last component must leave room for the temporary's suffix
// (".tmp.PID.N", at most 20 bytes) within the file system's NAME_MAX, so a
// long name is refused here and not by a raw system error mid-write.
constexpr std::size_t kTempSuffix = 20;

void check_name_length(const std::string& out) {
  const fs::path p(out);
  const fs::path parent = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  long name_max = ::pathconf(parent.c_str(), _PC_NAME_MAX);
  if (name_max <= 0) name_max = NAME_MAX;
  for (const fs::path& part : p) {
    const std::size_t n = part.native().size();
    if (n + kTempSuffix > std::size_t(name_max))
      refuse(out, "has a name component of " + std::to_string(n) + " bytes ('" + part.native().substr(0, 24) +
                      "...'); the file system allows " + std::to_string(name_max) + ", less " +
                      std::to_string(kTempSuffix) + " for the temporary name");
  }
  if (out.size() + kTempSuffix + 32 > PATH_MAX)
    refuse(out, "is " + std::to_string(out.size()) + " bytes long; the limit is " +
                                          std::to_string(PATH_MAX));
}

// A new output (file or case) goes into a directory that exists: a missing
// parent is refused for both kinds alike, never created (a typo in a path
// would otherwise create directories).
void check_parent(const std::string& out) {
  const fs::path parent = fs::path(out).parent_path();
  if (parent.empty()) return;
  const FileType t = file_type_followed(parent.string());
  if (t == FileType::Missing)
    refuse(out, "cannot be created: the directory '" + parent.string() + "' does not exist (create it first)");
  if (t != FileType::Directory)
    refuse(out, "cannot be created: '" + parent.string() + "' is " + describe_file_type(t) + ", not a directory");
}

// An existing output path must be what polydual writes in place of it: a
// regular file (`want` Regular) or a directory (a case). A link, to anything,
// is refused: a write through it would replace a file polydual did not
// write, wherever the link points.
void check_existing_kind(const std::string& out, FileType t, FileType want) {
  if (t == want) return;
  if (t == FileType::Symlink)
    refuse(out, "is a symbolic link (to '" + link_target(out) +
                    "'); polydual never writes through a link: remove it or give another name");
  if (t == FileType::Directory) refuse(out, "is a directory; a file is written here");
  if (want == FileType::Directory)
    refuse(out, std::string("exists and is ") + describe_file_type(t) + ", not a directory");
  refuse(out, std::string("is ") + describe_file_type(t) + "; polydual writes only regular files");
}

void check_file_target(const std::string& out, bool force, const std::string& extension) {
  const FileType t = file_type_no_follow(out);
  if (t == FileType::Missing) return check_parent(out);
  check_existing_kind(out, t, FileType::Regular);
  if (!force && !extension.empty() && fs::path(out).extension() != extension)
    refuse(out, "exists and is not a " + extension + " file; it would be replaced by one (--force to do so)");
}

}  // namespace

bool check_output_directory(const std::string& dir) {
  const FileType t = file_type_no_follow(dir);
  if (t == FileType::Missing) {
    check_parent(dir);
    return false;
  }
  check_existing_kind(dir, t, FileType::Directory);
  return true;
}

void check_case_directory(const std::string& case_dir, bool force) {
  std::error_code ec;
  const fs::path dir(case_dir);
  if (!check_output_directory(case_dir)) return;
  // The case's own directories are written into (constant/polyMesh replaced,
  // system/ added): a link among them would carry the write elsewhere.
  for (const char* sub : {"constant", "constant/polyMesh", "system"}) {
    const FileType st = file_type_no_follow((dir / sub).string());
    if (st == FileType::Symlink)
      refuse(case_dir, std::string("has a '") + sub + "' that is a symbolic link (to '" +
                           link_target((dir / sub).string()) +
                           "'); polydual writes only into the case's own directories (remove the link)");
    if (st != FileType::Missing && st != FileType::Directory)
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
  check_name_length(out);
  check_not_an_input(inputs, out, kind);
  if (kind == OutputKind::File) check_file_target(out, force, extension);
  else check_case_directory(out, force);
}

}  // namespace polydual
