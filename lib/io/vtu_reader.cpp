#include "io/vtu_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "io/file_bytes.h"
#include "io/record_checks.h"
#include "io/text_cursor.h"

namespace polydual {
namespace {

// One XML start or end tag. The scanner below understands just what VTK
// writes: declarations, comments, start/end/empty tags with quoted attributes.
struct Tag {
  std::string_view name;
  bool closing = false, empty = false;
  std::vector<std::pair<std::string_view, std::string_view>> attrs;
  std::size_t begin = 0, end = 0;  // byte range of "<...>"
  std::optional<std::string_view> attr(std::string_view key) const {
    for (const auto& [k, v] : attrs)
      if (k == key) return v;
    return std::nullopt;
  }
};

// A decoded DataArray: integers or reals, with its components per tuple.
struct Array {
  bool integer = false;
  std::vector<std::int64_t> ints;
  std::vector<double> reals;
  std::int64_t components = 1;
  std::size_t size() const { return integer ? ints.size() : reals.size(); }
};

struct TypeInfo {
  std::string_view name;
  int bytes;
  bool integer, is_signed;
};
constexpr TypeInfo kTypes[] = {{"Int8", 1, true, true},     {"UInt8", 1, true, false},  {"Int16", 2, true, true},
                               {"UInt16", 2, true, false},  {"Int32", 4, true, true},   {"UInt32", 4, true, false},
                               {"Int64", 8, true, true},    {"UInt64", 8, true, false}, {"Float32", 4, false, true},
                               {"Float64", 8, false, true}};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

class Reader {
 public:
  Reader(std::string_view bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}
  TetSoup read();

 private:
  std::size_t line_at(std::size_t pos) const {
    return 1 + static_cast<std::size_t>(std::count(bytes_.begin(), bytes_.begin() + std::min(pos, bytes_.size()), '\n'));
  }
  [[noreturn]] void fail(std::size_t pos, const std::string& what) const {
    throw InputError(source_, "line " + std::to_string(line_at(pos)), what);
  }
  std::optional<Tag> next_tag();
  Array decode(const Tag& tag, std::string_view content, std::size_t content_pos, const char* what);
  void decode_ascii(const TypeInfo& type, std::string_view content, std::size_t pos, const char* what, Array& a);
  void decode_binary(const Tag& tag, const TypeInfo& type, std::string_view content, std::size_t pos, Array& a);
  std::int64_t count_attr(const Tag& tag, std::string_view key);

  std::string_view bytes_;
  std::string source_;
  std::size_t pos_ = 0;
  bool header64_ = false;
};

std::optional<Tag> Reader::next_tag() {
  while (true) {
    const std::size_t lt = bytes_.find('<', pos_);
    if (lt == std::string_view::npos) return std::nullopt;
    auto skip_to = [&](std::string_view close) {
      const std::size_t e = bytes_.find(close, lt);
      if (e == std::string_view::npos) fail(lt, "unterminated '" + std::string(bytes_.substr(lt, 4)) + "'");
      pos_ = e + close.size();
    };
    if (bytes_.substr(lt, 4) == "<!--") { skip_to("-->"); continue; }
    if (bytes_.substr(lt, 2) == "<?") { skip_to("?>"); continue; }
    if (bytes_.substr(lt, 2) == "<!") { skip_to(">"); continue; }
    Tag t;
    t.begin = lt;
    std::size_t p = lt + 1;
    if (p < bytes_.size() && bytes_[p] == '/') { t.closing = true; ++p; }
    const std::size_t name_begin = p;
    while (p < bytes_.size() && !is_space(bytes_[p]) && bytes_[p] != '>' && bytes_[p] != '/') ++p;
    t.name = bytes_.substr(name_begin, p - name_begin);
    if (t.name.empty()) fail(lt, "malformed XML tag");
    while (true) {
      while (p < bytes_.size() && is_space(bytes_[p])) ++p;
      if (p >= bytes_.size()) fail(lt, "XML tag <" + io::quoted(t.name) + "> is not closed");
      if (bytes_[p] == '>') { ++p; break; }
      if (bytes_[p] == '/' && p + 1 < bytes_.size() && bytes_[p + 1] == '>') { t.empty = true; p += 2; break; }
      const std::size_t key_begin = p;
      while (p < bytes_.size() && bytes_[p] != '=' && !is_space(bytes_[p]) && bytes_[p] != '>') ++p;
      const std::string_view key = bytes_.substr(key_begin, p - key_begin);
      while (p < bytes_.size() && is_space(bytes_[p])) ++p;
      if (p >= bytes_.size() || bytes_[p] != '=') fail(p, "expected '=' after attribute '" + io::quoted(key) + "'");
      ++p;
      while (p < bytes_.size() && is_space(bytes_[p])) ++p;
      if (p >= bytes_.size() || (bytes_[p] != '"' && bytes_[p] != '\''))
        fail(p, "expected a quoted value for attribute '" + io::quoted(key) + "'");
      const char quote = bytes_[p++];
      const std::size_t close = bytes_.find(quote, p);
      if (close == std::string_view::npos) fail(p, "unterminated attribute value");
      t.attrs.emplace_back(key, bytes_.substr(p, close - p));
      p = close + 1;
    }
    t.end = pos_ = p;
    return t;
  }
}

std::int64_t Reader::count_attr(const Tag& tag, std::string_view key) {
  const auto v = tag.attr(key);
  if (!v) {
    std::string what = "<";  // built by append: GCC 12 warns falsely (-Wrestrict) on a + chain here
    what.append(tag.name).append("> has no ").append(key);
    fail(tag.begin, what);
  }
  io::TextCursor cur(*v, source_);
  cur.set_first_line(line_at(tag.begin));
  // Every point or cell takes at least a byte of the file: a larger count is a
  // lie, rejected before anything is sized by it.
  const std::int64_t n = cur.integer_in(std::string(key).c_str(), 0, static_cast<std::int64_t>(bytes_.size()));
  if (!cur.at_end()) fail(tag.begin, std::string(key) + " is not an integer");
  return n;
}

void Reader::decode_ascii(const TypeInfo& type, std::string_view content, std::size_t pos, const char* what, Array& a) {
  io::TextCursor cur(content, source_);
  cur.set_first_line(line_at(pos));
  while (!cur.at_end()) {
    if (type.integer) {
      const std::int64_t v = cur.integer("integer value");
      if (!type.is_signed && v < 0) cur.fail("negative value in unsigned DataArray");
      a.ints.push_back(v);
    } else {
      a.reals.push_back(cur.real(what));
    }
  }
}

// base64, decoding concatenated padded blocks: VTK writes the size header and
// the data either as one base64 stream or as two separately padded ones.
bool base64(std::string_view in, std::string& out) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  char group[4];
  int n = 0;
  for (char c : in) {
    if (is_space(c)) continue;
    group[n++] = c;
    if (n < 4) continue;
    n = 0;
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      if (group[k] == '=' && k >= 2) { v[k] = 0; ++pad; continue; }
      if (pad > 0) return false;
      v[k] = value(group[k]);
      if (v[k] < 0) return false;
    }
    const std::uint32_t bits = (v[0] << 18) | (v[1] << 12) | (v[2] << 6) | v[3];
    out += static_cast<char>(bits >> 16);
    if (pad < 2) out += static_cast<char>((bits >> 8) & 0xff);
    if (pad < 1) out += static_cast<char>(bits & 0xff);
  }
  return n == 0;
}

void Reader::decode_binary(const Tag& tag, const TypeInfo& type, std::string_view content, std::size_t pos, Array& a) {
  const std::string name(tag.attr("Name").value_or("(unnamed)"));
  std::string raw;
  if (!base64(content, raw)) fail(pos, "DataArray '" + name + "': invalid base64 data");
  const std::size_t header = header64_ ? 8 : 4;
  if (raw.size() < header) fail(pos, "DataArray '" + name + "': binary data shorter than its size header");
  std::uint64_t nbytes = 0;
  if (header64_) std::memcpy(&nbytes, raw.data(), 8);
  else { std::uint32_t n32; std::memcpy(&n32, raw.data(), 4); nbytes = n32; }
  // A separately encoded header may leave padding bytes: accept up to 2 extra.
  const std::uint64_t have = raw.size() - header;
  if (nbytes > have || have - nbytes > 2 || nbytes % type.bytes != 0)
    fail(pos, "DataArray '" + name + "': size header says " + std::to_string(nbytes) + " bytes but " +
                  std::to_string(have) + " bytes of " + std::string(type.name) + " follow");
  const char* p = raw.data() + header;
  for (std::uint64_t i = 0; i < nbytes / type.bytes; ++i, p += type.bytes) {
    if (!type.integer) {
      double v;
      if (type.bytes == 4) { float f; std::memcpy(&f, p, 4); v = f; } else std::memcpy(&v, p, 8);
      if (!std::isfinite(v)) fail(pos, "DataArray '" + name + "': value " + std::to_string(i) + " is not finite (" + std::to_string(v) + ")");
      a.reals.push_back(v);
      continue;
    }
    std::int64_t v = 0;
    switch (type.bytes) {
      case 1: v = type.is_signed ? static_cast<std::int8_t>(*p) : static_cast<std::uint8_t>(*p); break;
      case 2: { std::int16_t s; std::uint16_t u; std::memcpy(&s, p, 2); std::memcpy(&u, p, 2); v = type.is_signed ? s : u; break; }
      case 4: { std::int32_t s; std::uint32_t u; std::memcpy(&s, p, 4); std::memcpy(&u, p, 4); v = type.is_signed ? std::int64_t(s) : std::int64_t(u); break; }
      default: {
        std::memcpy(&v, p, 8);
        if (!type.is_signed && v < 0) fail(pos, "DataArray '" + name + "': UInt64 value too large");
      }
    }
    a.ints.push_back(v);
  }
}

Array Reader::decode(const Tag& tag, std::string_view content, std::size_t content_pos, const char* what) {
  Array a;
  const std::string_view type_name = tag.attr("type").value_or("");
  const TypeInfo* type = nullptr;
  for (const TypeInfo& t : kTypes)
    if (t.name == type_name) type = &t;
  if (!type) fail(tag.begin, "DataArray has unknown type '" + io::quoted(type_name) + "'");
  a.integer = type->integer;
  if (auto nc = tag.attr("NumberOfComponents")) {
    io::TextCursor cur(*nc, source_);
    cur.set_first_line(line_at(tag.begin));
    a.components = cur.integer_in("NumberOfComponents", 1, 1000);
  }
  const std::string_view format = tag.attr("format").value_or("ascii");
  if (format == "ascii") decode_ascii(*type, content, content_pos, what, a);
  else if (format == "binary") decode_binary(tag, *type, content, content_pos, a);
  else if (format == "appended") fail(tag.begin, "appended data not supported (write the VTU with ascii or binary DataArrays)");
  else fail(tag.begin, "unknown DataArray format '" + io::quoted(format) + "'");
  if (a.size() % a.components != 0)
    fail(tag.begin, "DataArray size " + std::to_string(a.size()) + " is not a multiple of its " +
                        std::to_string(a.components) + " components");
  return a;
}

TetSoup Reader::read() {
  constexpr std::string_view kRegionNames[] = {"region", "material", "gmsh:physical", "medit:ref", "CellEntityIds"};
  std::vector<std::string_view> stack;
  bool saw_vtkfile = false, saw_piece = false, saw_points = false;
  std::int64_t npoints = 0, ncells = 0;
  std::size_t piece_pos = 0;
  Array points;
  std::optional<Array> connectivity, offsets, types;
  std::optional<std::pair<std::size_t, Array>> region;  // (priority, array)
  std::size_t conn_pos = 0, off_pos = 0, types_pos = 0;
  while (auto tag = next_tag()) {
    if (tag->closing) {
      if (stack.empty() || stack.back() != tag->name) fail(tag->begin, "unexpected </" + io::quoted(tag->name) + ">");
      stack.pop_back();
      continue;
    }
    const std::string_view parent = stack.empty() ? "" : stack.back();
    if (tag->name == "VTKFile") {
      saw_vtkfile = true;
      if (tag->attr("type").value_or("") != "UnstructuredGrid")
        fail(tag->begin, "VTK file of type '" + io::quoted(tag->attr("type").value_or("")) + "' (expected UnstructuredGrid)");
      if (tag->attr("compressor")) fail(tag->begin, "compressed VTU not supported (write it uncompressed)");
      if (tag->attr("byte_order").value_or("LittleEndian") != "LittleEndian")
        fail(tag->begin, "big-endian VTU not supported");
      const std::string_view h = tag->attr("header_type").value_or("UInt32");
      if (h != "UInt32" && h != "UInt64") fail(tag->begin, "header_type '" + io::quoted(h) + "' not supported");
      header64_ = h == "UInt64";
    } else if (tag->name == "Piece") {
      if (saw_piece) fail(tag->begin, "more than one Piece not supported");
      saw_piece = true;
      piece_pos = tag->begin;
      npoints = count_attr(*tag, "NumberOfPoints");
      ncells = count_attr(*tag, "NumberOfCells");
    } else if (tag->name == "AppendedData") {
      fail(tag->begin, "appended data not supported (write the VTU with ascii or binary DataArrays)");
    } else if (tag->name == "DataArray") {
      std::string_view content;
      const std::size_t content_pos = tag->end;
      if (!tag->empty) {
        const std::size_t close = bytes_.find("</DataArray>", tag->end);
        if (close == std::string_view::npos) fail(tag->begin, "DataArray is not closed by </DataArray>");
        content = bytes_.substr(tag->end, close - tag->end);
        pos_ = close;  // the closing tag pops the stack
      }
      const std::string_view name = tag->attr("Name").value_or("");
      if (parent == "Points") {
        points = decode(*tag, content, content_pos, "coordinate");
        if (points.integer || points.components != 3) fail(tag->begin, "Points must be a Float32/Float64 array of 3 components");
        saw_points = true;
      } else if (parent == "Cells") {
        Array a = decode(*tag, content, content_pos, "value");
        if (!a.integer) fail(tag->begin, "cell array '" + io::quoted(name) + "' must have an integer type");
        if (name == "connectivity") { connectivity = std::move(a); conn_pos = tag->begin; }
        else if (name == "offsets") { offsets = std::move(a); off_pos = tag->begin; }
        else if (name == "types") { types = std::move(a); types_pos = tag->begin; }
      } else if (parent == "CellData") {
        for (std::size_t k = 0; k < std::size(kRegionNames); ++k) {
          if (name != kRegionNames[k] || (region && region->first <= k)) continue;
          Array a = decode(*tag, content, content_pos, "value");
          if (!a.integer) fail(tag->begin, "region array '" + std::string(name) + "' must have an Int type");
          if (a.components != 1 || static_cast<std::int64_t>(a.size()) != ncells)
            fail(tag->begin, "region array '" + std::string(name) + "' has " + std::to_string(a.size()) +
                                 " values for " + std::to_string(ncells) + " cells");
          region.emplace(k, std::move(a));
        }
      }
    }
    if (!tag->empty) stack.push_back(tag->name);
  }
  if (!stack.empty()) fail(bytes_.size(), "file ends inside <" + io::quoted(stack.back()) + ">");
  if (!saw_vtkfile) fail(0, "not a VTK XML file (no <VTKFile>)");
  if (!saw_piece) fail(0, "no <Piece> in the UnstructuredGrid");
  if (!saw_points) fail(piece_pos, "Piece has no Points");
  if (!connectivity || !offsets || !types) fail(piece_pos, "Cells need connectivity, offsets and types arrays");
  if (static_cast<std::int64_t>(points.reals.size()) != 3 * npoints)
    fail(piece_pos, "NumberOfPoints is " + std::to_string(npoints) + " but Points holds " +
                        std::to_string(points.reals.size() / 3));
  // VTK 9 may write offsets with a leading 0 (ncells + 1 entries).
  std::vector<std::int64_t>& off = offsets->ints;
  if (static_cast<std::int64_t>(off.size()) == ncells + 1 && !off.empty() && off[0] == 0) off.erase(off.begin());
  if (static_cast<std::int64_t>(off.size()) != ncells || static_cast<std::int64_t>(types->ints.size()) != ncells)
    fail(off_pos, "NumberOfCells is " + std::to_string(ncells) + " but offsets has " + std::to_string(off.size()) +
                        " and types " + std::to_string(types->ints.size()) + " entries");
  TetSoup soup;
  soup.source = source_;
  soup.points.resize(npoints);
  for (std::int64_t i = 0; i < npoints; ++i)
    soup.points[i] = {points.reals[3 * i], points.reals[3 * i + 1], points.reals[3 * i + 2]};
  std::int64_t begin = 0;
  const std::vector<std::int64_t>& conn = connectivity->ints;
  for (std::int64_t c = 0; c < ncells; ++c) {
    const std::int64_t type = types->ints[c], end = off[c];
    const std::string cell = "cell " + std::to_string(c);
    if (end < begin || end > static_cast<std::int64_t>(conn.size()))
      fail(off_pos, cell + ": offset " + std::to_string(end) + " out of range (" + std::to_string(begin) + ".." +
                          std::to_string(conn.size()) + ")");
    const std::int64_t expect = type == 10 ? 4 : type == 5 ? 3 : -1;
    if (expect < 0) fail(types_pos, cell + ": unsupported VTK cell type " + std::to_string(type) + " (only tetra 10 and triangle 5)");
    if (end - begin != expect)
      fail(off_pos, cell + ": expected " + std::to_string(expect) + " node indices, got " + std::to_string(end - begin));
    std::array<std::uint32_t, 4> v{};
    for (std::int64_t k = 0; k < expect; ++k) {
      const std::int64_t idx = conn[begin + k];
      if (idx < 0 || idx >= npoints)
        fail(conn_pos, cell + ": node index " + std::to_string(idx) + " out of range (0.." + std::to_string(npoints - 1) + ")");
      v[k] = static_cast<std::uint32_t>(idx);
    }
    std::int64_t tag = region ? region->second.ints[c] : (type == 10 ? 1 : 0);
    if (tag < std::numeric_limits<std::int32_t>::min() || tag > std::numeric_limits<std::int32_t>::max())
      fail(piece_pos, cell + ": region " + std::to_string(tag) + " does not fit in 32 bits");
    if (type == 10) {
      soup.tets.push_back(v);
      soup.tet_region.push_back(static_cast<std::int32_t>(tag));
    } else {
      const std::array<std::uint32_t, 3> tri{v[0], v[1], v[2]};
      if (const std::string bad = io::repeated_vertex(tri, "triangle"); !bad.empty()) fail(conn_pos, cell + ": " + bad);
      soup.triangles.push_back({tri, static_cast<std::int32_t>(tag)});
    }
    begin = end;
  }
  return soup;
}

}  // namespace

TetSoup read_vtu(std::string_view bytes, const std::string& source) { return Reader(bytes, source).read(); }

TetSoup read_vtu_file(const std::string& path) { return read_vtu(io::read_file_bytes(path), path); }

}  // namespace polydual
