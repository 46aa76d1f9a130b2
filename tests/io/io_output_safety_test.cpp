// Nothing the user owns is lost (lib/core/atomic_file, lib/core/interrupt,
// lib/io/output_guard, lib/io/foam_writer): outputs that are inputs or foreign
// directories are refused, an OpenFOAM case only ever has its polyMesh
// replaced, failures and interruptions leave the previous output and no
// temporary, and write errors carry the system's reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "io/foam_writer.h"
#include "io/output_guard.h"
#include "run_command.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path scratch_root() {
  return fs::temp_directory_path() / ("polydual_output_safety_" + std::to_string(::getpid()));
}
struct ScratchCleanup : ::testing::Environment {
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(scratch_root(), ec);
  }
};
[[maybe_unused]] const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

// A fresh, empty directory for one test.
fs::path scratch(const std::string& name) {
  const fs::path p = scratch_root() / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void put(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// Every entry under `dir` (relative path -> contents, "<dir>" for directories,
// "-> target" for symbolic links): compared before and after to prove that
// nothing was touched.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = fs::relative(it->path(), dir).string();
    if (it->is_symlink()) out[rel] = "-> " + fs::read_symlink(it->path()).string();
    else if (it->is_directory()) out[rel] = "<dir>";
    else if (!it->is_regular_file()) out[rel] = "<special>";  // never opened: a FIFO would block
    else out[rel] = slurp(it->path());
  }
  return out;
}

// Names anywhere under `dir` that look like a temporary of ours.
std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") != std::string::npos || name.find(".old.") != std::string::npos)
      out.push_back(e.path().string());
  }
  return out;
}

// An n*n*n block of hexes of edge `h` with integer-ish coordinates (short
// lines, so the file sizes are predictable): one material, six external patches.
PolyMesh hex_block(int n, double h) {
  PolyMesh m;
  auto pid = [&](int i, int j, int k) { return PointId(i + (n + 1) * (j + (n + 1) * k)); };
  auto cid = [&](int i, int j, int k) { return CellId(i + n * (j + n * k)); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.add_point({h * i, h * j, h * k}, ModelRef{3, 1});
  std::vector<std::vector<HalfFace>> cells(static_cast<std::size_t>(n * n * n));
  auto add = [&](int axis, int s, int a, int b) {
    auto at = [&](int da, int db) {
      std::array<int, 3> q{};
      q[axis] = s;
      q[(axis + 1) % 3] = a + da;
      q[(axis + 2) % 3] = b + db;
      return pid(q[0], q[1], q[2]);
    };
    std::vector<PointId> loop{at(0, 0), at(1, 0), at(1, 1), at(0, 1)};  // +axis normal
    std::array<int, 3> below{}, above{};
    below[axis] = s - 1;
    above[axis] = s;
    below[(axis + 1) % 3] = above[(axis + 1) % 3] = a;
    below[(axis + 2) % 3] = above[(axis + 2) % 3] = b;
    if (s == 0 || s == n) {
      const bool low = s == 0;
      const CellId c = low ? cid(above[0], above[1], above[2]) : cid(below[0], below[1], below[2]);
      if (low) std::reverse(loop.begin(), loop.end());
      const FaceId f = m.add_face(loop, c, CellId::invalid(), FaceKind::External, 2 * axis + (low ? 1 : 2));
      cells[c.idx].push_back(HalfFace(f, 0));
      return;
    }
    const CellId c0 = cid(below[0], below[1], below[2]), c1 = cid(above[0], above[1], above[2]);
    const FaceId f = m.add_face(loop, c0, c1, FaceKind::Interior, 0);
    cells[c0.idx].push_back(HalfFace(f, 0));
    cells[c1.idx].push_back(HalfFace(f, 1));
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int s = 0; s <= n; ++s)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) add(axis, s, a, b);
  for (std::size_t c = 0; c < cells.size(); ++c) m.add_cell(cells[c], 1, VertexId(c));
  return m;
}

const char* const kPolyMeshFiles[] = {"points", "faces", "owner", "neighbour", "boundary", "cellZones", "faceZones"};

std::map<std::string, std::string> poly_mesh_files(const fs::path& case_dir) {
  std::map<std::string, std::string> out;
  for (const char* f : kPolyMeshFiles) out[f] = slurp(case_dir / "constant" / "polyMesh" / f);
  return out;
}

// Lowers the largest file this process may write (a write beyond it fails
// with EFBIG: a full disk that needs neither root nor a mount), restored on
// destruction.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &old_);
    rlimit r = old_;
    r.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &r);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_;
  void (*old_handler_)(int);
};

// Clears a recorded interrupt whatever the test did.
struct InterruptReset {
  ~InterruptReset() { clear_interrupt(); }
};

// ---------------------------------------------------------------------------
// Interruption flag

TEST(Interrupt, HandlersRecordTheSignalAndThrowIfInterruptedReportsIt) {
  InterruptReset reset;
  for (int sig : {SIGINT, SIGTERM}) {
    clear_interrupt();
    install_interrupt_handlers();
    EXPECT_FALSE(interrupted());
    EXPECT_NO_THROW(throw_if_interrupted());
    ASSERT_EQ(std::raise(sig), 0);  // the process survives: the handler only records
    EXPECT_TRUE(interrupted());
    EXPECT_EQ(interrupt_signal(), sig);
    try {
      throw_if_interrupted();
      ADD_FAILURE() << "no Interrupted";
    } catch (const Interrupted& e) {
      EXPECT_EQ(e.signal(), sig);
      EXPECT_EQ(e.exit_status(), 128 + sig);
      EXPECT_THAT(e.what(), HasSubstr("interrupted"));
    }
  }
  // The handler reverts to the default after one signal (a second Ctrl-C
  // kills a computation that does not poll).
  struct sigaction now;
  sigaction(SIGTERM, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_DFL);
  // An ignored signal stays ignored.
  std::signal(SIGINT, SIG_IGN);
  install_interrupt_handlers();
  sigaction(SIGINT, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_IGN);
  sigaction(SIGTERM, nullptr, &now);
  EXPECT_NE(now.sa_handler, SIG_DFL);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

// ---------------------------------------------------------------------------
// write_file_atomically

TEST(AtomicFile, WritesAndReplacesOnlyOnSuccess) {
  const fs::path d = scratch("atomic_replace");
  const fs::path f = d / "out.vtu";
  write_file_atomically(f, [](std::ostream& os) { os << "first\n"; });
  EXPECT_EQ(slurp(f), "first\n");
  write_file_atomically(f, [](std::ostream& os) { os << "second " << 42 << '\n'; });
  EXPECT_EQ(slurp(f), "second 42\n");
  // A callback that throws after writing: the old file stays, no temporary.
  EXPECT_THROW(write_file_atomically(f, [](std::ostream& os) {
                 os << std::string(3 << 20, 'x');  // beyond one chunk: bytes did reach the temporary
                 throw std::runtime_error("injected");
               }),
               std::runtime_error);
  EXPECT_EQ(slurp(f), "second 42\n");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
  EXPECT_EQ(snapshot(d).size(), 1u);
}

TEST(AtomicFile, LargeOutputsArriveWhole) {
  const fs::path f = scratch("atomic_large") / "big.bin";
  std::string expected;
  write_file_atomically(f, [&](std::ostream& os) {
    for (int i = 0; i < 300000; ++i) {  // small pieces across many chunks...
      const std::string s = std::to_string(i) + ' ';
      os << s;
      expected += s;
    }
    const std::string block(5 << 20, 'b');  // ...and one block larger than a chunk
    os.write(block.data(), static_cast<std::streamsize>(block.size()));
    expected += block;
    os.put('\n');
    expected += '\n';
  }, true);
  EXPECT_EQ(slurp(f), expected);
}

TEST(AtomicFile, KeepsPermissionBitsAndSymbolicLinks) {
  const fs::path d = scratch("atomic_perms");
  const fs::path f = d / "out.vtu";
  put(f, "old");
  ASSERT_EQ(::chmod(f.c_str(), 0640), 0);
  write_file_atomically(f, [](std::ostream& os) { os << "new"; });
  struct stat st;
  ASSERT_EQ(::stat(f.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  ASSERT_EQ(::chmod(f.c_str(), 0604), 0);
  write_file_atomically(f, [](std::ostream& os) { os << "newer"; });
  ASSERT_EQ(::stat(f.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0604u);

  // A new file gets the usual 0666 & ~umask.
  const mode_t mask = ::umask(022);
  write_file_atomically(d / "fresh.vtu", [](std::ostream& os) { os << "x"; });
  ::umask(mask);
  ASSERT_EQ(::stat((d / "fresh.vtu").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0644u);

}

TEST(AtomicFile, NeverWritesThroughALinkOrIntoASpecialFile) {
  const fs::path d = scratch("atomic_links");
  put(d / "victim.txt", "the user's file");
  fs::create_symlink("victim.txt", d / "link.vtu");
  fs::create_symlink("/etc/hostname", d / "system.vtu");
  fs::create_symlink("nowhere", d / "dangling.vtu");
  ASSERT_EQ(::mkfifo((d / "pipe.vtu").c_str(), 0644), 0);
  const auto before = snapshot(d);
  const std::pair<const char*, const char*> cases[] = {{"link.vtu", "is a symbolic link (to 'victim.txt')"},
                                                       {"system.vtu", "is a symbolic link"},
                                                       {"dangling.vtu", "is a symbolic link (to 'nowhere')"},
                                                       {"pipe.vtu", "is a FIFO"}};
  for (const auto& [name, why] : cases) {
    try {
      write_file_atomically(d / name, [](std::ostream& os) { os << "output"; });
      ADD_FAILURE() << name << " was written";
    } catch (const WriteError& e) {
      EXPECT_THAT(e.what(), HasSubstr(why)) << e.what();
    }
  }
  EXPECT_EQ(snapshot(d), before);  // the links, their targets and the FIFO as they were
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
  for (const char* dev : {"/dev/null", "/dev/full"})
    EXPECT_THROW(write_file_atomically(dev, [](std::ostream& os) { os << "x"; }), WriteError) << dev;
  // A link as a directory output: refused, its target untouched.
  fs::create_directories(d / "real");
  fs::create_symlink("real", d / "dirlink");
  EXPECT_THROW(write_directory_atomically(d / "dirlink", [](const fs::path& tmp) { put(tmp / "x", "x"); }),
               WriteError);
  EXPECT_TRUE(fs::is_empty(d / "real"));
}

TEST(AtomicFile, InterruptStopsTheWriteBetweenChunksAndKeepsTheOldFile) {
  InterruptReset reset;
  const fs::path d = scratch("atomic_interrupt");
  const fs::path f = d / "out.vtu";
  put(f, "previous");
  bool finished = false;
  EXPECT_THROW(write_file_atomically(f, [&](std::ostream& os) {
                 os << std::string(2 << 20, 'a');
                 request_interrupt(SIGTERM);  // as the handler would, mid-write
                 for (int i = 0; i < 64; ++i) os << std::string(1 << 20, 'b');
                 finished = true;
               }),
               Interrupted);
  EXPECT_FALSE(finished) << "the stream must stop at the next chunk, not at the end";
  EXPECT_EQ(slurp(f), "previous");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
  // Interrupted before it starts: nothing is created at all.
  EXPECT_THROW(write_file_atomically(d / "new.vtu", [](std::ostream& os) { os << "x"; }), Interrupted);
  EXPECT_FALSE(fs::exists(d / "new.vtu"));
  // Interrupted after the last byte reached the file, before the rename: the
  // old file stays.
  clear_interrupt();
  EXPECT_THROW(write_file_atomically(f, [](std::ostream& os) {
                 os << "complete" << std::flush;
                 request_interrupt(SIGINT);
               }),
               Interrupted);
  EXPECT_EQ(slurp(f), "previous");
  EXPECT_EQ(snapshot(d).size(), 1u);
}

TEST(AtomicFile, WriteErrorsCarryThePathAndTheSystemReason) {
  const fs::path d = scratch("atomic_errors");
  put(d / "plain", "a file");
  // Under a file: ENOTDIR when the temporary is created.
  try {
    write_file_atomically(d / "plain" / "out.vtu", [](std::ostream& os) { os << "x"; });
    ADD_FAILURE() << "no error";
  } catch (const WriteError& e) {
    EXPECT_THAT(e.what(), HasSubstr((d / "plain" / "out.vtu").string()));
    EXPECT_THAT(e.what(), HasSubstr("Not a directory"));
    EXPECT_EQ(e.reason(), std::error_code(ENOTDIR, std::system_category()));
  }
  // /proc refuses new files (even to root).
  try {
    write_file_atomically("/proc/polydual_out.vtu", [](std::ostream& os) { os << "x"; });
    ADD_FAILURE() << "no error";
  } catch (const WriteError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/proc/polydual_out.vtu: cannot open for writing: "));
    EXPECT_TRUE(e.reason()) << e.what();
  }
  // A device is not written at all (no in-place writes: not atomic).
  try {
    write_file_atomically("/dev/full", [](std::ostream& os) { os << std::string(3 << 20, 'x'); });
    ADD_FAILURE() << "no error";
  } catch (const WriteError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/dev/full: is a character device; polydual writes only regular files"));
  }
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  // The file system full in the middle of a file (a file size limit: EFBIG).
  put(d / "out.vtu", "previous");
  {
    FileSizeLimit limit(100000);
    try {
      write_file_atomically(d / "out.vtu", [](std::ostream& os) { os << std::string(3 << 20, 'x'); });
      ADD_FAILURE() << "no error";
    } catch (const WriteError& e) {
      EXPECT_THAT(e.what(), HasSubstr((d / "out.vtu").string() + ": write failed: File too large"));
    }
  }
  EXPECT_EQ(slurp(d / "out.vtu"), "previous");
  // A directory is never replaced by a file.
  fs::create_directories(d / "dir.vtu");
  EXPECT_THROW(write_file_atomically(d / "dir.vtu", [](std::ostream& os) { os << "x"; }), WriteError);
  EXPECT_TRUE(fs::is_directory(d / "dir.vtu"));
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

// ---------------------------------------------------------------------------
// write_directory_atomically and friends

TEST(AtomicDirectory, ReplacesOnlyOnSuccessAndLeavesNoTemporary) {
  const fs::path d = scratch("atomic_dir");
  const fs::path mesh = d / "polyMesh";
  auto fill = [](const std::string& tag) {
    return [tag](const fs::path& tmp) {
      for (const char* f : {"points", "faces"}) put(tmp / f, tag + f);
    };
  };
  write_directory_atomically(mesh, fill("one:"));
  EXPECT_EQ(slurp(mesh / "faces"), "one:faces");
  write_directory_atomically(mesh, fill("two:"));
  EXPECT_EQ(slurp(mesh / "points"), "two:points");
  EXPECT_EQ(snapshot(d).size(), 3u);  // polyMesh, its two files: the old tree is gone
  // A fill that fails half way: the previous tree stays whole.
  EXPECT_THROW(write_directory_atomically(mesh, [](const fs::path& tmp) {
                 put(tmp / "points", "three:points");
                 throw std::runtime_error("injected");
               }),
               std::runtime_error);
  EXPECT_EQ(slurp(mesh / "points"), "two:points");
  EXPECT_EQ(slurp(mesh / "faces"), "two:faces");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
  // A file where the directory should be is not deleted.
  put(d / "notadir", "keep");
  EXPECT_THROW(write_directory_atomically(d / "notadir", fill("x")), WriteError);
  EXPECT_EQ(slurp(d / "notadir"), "keep");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

TEST(AtomicDirectory, RenameAsideFallbackSwapsAndRestores) {
  const fs::path d = scratch("atomic_aside");
  put(d / "mesh" / "points", "old");
  put(d / "fresh" / "points", "new");
  detail::replace_by_rename_aside(d / "fresh", d / "mesh");
  EXPECT_EQ(slurp(d / "mesh" / "points"), "new");
  EXPECT_FALSE(fs::exists(d / "fresh"));
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
  // The new one cannot be renamed in (it does not exist): the old one is put back.
  EXPECT_THROW(detail::replace_by_rename_aside(d / "missing", d / "mesh"), WriteError);
  EXPECT_EQ(slurp(d / "mesh" / "points"), "new");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

TEST(AtomicDirectory, WriteIfAbsentNeverTouchesAnExistingDirectory) {
  const fs::path d = scratch("atomic_absent");
  auto fill = [](const fs::path& tmp) { put(tmp / "controlDict", "ours"); };
  EXPECT_TRUE(write_directory_if_absent(d / "system", fill));
  EXPECT_EQ(slurp(d / "system" / "controlDict"), "ours");
  put(d / "user" / "controlDict", "theirs");
  EXPECT_FALSE(write_directory_if_absent(d / "user", fill));
  EXPECT_EQ(slurp(d / "user" / "controlDict"), "theirs");
  fs::create_directories(d / "empty");
  EXPECT_TRUE(write_directory_if_absent(d / "empty", fill));
  EXPECT_EQ(slurp(d / "empty" / "controlDict"), "ours");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

// ---------------------------------------------------------------------------
// check_output_target

void expect_refused(const std::vector<std::string>& in, const fs::path& out, OutputKind kind, bool force,
                    const std::string& why, const std::string& ext = ".vtu") {
  try {
    check_output_target(in, out.string(), kind, force, ext);
    ADD_FAILURE() << out << " was accepted";
  } catch (const UsageError& e) {
    // The path is named in full, or its first 100 characters when longer.
    const std::string shown = out.string();
    EXPECT_THAT(e.what(), HasSubstr(shown.size() > 100 ? shown.substr(0, 100) + "..." : shown)) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(why)) << e.what();
  }
}

TEST(OutputGuard, AnInputIsNeverTheOutput) {
  const fs::path d = scratch("guard_input");
  const fs::path in = d / "in.msh";
  put(in, "$MeshFormat");
  fs::create_directories(d / "sub");
  fs::create_symlink(in, d / "link.vtu");
  fs::create_hard_link(in, d / "hard.vtu");
  const std::vector<std::string> inputs{in.string()};
  for (const fs::path& out : {in, d / "link.vtu", d / "hard.vtu", d / "sub" / ".." / "in.msh"})
    for (bool force : {false, true}) expect_refused(inputs, out, OutputKind::File, force, "is the input");
  // The input among several (optimize IN --primal MESH).
  expect_refused({(d / "other").string(), in.string()}, d / "hard.vtu", OutputKind::File, true, "is the input");
  // An input inside the polyMesh that a case output replaces.
  put(d / "case" / "constant" / "polyMesh" / "in.msh", "x");
  expect_refused({(d / "case" / "constant" / "polyMesh" / "in.msh").string()}, d / "case",
                 OutputKind::FoamCase, true, "constant/polyMesh");
  expect_refused({(d / "sub" / ".." / "case" / "constant" / "polyMesh" / "in.msh").string()},
                 d / "sub" / ".." / "case", OutputKind::FoamCase, false, "constant/polyMesh");
  // Other names are fine, existing or not.
  EXPECT_NO_THROW(check_output_target(inputs, (d / "out.vtu").string(), OutputKind::File, false, ".vtu"));
  EXPECT_NO_THROW(check_output_target(inputs, (d / "newcase").string(), OutputKind::FoamCase, false));
  EXPECT_EQ(slurp(in), "$MeshFormat");
}

TEST(OutputGuard, FilesAreReplacedOnlyByTheirOwnKind) {
  const fs::path d = scratch("guard_file");
  put(d / "old.vtu", "previous run");
  put(d / "mesh.msh", "$MeshFormat");
  fs::create_directories(d / "dir.vtu");
  EXPECT_NO_THROW(check_output_target({}, (d / "old.vtu").string(), OutputKind::File, false, ".vtu"));
  expect_refused({}, d / "mesh.msh", OutputKind::File, false, "is not a .vtu file");
  EXPECT_NO_THROW(check_output_target({}, (d / "mesh.msh").string(), OutputKind::File, true, ".vtu"));
  EXPECT_NO_THROW(check_output_target({}, (d / "mesh.msh").string(), OutputKind::File, false, ""));
  for (bool force : {false, true}) {
    expect_refused({}, d / "dir.vtu", OutputKind::File, force, "is a directory");
    expect_refused({}, d / "old.vtu", OutputKind::FoamCase, force, "exists and is a regular file, not a directory");
  }
  expect_refused({}, d / "old.vtu" / "x.vtu", OutputKind::File, false, "is a regular file, not a directory");
  fs::create_symlink(d / "nowhere", d / "dangling.vtu");
  expect_refused({}, d / "dangling.vtu", OutputKind::File, false, "is a symbolic link (to '");
}

TEST(OutputGuard, LinksAndSpecialFilesAreRefusedEvenWithForce) {
  const fs::path d = scratch("guard_links");
  put(d / "victim.txt", "the user's file");
  fs::create_symlink("victim.txt", d / "link.vtu");
  fs::create_directories(d / "realdir");
  fs::create_symlink("realdir", d / "caselink");
  ASSERT_EQ(::mkfifo((d / "pipe.vtu").c_str(), 0644), 0);
  const auto before = snapshot(d);
  for (bool force : {false, true}) {
    expect_refused({}, d / "link.vtu", OutputKind::File, force, "is a symbolic link (to 'victim.txt'); polydual never writes through a link");
    expect_refused({}, d / "caselink", OutputKind::FoamCase, force, "is a symbolic link (to 'realdir')");
    expect_refused({}, d / "pipe.vtu", OutputKind::File, force, "is a FIFO (named pipe); polydual writes only regular files");
  }
  for (const char* dev : {"/dev/null", "/dev/zero"}) {
    expect_refused({}, dev, OutputKind::File, true, "is a character device", "");
    expect_refused({}, dev, OutputKind::FoamCase, true, "is a character device, not a directory");
  }
  EXPECT_EQ(snapshot(d), before);
}

TEST(OutputGuard, ACaseWhoseOwnDirectoriesAreLinksIsRefused) {
  const fs::path d = scratch("guard_case_links");
  fs::create_directories(d / "elsewhere" / "polyMesh");
  put(d / "elsewhere" / "polyMesh" / "points", "the user's points");
  // OUT/constant a link to a directory outside the case.
  fs::create_directories(d / "a");
  fs::create_symlink(d / "elsewhere", d / "a" / "constant");
  // OUT/constant/polyMesh a link.
  fs::create_directories(d / "b" / "constant");
  fs::create_symlink(d / "elsewhere" / "polyMesh", d / "b" / "constant" / "polyMesh");
  // OUT/system a link, even to a directory inside the case.
  fs::create_directories(d / "c" / "mine");
  fs::create_symlink("mine", d / "c" / "system");
  const auto before = snapshot(d);
  for (bool force : {false, true}) {
    expect_refused({}, d / "a", OutputKind::FoamCase, force, "has a 'constant' that is a symbolic link");
    expect_refused({}, d / "b", OutputKind::FoamCase, force, "has a 'constant/polyMesh' that is a symbolic link");
    expect_refused({}, d / "c", OutputKind::FoamCase, force, "has a 'system' that is a symbolic link");
    FoamOptions o;
    o.force = force;
    EXPECT_THROW(write_foam(hex_block(1, 1), (d / "a").string(), o), UsageError);
  }
  EXPECT_EQ(snapshot(d), before);
}

TEST(OutputGuard, AMissingParentIsRefusedAlikeForFilesAndCases) {
  const fs::path d = scratch("guard_parent");
  put(d / "plain", "a file");
  for (const auto kind : {OutputKind::File, OutputKind::FoamCase}) {
    const fs::path deep = d / "nope" / "deeper" / (kind == OutputKind::File ? "out.vtu" : "case");
    expect_refused({}, deep, kind, true, "cannot be created: the directory '" + (d / "nope" / "deeper").string() +
                                             "' does not exist");
    expect_refused({}, d / "plain" / "x", kind, true, "is a regular file, not a directory");
  }
  EXPECT_FALSE(fs::exists(d / "nope"));
  // A name component too long for the file system (with the temporary's suffix).
  const std::string long_name(250, 'a');
  expect_refused({}, d / long_name, OutputKind::FoamCase, false, "has a name component of 250 bytes");
  expect_refused({}, d / (long_name + ".vtu"), OutputKind::File, false, "the file system allows 255");
  EXPECT_NO_THROW(check_output_target({}, (d / std::string(200, 'b')).string(), OutputKind::FoamCase, false));
}

TEST(OutputGuard, CaseDirectories) {
  const fs::path d = scratch("guard_case");
  fs::create_directories(d / "empty");
  put(d / "project" / "src" / "main.cpp", "int main() {}");
  put(d / "case_c" / "constant" / "transportProperties", "nu 1;");
  put(d / "case_s" / "system" / "controlDict", "application simpleFoam;");
  put(d / "odd" / "constant", "a file named constant");
  const auto before = snapshot(d);
  for (const char* ok : {"empty", "case_c", "case_s", "absent"})
    EXPECT_NO_THROW(check_output_target({}, (d / ok).string(), OutputKind::FoamCase, false)) << ok;
  expect_refused({}, d / "project", OutputKind::FoamCase, false, "neither empty nor an OpenFOAM case");
  EXPECT_NO_THROW(check_output_target({}, (d / "project").string(), OutputKind::FoamCase, true));
  expect_refused({}, d / "odd", OutputKind::FoamCase, true, "'constant' that is not a directory");
  EXPECT_EQ(snapshot(d), before);  // checking touches nothing
}

// ---------------------------------------------------------------------------
// write_foam: only constant/polyMesh (and an absent system/) are written

TEST(FoamSafety, ANonCaseDirectoryIsRefusedAndLeftUntouched) {
  const fs::path d = scratch("foam_project");
  put(d / "src" / "main.cpp", "int main() {}");
  put(d / "notes.txt", "my notes");
  fs::create_symlink("notes.txt", d / "link");
  const auto before = snapshot(d);
  try {
    write_foam(hex_block(1, 1), d.string());
    ADD_FAILURE() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr(d.string()));
    EXPECT_THAT(e.what(), HasSubstr("neither empty nor an OpenFOAM case"));
  }
  EXPECT_EQ(snapshot(d), before);

  // --force: the case is added, every other file is kept as it was.
  FoamOptions force;
  force.force = true;
  write_foam(hex_block(1, 1), d.string(), force);
  auto after = snapshot(d);
  for (const auto& [name, contents] : before) EXPECT_EQ(after[name], contents) << name;
  for (const char* f : kPolyMeshFiles) EXPECT_TRUE(fs::is_regular_file(d / "constant" / "polyMesh" / f)) << f;
  for (const char* f : {"controlDict", "fvSchemes", "fvSolution"}) EXPECT_TRUE(fs::is_regular_file(d / "system" / f));
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

TEST(FoamSafety, AnExistingCaseKeepsEverythingButItsPolyMesh) {
  const fs::path d = scratch("foam_case");
  put(d / "0" / "U", "internalField uniform (1 0 0);");
  put(d / "system" / "controlDict", "application simpleFoam;");
  put(d / "system" / "fvSchemes", "user schemes");
  put(d / "constant" / "transportProperties", "nu 1e-5;");
  put(d / "constant" / "polyMesh" / "points", "an older mesh");
  put(d / "constant" / "polyMesh" / "stale", "from the older mesh");
  put(d / "Allrun", "#!/bin/sh");
  auto before = snapshot(d);
  write_foam(hex_block(1, 1), d.string());
  auto after = snapshot(d);
  for (auto& [name, contents] : before)
    if (name.rfind("constant/polyMesh", 0) != 0) EXPECT_EQ(after[name], contents) << name;
  EXPECT_FALSE(fs::exists(d / "system" / "fvSolution"));  // the user's system/ is theirs
  EXPECT_FALSE(fs::exists(d / "constant" / "polyMesh" / "stale"));  // the polyMesh is replaced whole
  EXPECT_NE(slurp(d / "constant" / "polyMesh" / "points"), "an older mesh");
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

TEST(FoamSafety, ARerunReplacesThePreviousPolyMesh) {
  const fs::path d = scratch("foam_rerun") / "case";
  write_foam(hex_block(1, 1), d.string());
  const auto first = poly_mesh_files(d);
  const std::string control = slurp(d / "system" / "controlDict");
  write_foam(hex_block(2, 3), d.string());
  const auto second = poly_mesh_files(d);
  EXPECT_NE(first.at("points"), second.at("points"));
  EXPECT_NE(first.at("owner"), second.at("owner"));
  EXPECT_EQ(slurp(d / "system" / "controlDict"), control);
  write_foam(hex_block(1, 1), d.string());
  EXPECT_EQ(poly_mesh_files(d), first);  // same mesh, same bytes
  EXPECT_THAT(temporaries(d.parent_path()), ::testing::IsEmpty());
}

TEST(FoamSafety, AFailureMidWriteKeepsThePreviousCaseAndNoTemporary) {
  const fs::path d = scratch("foam_midwrite") / "case";
  write_foam(hex_block(1, 1), d.string());
  put(d / "0" / "p", "user field");
  const auto before = snapshot(d.parent_path());
  {
    // points (3.2 kB) fits, faces (14 kB) does not: a failure with some
    // files of the new polyMesh complete and one half written.
    FileSizeLimit limit(8000);
    try {
      write_foam(hex_block(6, 1), d.string());
      ADD_FAILURE() << "no error";
    } catch (const WriteError& e) {
      EXPECT_THAT(e.what(), HasSubstr("faces: write failed: File too large"));
    }
  }
  EXPECT_EQ(snapshot(d.parent_path()), before);
  // The same failure on a fresh case leaves nothing at all.
  const fs::path fresh = d.parent_path() / "fresh";
  {
    FileSizeLimit limit(8000);
    EXPECT_THROW(write_foam(hex_block(6, 1), fresh.string()), WriteError);
  }
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_EQ(snapshot(d.parent_path()), before);
}

TEST(FoamSafety, AnInterruptKeepsThePreviousCase) {
  InterruptReset reset;
  const fs::path d = scratch("foam_interrupt") / "case";
  write_foam(hex_block(1, 1), d.string());
  const auto before = snapshot(d.parent_path());
  request_interrupt(SIGTERM);
  EXPECT_THROW(write_foam(hex_block(2, 1), d.string()), Interrupted);
  EXPECT_THROW(write_foam(hex_block(2, 1), (d.parent_path() / "fresh").string()), Interrupted);
  EXPECT_EQ(snapshot(d.parent_path()), before);
}

// ---------------------------------------------------------------------------
// The command applies the guard before any work (lib/cli/main.cpp)

using polydual::testing::CmdResult;
CmdResult run(const std::string& args) { return polydual::testing::run_polydual(args); }

TEST(CommandSafety, ConvertRefusesToReplaceItsInputOrAUsersDirectory) {
  const fs::path d = scratch("command");
  const fs::path in = d / "in.msh";
  fs::copy_file(fs::path(POLYDUAL_TEST_DATA) / "cube5.msh", in);
  fs::create_symlink(in, d / "link.vtu");
  put(d / "project" / "src" / "main.cpp", "int main() {}");
  const auto before = snapshot(d);
  for (const std::string out : {in.string(), (d / "link.vtu").string(), (d / "project").string()}) {
    const CmdResult r = run("convert " + in.string() + " -o " + out + " --optimize none");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_THAT(r.out, HasSubstr("usage error: output '" + out + "'"));
  }
  EXPECT_EQ(snapshot(d), before);
  // A rerun over its own VTU output is fine.
  for (int i = 0; i < 2; ++i) {
    const CmdResult r = run("convert " + in.string() + " -o " + (d / "out.vtu").string() + " --optimize none");
    EXPECT_EQ(r.code, 0) << r.out;
  }
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}


// ---------------------------------------------------------------------------
// Every interrupt ends the run: the watchdog (core/interrupt.h)

namespace watchdog {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Waits up to `limit` seconds for `pid`; kills it and returns -1 if it is
// still running then (the hang the watchdog must prevent).
int wait_for(pid_t pid, double limit) {
  const double t0 = now();
  for (;;) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return status;
    if (now() - t0 > limit) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    ::usleep(10000);
  }
}

bool wait_until_exists(const fs::path& p, double limit) {
  for (const double t0 = now(); now() - t0 < limit; ::usleep(10000))
    if (fs::exists(p)) return true;
  return false;
}

// A child that registers the temporary `tmp`, creates it, then runs `stall`
// (which never polls the interrupt flag) under a watchdog of `grace` seconds.
template <class Stall>
pid_t child(const fs::path& tmp, double grace, Stall stall) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  start_interrupt_watchdog(grace);
  ScopedTemporary registered(tmp, ScopedTemporary::Kind::File);
  put(tmp, "half written");
  stall();
  ::_exit(0);  // not reached: the watchdog ends the process
}

}  // namespace watchdog

TEST(InterruptWatchdog, ASignalWhileBlockedInASystemCallEndsTheProcessAndRemovesTheTemporary) {
  const fs::path d = scratch("watchdog_blocked");
  const fs::path tmp = d / "out.vtu.tmp.1";
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = watchdog::child(tmp, 0.3, [&] {
    char c;
    for (;;) [[maybe_unused]] const ssize_t n = ::read(fds[0], &c, 1);  // blocks: nothing is ever written
  });
  ASSERT_TRUE(watchdog::wait_until_exists(tmp, 10));
  const double t0 = watchdog::now();
  ::kill(pid, SIGTERM);
  const int status = watchdog::wait_for(pid, 10);
  const double took = watchdog::now() - t0;
  ::close(fds[0]);
  ::close(fds[1]);
  ASSERT_NE(status, -1) << "still blocked 10 s after SIGTERM";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_LT(took, 3.0);
  EXPECT_FALSE(fs::exists(tmp));
}

TEST(InterruptWatchdog, ASecondSignalEndsTheProcessAtOnce) {
  const fs::path d = scratch("watchdog_second");
  const fs::path tmp = d / "case.tmp.1";
  const pid_t pid = watchdog::child(tmp, 600, [] {
    volatile unsigned long i = 0;
    for (;;) i = i + 1;  // a computation that never polls
  });
  ASSERT_TRUE(watchdog::wait_until_exists(tmp, 10));
  ::kill(pid, SIGINT);
  ::usleep(200000);
  EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), 0) << "the first signal alone must leave the grace to the run";
  const double t0 = watchdog::now();
  ::kill(pid, SIGINT);
  const int status = watchdog::wait_for(pid, 10);
  ASSERT_NE(status, -1) << "a second SIGINT did not end the process";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT);  // the first signal's status
  EXPECT_LT(watchdog::now() - t0, 2.0);
  EXPECT_FALSE(fs::exists(tmp));
}

// `generate` while Gmsh meshes (no poll point inside Gmsh): the watchdog ends
// it; no file is written after the signal.
TEST(CommandSafety, GenerateIsInterruptedWhileGmshMeshes) {
  const fs::path d = scratch("generate_interrupt");
  const fs::path out = d / "g.msh";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGINT, SIG_DFL);
    ::execl(POLYDUAL_BINARY, "polydual", "generate", "twomat", "--tets", "400000", "-o", out.c_str(), "--quiet",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::usleep(1500000);  // Gmsh is meshing (400k tets take several seconds)
  const double t0 = watchdog::now();
  ::kill(pid, SIGTERM);
  const int status = watchdog::wait_for(pid, 30);
  ASSERT_NE(status, -1) << "generate outlived its SIGTERM by 30 s";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_LT(watchdog::now() - t0, 5.0);
  ::usleep(500000);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_THAT(temporaries(d), ::testing::IsEmpty());
}

TEST(CommandSafety, LinksFifosAndDevicesAsOutputAreRefusedBeforeAnyWork) {
  const fs::path d = scratch("command_links");
  const fs::path in = d / "in.msh";
  fs::copy_file(fs::path(POLYDUAL_TEST_DATA) / "cube5.msh", in);
  put(d / "victim.txt", "the user's file");
  fs::create_symlink("victim.txt", d / "out.vtu");
  fs::create_directories(d / "real");
  fs::create_symlink("real", d / "caselink");
  ASSERT_EQ(::mkfifo((d / "pipe.vtu").c_str(), 0644), 0);
  const auto before = snapshot(d);
  const std::pair<std::string, std::string> cases[] = {
      {(d / "out.vtu").string(), "is a symbolic link (to 'victim.txt')"},
      {(d / "caselink").string(), "is a symbolic link (to 'real')"},
      {(d / "pipe.vtu").string(), "is a FIFO (named pipe)"},
      {"/dev/null", "is a character device"}};
  for (const auto& [out, why] : cases) {
    const double t0 = watchdog::now();
    const CmdResult r = run("convert " + in.string() + " -o " + out + " --force");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_THAT(r.out, HasSubstr(why));
    EXPECT_LT(watchdog::now() - t0, 5.0) << out;
  }
  EXPECT_EQ(snapshot(d), before);
}

}  // namespace
}  // namespace polydual
