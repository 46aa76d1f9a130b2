// The format registry: every registered reader and writer is found again by
// its extensions and name, appears in the command's help, and an unknown
// format or extension is refused with the file and the known ones named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <unistd.h>

#include "core/error.h"
#include "io/format_registry.h"
#include "io/msh_reader.h"
#include "io/read_tet_mesh.h"
#include "io/write_poly_mesh.h"
#include "io/write_tet_mesh.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("polydual_registry_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string run(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(::popen(cmd.c_str(), "r"), ::pclose);
  char buf[4096];
  for (std::size_t n; p && (n = std::fread(buf, 1, sizeof buf, p.get())) > 0;) out.append(buf, n);
  return out;
}

TEST(FormatRegistry, NamesAndExtensionsAreDistinct) {
  std::set<std::string> names, exts;
  for (const MeshFormat* r : mesh_formats()) {
    EXPECT_TRUE(names.insert(std::string(r->name())).second) << r->name();
    EXPECT_FALSE(r->help().empty()) << r->name();
    for (std::string_view e : r->extensions()) EXPECT_TRUE(exts.insert(std::string(e)).second) << e;
  }
  EXPECT_EQ(exts, (std::set<std::string>{".msh", ".gmsh2", ".mesh", ".node", ".ele", ".vtu"}));
  std::set<std::string> writers;
  for (const PolyWriter* w : poly_writers()) EXPECT_TRUE(writers.insert(std::string(w->name())).second);
  EXPECT_EQ(writers, (std::set<std::string>{"vtu", "foam"}));
}

// Every reader's own extension round-trips: a mesh written under it is read
// back by that reader (case-insensitively too), with the same tets.
TEST(FormatRegistry, EveryReaderRoundTripsItsExtension) {
  const TetSoup a = read_msh_file(std::string(POLYDUAL_TEST_DATA) + "/cube5.msh");
  const fs::path dir = scratch();
  for (const MeshFormat* r : mesh_formats()) {
    for (std::string_view e : r->extensions()) {
      EXPECT_EQ(&mesh_format_for("a/b" + std::string(e)), r) << e;
      std::string upper(e);
      for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      EXPECT_EQ(&mesh_format_for("B" + upper), r) << upper;
    }
    const std::string path = (dir / ("rt" + std::string(r->extensions().front()))).string();
    write_tet_mesh(a, path);  // by extension: the format's own writer
    const TetSoup b = r->read(path);
    EXPECT_EQ(b.tets, a.tets) << r->name();
    EXPECT_EQ(read_tet_mesh(path).tets, a.tets) << r->name();
    const std::string direct = (dir / ("w" + std::string(r->extensions().front()))).string();
    r->write(a, direct);
    EXPECT_EQ(r->read(direct).tets, a.tets) << r->name();
  }
  try {
    write_tet_mesh(a, (dir / "x.stl").string());
    ADD_FAILURE() << "no UsageError";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr(mesh_extensions_text()));
  }
  EXPECT_FALSE(fs::exists(dir / "x.stl"));
  fs::remove_all(dir);
}

TEST(FormatRegistry, EveryWriterRoundTripsItsNameAndExtension) {
  for (const PolyWriter* w : poly_writers()) {
    EXPECT_EQ(&poly_writer_named(w->name()), w);
    EXPECT_EQ(parse_poly_format(w->name()).name(), w->name());
    const std::string out = w->extension().empty() ? "dir/case" : "dir/out" + std::string(w->extension());
    EXPECT_EQ(&poly_writer_for_path(out), w) << out;
    EXPECT_EQ(&poly_format_for("", out).writer(), w) << out;
    EXPECT_EQ(w->output_kind() == OutputKind::File, !w->extension().empty()) << w->name();
  }
  EXPECT_EQ(&poly_writer_for_path("dir/case.d/"), &PolyFormat::Foam.writer());
  EXPECT_EQ(poly_format_for("foam", "x.vtu"), PolyFormat::Foam);  // a named format wins over the path
}

// The command's --format values, the option's help and the synopsis come
// from the registry: every writer's name and help line, every reader's
// extensions.
TEST(FormatRegistry, HelpTextListsEveryFormat) {
  const std::string help = run(std::string(POLYDUAL_BINARY) + " convert --help 2>&1");
  ASSERT_THAT(help, HasSubstr("--format " + poly_format_choices()));
  EXPECT_EQ(poly_format_choices(), "vtu|foam");
  for (const PolyWriter* w : poly_writers()) {
    EXPECT_THAT(poly_format_help(), HasSubstr(std::string(w->name()) + ": " + std::string(w->help())));
    EXPECT_THAT(help, HasSubstr(std::string(w->help()).substr(0, 20))) << w->name();
  }
  for (const MeshFormat* r : mesh_formats())
    for (std::string_view e : r->extensions()) EXPECT_THAT(help, HasSubstr(std::string(e))) << e;
  const std::string usage = run(std::string(POLYDUAL_BINARY) + " --help 2>&1");
  EXPECT_THAT(usage, HasSubstr("convert IN -o OUT [--format vtu|foam]"));
}

TEST(FormatRegistry, UnknownInputExtensionIsRefusedNamingTheFile) {
  const fs::path dir = scratch();
  const std::string stl = (dir / "part.stl").string();
  std::ofstream(stl) << "solid x\nendsolid x\n";
  try {
    read_tet_mesh(stl);
    FAIL() << "read an .stl";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(stl));
    EXPECT_THAT(e.what(), HasSubstr("unknown mesh file extension '.stl'"));
    EXPECT_THAT(e.what(), HasSubstr("supported: " + mesh_extensions_text()));
    EXPECT_EQ(mesh_extensions_text(), ".msh or .gmsh2, .mesh, .node or .ele, .vtu");
  }
  // A missing file is reported as missing, not as an unknown format.
  try {
    read_tet_mesh((dir / "none.stl").string());
    FAIL() << "read a missing file";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("none.stl"));
    EXPECT_THAT(e.what(), testing::Not(HasSubstr("extension")));
  }
  fs::remove_all(dir);
}

TEST(FormatRegistry, UnknownOutputFormatOrExtensionIsRefused) {
  try {
    poly_format_for("", "out/mesh.msh");
    FAIL() << "took .msh for a polyhedral output";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr("out/mesh.msh"));
    EXPECT_THAT(e.what(), HasSubstr(".vtu (vtu)"));
    EXPECT_THAT(e.what(), HasSubstr("a directory without an extension (foam)"));
  }
  try {
    poly_format_for("exodus", "out.vtu");
    FAIL() << "took an unknown format name";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown output format 'exodus' (known: vtu|foam)"));
  }
  // Through the command: exit 2, the file named, nothing written.
  const fs::path dir = scratch();
  const std::string out = (dir / "o.stl").string();
  const std::string msg = run(std::string(POLYDUAL_BINARY) + " convert " + POLYDUAL_TEST_DATA +
                              "/cube5.msh -o " + out + " --quiet 2>&1; echo rc=$?");
  EXPECT_THAT(msg, HasSubstr(out));
  EXPECT_THAT(msg, HasSubstr("rc=2"));
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace polydual
