#include "io/msh_reader.h"

#include <cmath>

#include "io/file_bytes.h"
#include "io/msh_internal.h"
#include "io/unattached.h"

namespace polydual {

namespace io::msh {

int node_count(std::int64_t type) {
  // Gmsh element types 1..31 (GmshDefines.h); 92/93 are the cubic hexes.
  static constexpr int kNodes[32] = {-1, 2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1,
                                     8,  20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5, 6, 20, 35, 56};
  if (type >= 1 && type <= 31) return kNodes[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return -1;
}

static int element_dim(std::int64_t type) {
  static constexpr int kDim[32] = {-1, 1, 2, 2, 3, 3, 3, 3, 1, 2, 2, 3, 3, 3, 3, 0,
                                   2,  3, 3, 3, 2, 2, 2, 2, 2, 2, 1, 1, 1, 3, 3, 3};
  if (type >= 1 && type <= 31) return kDim[type];
  return 3;  // 92, 93
}

int element_order(std::int64_t type) {
  switch (type) {
    case 8: case 9: case 11: return 2;                      // line3, triangle6, tet10
    case 26: case 20: case 21: case 29: return 3;           // line4, triangle9/10, tet20
    case 27: case 22: case 23: case 30: return 4;           // line5, triangle12/15, tet35
    case 28: case 24: case 25: case 31: return 5;           // line6, triangle15i/21, tet56
    default: return 1;
  }
}

Use element_use(const TextCursor& cur, std::int64_t type) {
  auto fail = [&](const std::string& what) { cur.fail(what); };
  if (node_count(type) < 0) fail("unknown element type " + std::to_string(type));
  switch (type) {
    case 4: case 11: case 29: case 30: case 31: return Use::tet;
    case 2: case 9: case 20: case 21: case 22: case 23: case 24: case 25: return Use::triangle;
    case 1: case 8: case 26: case 27: case 28: return Use::line;
    case 15: return Use::point;
    case 7: case 14: case 19: return Use::pyramid;
    case 6: case 13: case 18: return Use::prism;
    case 5: case 12: case 17: case 92: case 93: return Use::hex;
    case 3: case 10: case 16: return Use::quad;
    default: break;
  }
  if (element_dim(type) == 3)
    fail("unsupported element type " + std::to_string(type) + " (only tetrahedra, pyramids, prisms and hexahedra)");
  return Use::ignore;
}

int use_dim(Use u) {
  switch (u) {
    case Use::tet: case Use::pyramid: case Use::prism: case Use::hex: return 3;
    case Use::triangle: case Use::quad: return 2;
    case Use::line: return 1;
    case Use::point: return 0;
    case Use::ignore: break;
  }
  return -1;
}

int use_corners(Use u) {
  switch (u) {
    case Use::tet: case Use::quad: return 4;
    case Use::triangle: return 3;
    case Use::line: return 2;
    case Use::point: return 1;
    case Use::pyramid: return 5;
    case Use::prism: return 6;
    case Use::hex: return 8;
    case Use::ignore: break;
  }
  return 0;
}

CellType use_cell_type(Use u) {
  return u == Use::pyramid ? CellType::Pyramid : u == Use::prism ? CellType::Prism : CellType::Hex;
}

std::string high_order_warning(const std::string& source, int max_order) {
  if (max_order <= 1) return {};
  return source + ": " + (max_order == 2 ? std::string("second-order") : "order-" + std::to_string(max_order)) +
         " elements: using their corner vertices (the other nodes are left unused)";
}

void skip_section(TextCursor& cur, std::string_view name) {
  // Searching the raw bytes works for binary sections as well as text ones.
  const std::string end = "$End" + std::string(name);
  const std::size_t at = cur.find(end);
  if (at == std::string_view::npos) cur.fail("section $" + std::string(name) + " is not closed by " + end);
  cur.seek(at + end.size());
}

void expect_end(TextCursor& cur, std::string_view name) {
  const std::string end = "$End" + std::string(name);
  const std::string_view t = cur.token(end.c_str());
  if (t != end) cur.fail("expected " + end + ", got '" + quoted(t) + "' (count larger than the data?)");
}

std::string physical_name(TextCursor& cur) {
  const std::string_view line = cur.rest_of_line();
  const std::size_t first = line.find('"'), last = line.rfind('"');
  if (first == std::string_view::npos || last == first) cur.fail("expected a quoted physical name");
  return std::string(line.substr(first + 1, last - first - 1));
}

void require_tets(const TetSoup& soup, const TextCursor& cur, const std::string& elements_place, bool surfaces) {
  if (!soup.tets.empty() || !soup.other_cells.empty()) return;
  if (surfaces && !(soup.triangles.empty() && soup.quads.empty())) return;
  const std::size_t others = soup.triangles.size() + soup.edges.size() + soup.corners.size();
  const std::string only = others ? ", only " + count_of(others, "triangle, line or point", "triangles, lines and points") : "";
  throw InputError(cur.source(), elements_place, "the file holds no tetrahedra ($Elements has none" + only + ")");
}

double binary_coordinate(TextCursor& cur, const char* what) {
  const std::size_t at = cur.offset();
  const double v = cur.binary<double>(what);
  if (!std::isfinite(v))
    throw InputError(cur.source(), "byte " + std::to_string(at),
                     "coordinate is not finite (" + std::to_string(v) + ")");
  return v;
}

}  // namespace io::msh

namespace {

// The version of $MeshFormat in tenths (22 for "2.2"), whatever its spelling:
// Gmsh itself reads it as a double, so "2", "2.0" and Netgen's "2.000000" are
// version 2.0 and "2.10" is 2.1. -1 when it is not a plain decimal number or
// falls between tenths.
int version_tenths(std::string_view v) {
  std::size_t i = 0, digits = 0;
  long whole = 0, tenth = 0;
  for (; i < v.size() && v[i] >= '0' && v[i] <= '9' && whole < 1000; ++i, ++digits) whole = whole * 10 + (v[i] - '0');
  if (digits == 0) return -1;
  if (i < v.size() && v[i] == '.') {
    ++i;
    if (i < v.size() && v[i] >= '0' && v[i] <= '9') tenth = v[i++] - '0';
    while (i < v.size() && v[i] == '0') ++i;  // "2.000000", "2.10": nothing below a tenth
  }
  if (i != v.size() || whole >= 1000) return -1;
  return int(whole * 10 + tenth);
}

// $MeshFormat, then the sections of its version; the cursor names the source.
TetSoup read_msh_from(io::TextCursor& cur, bool surfaces) {
  const std::string& source = cur.source();
  if (cur.at_end()) throw InputError(source, "", "the file is empty");
  const std::string_view first = cur.token("$MeshFormat");
  if (first != "$MeshFormat")
    cur.fail("not a Gmsh file: expected $MeshFormat, got '" + io::quoted(first) + "'");
  const std::string_view version = cur.token("format version");
  const std::int64_t file_type = cur.integer_in("file type", 0, 1);
  const std::int64_t data_size = cur.integer("data size");
  if (data_size != 8) cur.fail("data size " + std::to_string(data_size) + " not supported (only 8)");
  const int tenths = version_tenths(version);
  if (tenths != 20 && tenths != 21 && tenths != 22 && tenths != 41)
    cur.fail("msh format version '" + io::quoted(version) + "' not supported (use 2.2 or 4.1)");
  const bool binary = file_type == 1;
  if (binary) {
    // The binary int 1 tells the writer's endianness; we only read files
    // written on a little-endian machine like ours.
    cur.skip_end_of_line();
    const int one = cur.binary<int>("the endianness check of $MeshFormat");
    if (one != 1) cur.fail_byte("binary file of the other endianness (or corrupt $MeshFormat): got " +
                                std::to_string(one) + " instead of 1");
  }
  io::msh::expect_end(cur, "MeshFormat");
  cur.set_binary(binary);
  TetSoup soup = tenths == 41 ? io::msh::read_msh4(cur, binary, surfaces)
                                : io::msh::read_msh2(cur, binary, tenths % 10, surfaces);
  soup.source = source;
  return soup;
}

}  // namespace

TetSoup read_msh(std::string_view bytes, const std::string& source, bool surfaces) {
  io::TextCursor cur(bytes, source);
  return read_msh_from(cur, surfaces);
}

TetSoup read_msh_file(const std::string& path, bool surfaces) {
  io::InputFile file(path);
  io::TextCursor cur(file);
  return read_msh_from(cur, surfaces);
}

}  // namespace polydual
