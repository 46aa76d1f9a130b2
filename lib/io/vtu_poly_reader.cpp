#include "io/vtu_poly_reader.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "core/error.h"

namespace polydual {
namespace {

static_assert(std::endian::native == std::endian::little, "vtu binary mode assumes little endian");

constexpr std::int64_t kVtkPolyhedron = 42;

// One <DataArray>: its attributes, the section it sits in, and its raw text.
struct Array {
  std::string section;  // FieldData, PointData, CellData, Points, Cells
  std::map<std::string, std::string> attr;
  std::string_view text;
  std::size_t pos = 0;  // byte offset of the tag, for error places
};

// A scanner for the XML subset VTK writes: elements with attributes and text,
// comments, the <?xml?> declaration. Enough to read our own files and VTK's
// uncompressed ones; appended data and compression are reported as errors.
class VtuFile {
 public:
  VtuFile(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {
    parse();
  }

  [[noreturn]] void fail(std::size_t pos, const std::string& what) const {
    const auto line = 1 + std::count(text_.begin(), text_.begin() + static_cast<long>(pos), '\n');
    throw InputError(path_, "line " + std::to_string(line), what);
  }
  [[noreturn]] void fail_at(const std::string& place, const std::string& what) const {
    throw InputError(path_, place, what);
  }

  const Array* find(const std::string& section, const std::string& name) const {
    for (const Array& a : arrays_)
      if (a.section == section && a.attr.count("Name") && a.attr.at("Name") == name) return &a;
    return nullptr;
  }
  const Array& need(const std::string& section, const std::string& name) const {
    if (const Array* a = find(section, name)) return *a;
    fail_at(section, "missing DataArray '" + name + "'");
  }
  const Array* points() const {  // the Points array may have any name
    for (const Array& a : arrays_)
      if (a.section == "Points") return &a;
    return nullptr;
  }
  std::size_t piece_count(const char* key) const {
    auto it = piece_.find(key);
    if (it == piece_.end()) fail_at("Piece", std::string("missing ") + key);
    std::size_t n = 0;
    auto r = std::from_chars(it->second.data(), it->second.data() + it->second.size(), n);
    if (r.ec != std::errc() || r.ptr != it->second.data() + it->second.size())
      fail_at("Piece", std::string("bad ") + key + " '" + it->second + "'");
    return n;
  }

  // The values of `a` converted to T (an integer type or double), checking count.
  template <class T>
  std::vector<T> values(const Array& a, std::size_t expected) const {
    const std::string type = a.attr.count("type") ? a.attr.at("type") : "";
    const std::string format = a.attr.count("format") ? a.attr.at("format") : "ascii";
    std::vector<T> out;
    if (format == "ascii") {
      read_ascii(a, type, out);
    } else if (format == "binary") {
      read_binary(a, type, out);
    } else {
      fail(a.pos, "unsupported DataArray format '" + format + "'");
    }
    if (out.size() != expected)
      fail(a.pos, "DataArray '" + (a.attr.count("Name") ? a.attr.at("Name") : "") + "' has " +
                      std::to_string(out.size()) + " values, expected " +
                      std::to_string(expected));
    return out;
  }

 private:
  void parse();
  template <class T> void read_ascii(const Array& a, const std::string& type, std::vector<T>& out) const;
  template <class T> void read_binary(const Array& a, const std::string& type, std::vector<T>& out) const;

  std::string path_, text_;
  std::vector<Array> arrays_;
  std::map<std::string, std::string> root_, piece_;
};

void VtuFile::parse() {
  std::vector<std::string> stack;
  std::size_t i = 0;
  while ((i = text_.find('<', i)) != std::string::npos) {
    const std::size_t tag = i;
    if (text_.compare(i, 4, "<!--") == 0 || text_.compare(i, 2, "<?") == 0) {
      const char* end = text_[i + 1] == '!' ? "-->" : "?>";
      i = text_.find(end, i);
      if (i == std::string::npos) fail(tag, "unterminated comment or declaration");
      continue;
    }
    const std::size_t close = text_.find('>', i);
    if (close == std::string::npos) fail(tag, "unterminated tag");
    std::string_view body(text_.data() + i + 1, close - i - 1);
    i = close + 1;
    if (!body.empty() && body[0] == '/') {
      if (stack.empty() || stack.back() != body.substr(1)) fail(tag, "mismatched closing tag");
      stack.pop_back();
      continue;
    }
    const bool self_closing = !body.empty() && body.back() == '/';
    if (self_closing) body.remove_suffix(1);
    const std::size_t name_end = std::min(body.find_first_of(" \t\r\n"), body.size());
    const std::string name(body.substr(0, name_end));
    std::map<std::string, std::string> attr;
    for (std::size_t k = name_end; k < body.size();) {
      const std::size_t eq = body.find('=', k);
      if (eq == std::string_view::npos) break;
      const std::size_t q1 = body.find('"', eq), q2 = body.find('"', q1 + 1);
      if (q1 == std::string_view::npos || q2 == std::string_view::npos) fail(tag, "bad attribute");
      std::string_view key = body.substr(k, eq - k);
      while (!key.empty() && std::isspace(static_cast<unsigned char>(key.front()))) key.remove_prefix(1);
      attr.emplace(std::string(key), std::string(body.substr(q1 + 1, q2 - q1 - 1)));
      k = q2 + 1;
    }
    if (name == "VTKFile") root_ = attr;
    if (name == "Piece") {
      if (!piece_.empty()) fail(tag, "more than one Piece is not supported");
      piece_ = attr;
    }
    if (name == "AppendedData") fail(tag, "appended data is not supported");
    if (name == "DataArray" && !self_closing) {
      const std::size_t end = text_.find("</DataArray>", i);
      if (end == std::string::npos) fail(tag, "unterminated DataArray");
      Array a{stack.empty() ? "" : stack.back(), std::move(attr), {}, tag};
      a.text = std::string_view(text_.data() + i, end - i);
      // Drop nested elements (VTK's <InformationKey>) from the value text.
      if (auto lt = a.text.find('<'); lt != std::string_view::npos) a.text = a.text.substr(0, lt);
      arrays_.push_back(std::move(a));
      i = end + 12;
      continue;
    }
    if (!self_closing) stack.push_back(name);
  }
  if (!stack.empty()) fail(text_.size(), "unclosed element <" + stack.back() + ">");
  if (root_.count("type") == 0 || root_.at("type") != "UnstructuredGrid")
    fail_at("VTKFile", "not a VTK UnstructuredGrid file");
  if (root_.count("compressor")) fail_at("VTKFile", "compressed data is not supported");
  if (root_.count("byte_order") && root_.at("byte_order") != "LittleEndian")
    fail_at("VTKFile", "big-endian data is not supported");
}

template <class T>
void VtuFile::read_ascii(const Array& a, const std::string& type, std::vector<T>& out) const {
  const bool real = type == "Float32" || type == "Float64";
  const char* p = a.text.data();
  const char* end = p + a.text.size();
  while (true) {
    while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (p == end) break;
    std::from_chars_result r;
    if (real) {
      double v = 0;
      r = std::from_chars(p, end, v);
      if constexpr (std::is_integral_v<T>)
        if (r.ec == std::errc() && v != static_cast<double>(static_cast<T>(v)))
          fail(a.pos, "non-integer value in an index array");
      out.push_back(static_cast<T>(v));
    } else {
      std::int64_t v = 0;
      r = std::from_chars(p, end, v);
      out.push_back(static_cast<T>(v));
    }
    if (r.ec != std::errc() || (r.ptr < end && !std::isspace(static_cast<unsigned char>(*r.ptr))))
      fail(a.pos, "bad number '" + std::string(p, std::find_if(p, end, [](char c) {
                                                  return std::isspace(static_cast<unsigned char>(c));
                                                })) + "'");
    p = r.ptr;
  }
}

std::optional<std::vector<unsigned char>> decode_base64(std::string_view s) {
  std::vector<unsigned char> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+') v = 62;
    else if (c == '/') v = 63;
    else if (c == '=' || std::isspace(static_cast<unsigned char>(c))) continue;
    else return std::nullopt;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

template <class S, class T>
void convert_raw(const unsigned char* p, std::size_t n, std::vector<T>& out) {
  for (std::size_t k = 0; k < n; ++k) {
    S v;
    std::memcpy(&v, p + k * sizeof(S), sizeof(S));
    out.push_back(static_cast<T>(v));
  }
}

template <class T>
void VtuFile::read_binary(const Array& a, const std::string& type, std::vector<T>& out) const {
  auto raw = decode_base64(a.text);
  if (!raw) fail(a.pos, "bad base64 data");
  const bool h64 = !root_.count("header_type") || root_.at("header_type") == "UInt64";
  const std::size_t hsize = h64 ? 8 : 4;
  if (raw->size() < hsize) fail(a.pos, "binary DataArray without a byte-count header");
  std::uint64_t bytes = 0;
  if (h64) std::memcpy(&bytes, raw->data(), 8);
  else { std::uint32_t b32; std::memcpy(&b32, raw->data(), 4); bytes = b32; }
  if (bytes > raw->size() - hsize) fail(a.pos, "binary DataArray shorter than its header says");
  const unsigned char* p = raw->data() + hsize;
  auto sized = [&](std::size_t size) {
    if (bytes % size) fail(a.pos, "binary DataArray size is not a multiple of its type");
    return bytes / size;
  };
  if (type == "Int8") convert_raw<std::int8_t>(p, sized(1), out);
  else if (type == "UInt8") convert_raw<std::uint8_t>(p, sized(1), out);
  else if (type == "Int32") convert_raw<std::int32_t>(p, sized(4), out);
  else if (type == "UInt32") convert_raw<std::uint32_t>(p, sized(4), out);
  else if (type == "Int64") convert_raw<std::int64_t>(p, sized(8), out);
  else if (type == "UInt64") convert_raw<std::uint64_t>(p, sized(8), out);
  else if (type == "Float64" && std::is_floating_point_v<T>) convert_raw<double>(p, sized(8), out);
  else if (type == "Float32" && std::is_floating_point_v<T>) convert_raw<float>(p, sized(4), out);
  else fail(a.pos, "unsupported DataArray type '" + type + "' here");
}

// A face loop up to rotation: its lexicographically smallest rotation over both
// reading directions (all starts, since a loop may repeat a point, e.g. a cap
// through a model-edge midpoint twice). `reversed` tells which direction won,
// so the two sides of one face get the same key and opposite flags.
struct CanonicalLoop {
  std::vector<std::uint32_t> key;
  bool reversed = false;
};
CanonicalLoop canonical(const std::vector<PointId>& loop) {
  const std::size_t n = loop.size();
  const PointId lowest = *std::min_element(loop.begin(), loop.end());
  CanonicalLoop best;
  std::vector<std::uint32_t> candidate(n);
  for (bool reversed : {false, true})
    for (std::size_t m = 0; m < n; ++m) {
      if (loop[m] != lowest) continue;
      for (std::size_t k = 0; k < n; ++k)
        candidate[k] = loop[reversed ? (m + n - k) % n : (m + k) % n].idx;
      if (best.key.empty() || candidate < best.key) best = {candidate, reversed};
    }
  return best;
}

}  // namespace

PolyMesh read_vtu_poly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  const VtuFile file(path, ss.str());

  const std::size_t np = file.piece_count("NumberOfPoints"), nc = file.piece_count("NumberOfCells");
  PolyMesh mesh;
  const Array* pts = file.points();
  if (!pts && np > 0) file.fail_at("Points", "missing");
  const std::vector<double> xyz = pts ? file.values<double>(*pts, 3 * np) : std::vector<double>{};
  std::vector<std::int64_t> cdim(np, ModelRef::kNone), ctag(np, 0);
  if (const Array* a = file.find("PointData", "class_dim")) cdim = file.values<std::int64_t>(*a, np);
  if (const Array* a = file.find("PointData", "class_tag")) ctag = file.values<std::int64_t>(*a, np);
  for (std::size_t i = 0; i < np; ++i)
    mesh.add_point({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]},
                   ModelRef{static_cast<std::int8_t>(cdim[i]), static_cast<std::int32_t>(ctag[i])});

  const auto types = file.values<std::int64_t>(file.need("Cells", "types"), nc);
  const Array& faces_a = file.need("Cells", "faces");
  const auto& fo_a = file.need("Cells", "faceoffsets");
  const auto face_offsets = file.values<std::int64_t>(fo_a, nc);
  const std::size_t stream_size = nc ? static_cast<std::size_t>(std::max<std::int64_t>(0, face_offsets.back())) : 0;
  const auto faces = file.values<std::int64_t>(faces_a, stream_size);
  std::vector<std::int64_t> material(nc, 0), primal(nc, -1);
  if (const Array* a = file.find("CellData", "material")) material = file.values<std::int64_t>(*a, nc);
  if (const Array* a = file.find("CellData", "primal_vertex")) primal = file.values<std::int64_t>(*a, nc);
  // Per-occurrence face classification (see vtu_poly_writer.h); counted later.
  const Array* kind_a = file.find("FieldData", "face_kind");
  const Array* tag_a = file.find("FieldData", "face_tag");

  struct Occurrence { CellId cell; std::vector<PointId> loop; };
  std::vector<Occurrence> occ;
  std::vector<std::size_t> cell_first(nc + 1, 0);
  std::size_t k = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    const std::string place = "cell " + std::to_string(c);
    if (types[c] != kVtkPolyhedron) file.fail_at(place, "is not a VTK_POLYHEDRON (type 42)");
    cell_first[c] = occ.size();
    if (k >= faces.size()) file.fail_at(place, "faces stream ends early");
    const std::int64_t nf = faces[k++];
    for (std::int64_t j = 0; j < nf; ++j) {
      if (k >= faces.size()) file.fail_at(place, "faces stream ends early");
      const std::int64_t n = faces[k++];
      if (n < 3 || static_cast<std::size_t>(n) > faces.size() - k)
        file.fail_at(place, "face " + std::to_string(j) + " has a bad point count");
      Occurrence o{CellId(c), {}};
      for (std::int64_t v = 0; v < n; ++v, ++k) {
        if (faces[k] < 0 || static_cast<std::size_t>(faces[k]) >= np)
          file.fail_at(place, "face point index out of range");
        o.loop.emplace_back(static_cast<std::uint32_t>(faces[k]));
      }
      occ.push_back(std::move(o));
    }
    if (static_cast<std::int64_t>(k) != face_offsets[c])
      file.fail_at(place, "faceoffsets disagrees with the faces stream");
  }
  cell_first[nc] = occ.size();
  std::vector<std::int64_t> kinds, tags;
  if (kind_a) kinds = file.values<std::int64_t>(*kind_a, occ.size());
  if (tag_a) tags = file.values<std::int64_t>(*tag_a, occ.size());

  // Pair occurrences into faces: an open (unpaired) face waits under its
  // canonical loop for an occurrence in the opposite sense.
  struct Open { FaceId face; bool reversed; };
  std::map<std::vector<std::uint32_t>, std::vector<Open>> open;
  std::vector<HalfFace> half(occ.size());
  for (std::size_t o = 0; o < occ.size(); ++o) {
    CanonicalLoop c = canonical(occ[o].loop);
    auto& waiting = open[c.key];
    auto it = std::find_if(waiting.begin(), waiting.end(),
                           [&](const Open& w) { return w.reversed != c.reversed; });
    if (it != waiting.end()) {
      mesh.face_neighbour[it->face.idx] = occ[o].cell;
      half[o] = HalfFace(it->face, 1);
      if (kind_a && (kinds[o] != static_cast<std::int64_t>(mesh.face_kind[it->face.idx]) ||
                     (tag_a && tags[o] != mesh.face_tag[it->face.idx])))
        file.fail_at("cell " + std::to_string(occ[o].cell.idx),
                     "the two sides of a face disagree on its kind or tag");
      waiting.erase(it);
      continue;
    }
    const auto kind = kind_a ? kinds[o] : -1;
    if (kind_a && (kind < 0 || kind > static_cast<int>(FaceKind::Fracture)))
      file.fail_at("face_kind", "bad face kind " + std::to_string(kind));
    const FaceId f = mesh.add_face(occ[o].loop, occ[o].cell, CellId::invalid(),
                                   kind_a ? static_cast<FaceKind>(kind) : FaceKind::Interior,
                                   tag_a ? static_cast<std::int32_t>(tags[o]) : 0);
    half[o] = HalfFace(f, 0);
    waiting.push_back({f, c.reversed});
  }
  if (!kind_a)  // no classification stored: an unpaired face lies on the boundary
    for (std::size_t f = 0; f < mesh.num_faces(); ++f)
      if (!mesh.face_neighbour[f].valid()) mesh.face_kind[f] = FaceKind::External;

  for (std::size_t c = 0; c < nc; ++c)
    mesh.add_cell(std::span<const HalfFace>(half.data() + cell_first[c], half.data() + cell_first[c + 1]),
                  static_cast<std::int32_t>(material[c]),
                  primal[c] < 0 ? VertexId::invalid() : VertexId(static_cast<std::uint32_t>(primal[c])));
  return mesh;
}

}  // namespace polydual
