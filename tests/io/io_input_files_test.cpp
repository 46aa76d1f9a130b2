// What the readers do with hostile input files: paths that are not regular
// files (a directory, a FIFO with no writer, a character device, a dangling
// link) are refused with their own reason and never block; huge sparse or
// zero-filled files are refused from their first bytes, within a second and
// without reading them whole; NUL bytes in text are errors at their line; a
// UTF-8 byte-order mark is skipped; msh 4.1 bounding entities must exist.
// Library reads run in a forked child with a deadline, so a regression that
// hangs or reads 2 GB fails the test (with the time and peak memory it took)
// instead of stalling the suite.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "core/error.h"
#include "io/read_tet_mesh.h"
#include "run_command.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using polydual::testing::CmdResult;

const std::string kData = POLYDUAL_TEST_DATA;
constexpr std::uintmax_t k2G = std::uintmax_t(2) << 30;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// How a read in a child process ended. Its cost is the child's own CPU
// time and the bytes it read (the kernel's rchar: every pread counts), not
// the wall clock, which a loaded machine or a sanitizer build stretches.
struct Outcome {
  std::string message;  // "tets N", the InputError's text, or what went wrong
  double cpu_seconds = 0;
  std::uint64_t bytes_read = 0;
  long peak_rss_mb = 0;
};

// This process's bytes read so far (/proc/self/io's rchar).
std::uint64_t bytes_read_so_far() {
  std::ifstream io("/proc/self/io");
  std::string key;
  std::uint64_t value = 0;
  while (io >> key >> value)
    if (key == "rchar:") return value;
  return 0;
}

double cpu_seconds(const struct rusage& ru) {
  return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

// The CPU seconds of the children this process has waited for so far.
double children_cpu_seconds() {
  struct rusage ru {};
  ::getrusage(RUSAGE_CHILDREN, &ru);
  return cpu_seconds(ru);
}

// read_tet_mesh(path) in a forked child, killed after `deadline` seconds.
Outcome read_in_child(const std::string& path, double deadline = 10) {
  int fds[2];
  if (::pipe(fds) != 0) return {"pipe failed"};
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    const std::uint64_t before = bytes_read_so_far();
    std::string msg;
    try {
      msg = "tets " + std::to_string(read_tet_mesh(path).tets.size());
    } catch (const InputError& e) {
      msg = e.what();
    } catch (const std::exception& e) {
      msg = std::string("not an InputError: ") + e.what();
    }
    const std::uint64_t read = bytes_read_so_far() - before;
    msg = std::string(reinterpret_cast<const char*>(&read), sizeof read) + msg;
    if (::write(fds[1], msg.data(), msg.size()) < 0) ::_exit(2);
    ::_exit(0);
  }
  ::close(fds[1]);
  Outcome out;
  int status = 0;
  struct rusage ru {};
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  while (::wait4(pid, &status, WNOHANG, &ru) != pid) {
    if (elapsed() > deadline) {
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &ru);
      out.message = "TIMEOUT: still reading after " + std::to_string(deadline) + " s";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  out.cpu_seconds = cpu_seconds(ru);
  out.peak_rss_mb = ru.ru_maxrss / 1024;
  char buf[4096];
  std::string got;
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) got.append(buf, std::size_t(n));
  ::close(fds[0]);
  if (got.size() >= sizeof out.bytes_read) {
    std::memcpy(&out.bytes_read, got.data(), sizeof out.bytes_read);
    out.message += got.substr(sizeof out.bytes_read);
  }
  if (WIFSIGNALED(status) && out.message.empty()) out.message = "killed by signal " + std::to_string(WTERMSIG(status));
  return out;
}

// `polydual convert IN -o OUT.vtu` under timeout(1); its output and exit code.
CmdResult convert(const std::string& in, const fs::path& out) {
  CmdResult r{0, {}};
  r.out = polydual::testing::capture("timeout 20 " + std::string(POLYDUAL_BINARY) + " convert '" + in + "' -o '" +
                               out.string() + "' --optimize none 2>&1",
                           r.code);
  return r;
}

class InputFiles : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("polydual_input_files_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
  std::string at(const std::string& name) const { return (dir / name).string(); }
  // `head` written, then the file extended with a hole to `size` bytes.
  std::string sparse(const std::string& name, const std::string& head, std::uintmax_t size = k2G) const {
    std::ofstream(at(name), std::ios::binary) << head;
    fs::resize_file(at(name), size);
    return at(name);
  }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(at(name), std::ios::binary) << bytes;
    return at(name);
  }
  // The CLI refuses `in` with exit code 1, a message holding `reason`, and
  // no output file (nor a temporary).
  void expect_cli_refuses(const std::string& in, const std::string& reason) const {
    const CmdResult r = convert(in, dir / "out.vtu");
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_THAT(r.out, AllOf(HasSubstr(in), HasSubstr(reason)));
    EXPECT_FALSE(fs::exists(dir / "out.vtu"));
    for (const auto& e : fs::directory_iterator(dir))
      EXPECT_THAT(e.path().filename().string(), Not(HasSubstr(".tmp")));
  }
};

// ---- paths that are not regular files

TEST_F(InputFiles, DirectoryIsNamedAsSuch) {
  fs::create_directory(at("d.msh"));
  EXPECT_THAT(read_in_child(at("d.msh")).message,
              HasSubstr("d.msh: is a directory; polydual reads only regular files"));
  expect_cli_refuses(at("d.msh"), "is a directory");
}

TEST_F(InputFiles, FifoWithoutWriterIsRefusedWithoutBlocking) {
  for (const char* name : {"p.msh", "p.mesh", "p.vtu", "p.node"}) {
    ASSERT_EQ(::mkfifo(at(name).c_str(), 0600), 0);
    // A read that blocked would be killed at the deadline (message TIMEOUT).
    const Outcome o = read_in_child(at(name), 5);
    EXPECT_THAT(o.message, HasSubstr(std::string(name) + ": is a FIFO (named pipe); polydual reads only regular files"));
    EXPECT_LT(o.bytes_read, 4096u) << name;  // nothing of the FIFO (the count includes reading /proc/self/io)
  }
  expect_cli_refuses(at("p.msh"), "is a FIFO (named pipe); polydual reads only regular files");
}

TEST_F(InputFiles, CharacterDeviceIsNamedAsSuch) {
  // /dev/zero never ends: reading it would fill memory.
  EXPECT_THAT(read_in_child("/dev/zero", 5).message,
              HasSubstr("/dev/zero: is a character device; polydual reads only regular files"));
  fs::create_symlink("/dev/zero", at("zero.msh"));
  EXPECT_THAT(read_in_child(at("zero.msh"), 5).message,
              HasSubstr("zero.msh: is a symbolic link (to '/dev/zero') to a character device"));
  expect_cli_refuses("/dev/zero", "is a character device");
  expect_cli_refuses(at("zero.msh"), "to a character device");
}

TEST_F(InputFiles, DanglingLinkNamesItsTarget) {
  fs::create_symlink("nowhere.msh", at("dangling.msh"));
  EXPECT_THAT(read_in_child(at("dangling.msh")).message,
              HasSubstr("dangling.msh: is a dangling symbolic link (to 'nowhere.msh')"));
  expect_cli_refuses(at("dangling.msh"), "is a dangling symbolic link (to 'nowhere.msh')");
  EXPECT_THAT(read_in_child(at("missing.msh")).message, HasSubstr("missing.msh: cannot open file (No such file"));
}

TEST_F(InputFiles, LinkToARegularFileIsFollowed) {
  fs::create_symlink(kData + "/cube5.msh", at("good.msh"));
  fs::create_symlink("good.msh", at("good2.msh"));  // a relative link to a link
  EXPECT_EQ(read_in_child(at("good.msh")).message, "tets 5");
  EXPECT_EQ(read_in_child(at("good2.msh")).message, "tets 5");
  const CmdResult r = convert(at("good2.msh"), dir / "out.vtu");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(dir / "out.vtu"));
}

TEST_F(InputFiles, TetGenFaceFileThatIsNotRegularIsRefused) {
  for (const char* ext : {".node", ".ele"}) fs::copy_file(kData + "/cube5" + ext, at(std::string("c") + ext));
  EXPECT_EQ(read_in_child(at("c.node")).message, "tets 5");  // no .face: none read
  ASSERT_EQ(::mkfifo(at("c.face").c_str(), 0600), 0);
  EXPECT_THAT(read_in_child(at("c.ele"), 5).message, HasSubstr("c.face: is a FIFO (named pipe)"));
}

// ---- huge sparse and zero-filled files: refused from their first bytes

// AddressSanitizer keeps a shadow byte for every 8 bytes allocated and
// writes it at allocation, touched or not: under it the peak RSS of a read
// that allocates the file's size (2 GB: 256 MB of shadow) says nothing of how
// much was read. The memory bound is checked by the Release build.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kShadowMemory = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kShadowMemory = true;
#else
constexpr bool kShadowMemory = false;
#endif
#else
constexpr bool kShadowMemory = false;
#endif

// A 2 GB file refused having read at most 256 MiB of it (chunks of at most
// 64 MiB, growing with what was loaded), in under 2 s of CPU, with peak
// memory far below its size.
void expect_quick_refusal(const Outcome& o, const std::string& message) {
  EXPECT_THAT(o.message, HasSubstr(message));
  EXPECT_LT(o.bytes_read, std::uint64_t(256) << 20) << o.message;
  EXPECT_LT(o.cpu_seconds, 2.0) << o.message;
  if (!kShadowMemory) EXPECT_LT(o.peak_rss_mb, 256) << o.message;
}

TEST_F(InputFiles, SparseFilesAreRefusedAtTheirFirstByte) {
  const std::string nul = "line 1: NUL byte where text was expected";
  expect_quick_refusal(read_in_child(sparse("z.mesh", "")), "z.mesh: " + nul);
  expect_quick_refusal(read_in_child(sparse("z.msh", "")), "z.msh: " + nul);
  expect_quick_refusal(read_in_child(sparse("z.vtu", "")), "z.vtu: " + nul);
  sparse("z.ele", "");
  expect_quick_refusal(read_in_child(sparse("z.node", "")), "z.node: " + nul);
}

TEST_F(InputFiles, ValidHeaderThenZerosIsRefusedAtTheZeros) {
  const std::string nul = "NUL byte where text was expected";
  expect_quick_refusal(read_in_child(sparse("h.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n")),
                       "h.mesh: line 4: " + nul);
  expect_quick_refusal(read_in_child(sparse("h.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n")),
                       "h.msh: line 5: " + nul);
  const std::int32_t one = 1;
  const std::string bin = "$MeshFormat\n4.1 1 8\n" + std::string(reinterpret_cast<const char*>(&one), 4) +
                          "\n$EndMeshFormat\n$Nodes\n";
  expect_quick_refusal(read_in_child(sparse("hb.msh", bin + std::string(16, '\1'))), "hb.msh: byte ");
  expect_quick_refusal(read_in_child(sparse("h.vtu", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">\n")),
                       "h.vtu: line 3: " + nul);
  fs::copy_file(kData + "/cube5.node", at("h.node"));
  expect_quick_refusal(read_in_child(sparse("h.ele", "5 4 1\n")), "h.ele: line 2: " + nul);
  // A valid start of real content, then the hole: the read stops there.
  const std::string mesh = slurp(kData + "/cube5.mesh");
  expect_quick_refusal(read_in_child(sparse("p.mesh", mesh.substr(0, mesh.find("Tetrahedra")))), "p.mesh: line ");
}

// Counts that a 2 GB file could hold, then the hole: what the header
// announces costs address space, not memory, until records are read.
TEST_F(InputFiles, HeaderAnnouncingManyRecordsThenZerosCostsNoMemory) {
  const std::string nul = "NUL byte where text was expected";
  expect_quick_refusal(read_in_child(sparse("m.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n"
                                                     "1 200000000 1 200000000\n3 1 0 200000000\n")),
                       "m.msh: line 7: " + nul);
  auto bytes = [](auto v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
  std::string bin = "$MeshFormat\n4.1 1 8\n" + bytes(std::int32_t(1)) + "\n$EndMeshFormat\n$Nodes\n";
  for (std::uint64_t n : {1, 60000000, 1, 60000000}) bin += bytes(n);
  bin += bytes(std::int32_t(3)) + bytes(std::int32_t(1)) + bytes(std::int32_t(0)) + bytes(std::uint64_t(60000000));
  expect_quick_refusal(read_in_child(sparse("mb.msh", bin)), "mb.msh: byte " + std::to_string(bin.size() + 16) +
                                                                 ": node tag 0 defined twice");
  expect_quick_refusal(read_in_child(sparse("m.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n200000000\n")),
                       "m.mesh: line 5: " + nul);
}

TEST_F(InputFiles, VtuWithRawAppendedDataThenZerosIsRefusedFromItsEnd) {
  // NUL bytes are legitimate in raw appended data: the file's last bytes tell.
  const std::string raw = slurp(kData + "/cube5_vtk_appended_raw.vtu");
  const std::string head = raw.substr(0, raw.find("</AppendedData>"));
  const Outcome o = read_in_child(sparse("a.vtu", head));
  expect_quick_refusal(o, "a.vtu: byte " + std::to_string(k2G - 1) + ": the file ends in NUL bytes, not in </VTKFile>");
}

TEST_F(InputFiles, SparseFileThroughTheCommand) {
  sparse("z.mesh", "");
  const double cpu0 = children_cpu_seconds();
  const CmdResult r = convert(at("z.mesh"), dir / "out.vtu");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("z.mesh: line 1: NUL byte where text was expected"));
  EXPECT_LT(children_cpu_seconds() - cpu0, 2.0);
  EXPECT_FALSE(fs::exists(dir / "out.vtu"));
}

// `check` and `optimize` read polyhedral VTUs through the same bounded loader.
TEST_F(InputFiles, PolyhedralVtuInputsAreBoundedToo) {
  sparse("z.vtu", "");
  sparse("h.vtu", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">\n");
  for (const char* cmd : {"check", "optimize"}) {
    for (const char* name : {"z.vtu", "h.vtu"}) {
      const double cpu0 = children_cpu_seconds();
      CmdResult r{0, {}};
      const std::string extra = std::string(cmd) == "optimize" ? " -o '" + at("o.vtu") + "'" : "";
      r.out = polydual::testing::capture(
          "timeout 20 " + std::string(POLYDUAL_BINARY) + " " + cmd + " '" + at(name) + "'" + extra + " 2>&1", r.code);
      EXPECT_EQ(r.code, 1) << cmd << " " << name << ": " << r.out;
      EXPECT_THAT(r.out, HasSubstr(at(name) + ": ")) << cmd;
      EXPECT_LT(children_cpu_seconds() - cpu0, 2.0) << cmd << " " << name;
      EXPECT_FALSE(fs::exists(at("o.vtu")));
    }
  }
}

// ---- NUL bytes in text, byte-order marks

// `text` with its byte at `at` replaced by NUL.
std::string with_nul(std::string text, std::size_t at) {
  text[at] = '\0';
  return text;
}

TEST_F(InputFiles, NulByteInTextIsAnErrorAtItsLine) {
  const std::string mesh = slurp(kData + "/cube5.mesh");
  EXPECT_THAT(read_in_child(write("n.mesh", with_nul(mesh, mesh.find("Tetrahedra") + 3))).message,
              HasSubstr("n.mesh: line " + std::to_string(1 + std::count(mesh.begin(), mesh.begin() + long(mesh.find("Tetrahedra")), '\n')) +
                        ": NUL byte where text was expected"));
  const std::string msh = slurp(kData + "/cube5.msh");
  const std::size_t in_nodes = msh.find("$Nodes") + 12;
  EXPECT_THAT(read_in_child(write("n.msh", with_nul(msh, in_nodes))).message,
              AllOf(HasSubstr("n.msh: line "), HasSubstr("NUL byte where text was expected")));
  const std::string vtu = slurp(kData + "/cube5.vtu");
  const std::size_t in_points = vtu.find("0 0 0");
  EXPECT_THAT(read_in_child(write("n.vtu", with_nul(vtu, in_points + 1))).message,
              HasSubstr("n.vtu: line " + std::to_string(1 + std::count(vtu.begin(), vtu.begin() + long(in_points), '\n')) +
                        ": NUL byte where text was expected"));
  fs::copy_file(kData + "/cube5.ele", at("n.ele"));
  EXPECT_THAT(read_in_child(write("n.node", with_nul(slurp(kData + "/cube5.node"), 0))).message,
              HasSubstr("n.node: line 1: NUL byte"));
}

TEST_F(InputFiles, ByteOrderMarkIsSkippedInEveryTextFormat) {
  const std::string bom = "\xEF\xBB\xBF";
  for (const char* name : {"cube5.msh", "cube5_v2.msh", "cube5.mesh", "cube5.vtu"}) {
    EXPECT_EQ(read_in_child(write(std::string("b_") + name, bom + slurp(kData + "/" + name))).message, "tets 5")
        << name;
  }
  write("b.node", bom + slurp(kData + "/cube5.node"));
  write("b.ele", bom + slurp(kData + "/cube5.ele"));
  write("b.face", bom + slurp(kData + "/cube5.face"));
  EXPECT_EQ(read_in_child(at("b.ele")).message, "tets 5");
  const CmdResult r = convert(at("b_cube5.msh"), dir / "out.vtu");
  EXPECT_EQ(r.code, 0) << r.out;
}

// ---- msh 4.1 $Entities: bounding entities must exist

const std::string kMsh4Cube =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
    "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";
std::string msh4_with_entities(const std::string& entities) {
  return kMsh4Cube.substr(0, kMsh4Cube.find("$Nodes")) + "$Entities\n" + entities + "$EndEntities\n" +
         kMsh4Cube.substr(kMsh4Cube.find("$Nodes"));
}

TEST_F(InputFiles, Msh4BoundingEntityMustBeDeclared) {
  // Points 1, 2; curve 1 from 1 to 2 (the end point negative, as Gmsh writes);
  // surface 1 bounded by curve -1; volume 1 bounded by surface 1.
  const std::string points = "1 0 0 0 0\n2 1 0 0 0\n";
  const std::string ok = "2 1 1 1\n" + points + "1 0 0 0 1 0 0 0 2 1 -2\n1 0 0 0 1 1 0 0 1 -1\n" +
                         "1 0 0 0 1 1 1 0 1 1\n";
  EXPECT_EQ(read_in_child(write("ok.msh", msh4_with_entities(ok))).message, "tets 1");
  const std::string no_point = "2 1 1 1\n" + points + "1 0 0 0 1 0 0 0 2 1 -3\n1 0 0 0 1 1 0 0 1 -1\n" +
                               "1 0 0 0 1 1 1 0 1 1\n";
  EXPECT_THAT(read_in_child(write("np.msh", msh4_with_entities(no_point))).message,
              HasSubstr("np.msh: line 8: curve 1 is bounded by point -3, which is not in $Entities"));
  const std::string no_surface = "2 1 1 1\n" + points + "1 0 0 0 1 0 0 0 2 1 -2\n1 0 0 0 1 1 0 0 1 -1\n" +
                                 "1 0 0 0 1 1 1 0 2 1 -7\n";
  EXPECT_THAT(read_in_child(write("ns.msh", msh4_with_entities(no_surface))).message,
              HasSubstr("ns.msh: line 10: volume 1 is bounded by surface -7, which is not in $Entities"));
}

// ---- empty files and sections

TEST_F(InputFiles, EmptyFilesSayTheyAreEmpty) {
  for (const char* name : {"e.msh", "e.mesh", "e.vtu", "e.node"})
    EXPECT_THAT(read_in_child(write(name, "")).message, HasSubstr(std::string(name) + ": the file is empty"));
  EXPECT_THAT(read_in_child(write("e2.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 0 0\n$EndNodes\n"
                                            "$Elements\n0 0 0 0\n$EndElements\n"))
                  .message,
              HasSubstr("e2.msh: line 7: the file holds no tetrahedra ($Elements has none)"));
  EXPECT_THAT(read_in_child(write("e3.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")).message,
              HasSubstr("e3.msh: end of file: the file holds no tetrahedra (no $Nodes and no $Elements section)"));
}

}  // namespace
}  // namespace polydual
