#include "io/vtu_poly_writer.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <functional>
#include <optional>
#include <ostream>
#include <set>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/vtk_xml.h"

namespace polydual {
namespace {

// Binary arrays are the in-memory bytes; the file declares LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtu binary mode assumes little endian");

constexpr std::uint8_t kVtkPolyhedron = 42;

// One number as text. Doubles get 17 significant digits: that is the smallest
// count that makes every IEEE binary64 value round-trip through decimal exactly,
// so the reader recovers bit-identical coordinates (the validity test is exact,
// a rounded point could flip a cell's verdict). to_chars is locale-independent.
template <class T>
void put_number(std::string& s, T v) {
  std::array<char, 32> buf;
  std::to_chars_result r;
  if constexpr (std::is_floating_point_v<T>)
    r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  else
    r = std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<std::int64_t>(v));
  s.append(buf.data(), r.ptr);
}

// One DataArray to write: its XML attributes, its values as bytes (binary
// modes) and as text (ascii).
struct OutArray {
  const char* type;
  std::string name;
  int components;
  bool field_data;  // FieldData arrays declare NumberOfTuples
  std::size_t count;
  std::string_view bytes;
  std::function<void(std::ostream&)> ascii;
};

template <class T>
OutArray out_array(const char* type, std::string name, int components, const std::vector<T>& v,
                   bool field_data = false) {
  OutArray a{type, std::move(name), components, field_data, v.size(),
             {reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)}, {}};
  a.ascii = [&v, components](std::ostream& os) {
    const std::size_t per_line = components > 1 ? static_cast<std::size_t>(components) : 12;
    std::string line;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i % per_line == 0) line = "          ";
      else line += ' ';
      put_number(line, v[i]);
      if (i % per_line == per_line - 1 || i + 1 == v.size()) os << line << "\n";
    }
  };
  return a;
}

// The binary payload of an array as VTK lays it out: a UInt64 byte count and
// the bytes, or the zlib header and blocks.
struct Payload {
  std::string header, compressed;
  std::string_view data;  // the uncompressed bytes (not copied)
  std::size_t size() const { return header.size() + (compressed.empty() ? data.size() : compressed.size()); }
};
Payload payload_of(const OutArray& a, int zlib_level) {
  Payload p;
  if (zlib_level > 0) {
    io::vtkxml::ZlibPayload z = io::vtkxml::zlib_compress(a.bytes, zlib_level, true);
    p.header = std::move(z.header);
    p.compressed = std::move(z.blocks);
    return p;
  }
  const std::uint64_t n = a.bytes.size();
  p.header.assign(reinterpret_cast<const char*>(&n), sizeof n);
  p.data = a.bytes;
  return p;
}

void write_array(std::ostream& os, const OutArray& a, const VtuOptions& o, std::optional<std::uint64_t> offset) {
  os << "        <DataArray type=\"" << a.type << "\" Name=\"" << a.name << "\"";
  if (a.components > 1) os << " NumberOfComponents=\"" << a.components << "\"";
  if (a.field_data) os << " NumberOfTuples=\"" << a.count << "\"";
  if (offset) {
    os << " format=\"appended\" offset=\"" << *offset << "\"/>\n";
    return;
  }
  os << " format=\"" << (o.binary ? "binary" : "ascii") << "\">\n";
  if (!o.binary) {
    a.ascii(os);
  } else if (o.zlib_level > 0) {
    // As VTK does: the header and the blocks as two base64 streams.
    const Payload p = payload_of(a, o.zlib_level);
    os << "          " << io::vtkxml::encode_base64(p.header) << io::vtkxml::encode_base64(p.compressed) << "\n";
  } else {
    // The byte count and the values base64-encoded together as one stream.
    std::string raw = payload_of(a, 0).header;
    raw.append(a.bytes);
    os << "          " << io::vtkxml::encode_base64(raw) << "\n";
  }
  os << "        </DataArray>\n";
}

// The arrays of the file by section, each section in file order.
struct Layout {
  std::vector<OutArray> field, point, cell, points, cells;
  std::vector<const OutArray*> in_file_order() const {
    std::vector<const OutArray*> all;
    for (const auto* section : {&field, &point, &cell, &points, &cells})
      for (const OutArray& a : *section) all.push_back(&a);
    return all;
  }
};

// The XML part of the file; with `offsets` (one per array in file order) the
// arrays are appended at those offsets.
void write_xml(std::ostream& os, std::size_t np, std::size_t nc, const Layout& layout, const VtuOptions& o,
               const std::vector<std::uint64_t>* offsets) {
  std::size_t i = 0;
  auto section = [&](const char* open, const char* close, const std::vector<OutArray>& arrays) {
    os << open;
    for (const OutArray& a : arrays)
      write_array(os, a, o, offsets ? std::optional<std::uint64_t>((*offsets)[i++]) : std::nullopt);
    os << close;
  };
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
     << " header_type=\"UInt64\"" << (o.zlib_level > 0 ? " compressor=\"vtkZLibDataCompressor\"" : "")
     << ">\n  <UnstructuredGrid>\n";
  section("    <FieldData>\n", "    </FieldData>\n", layout.field);
  os << "    <Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n";
  section("      <PointData>\n", "      </PointData>\n", layout.point);
  section("      <CellData>\n", "      </CellData>\n", layout.cell);
  section("      <Points>\n", "      </Points>\n", layout.points);
  section("      <Cells>\n", "      </Cells>\n", layout.cells);
  os << "    </Piece>\n  </UnstructuredGrid>\n";
}

// The whole file: XML, then for appended output the payloads after '_'.
void write_file(std::ostream& os, std::size_t np, std::size_t nc, const Layout& layout, const VtuOptions& o) {
  if (!o.appended) {
    write_xml(os, np, nc, layout, o, nullptr);
    os << "</VTKFile>\n";
    return;
  }
  std::vector<Payload> payloads;
  std::vector<std::uint64_t> offsets;
  std::uint64_t at = 0;
  for (const OutArray* a : layout.in_file_order()) {
    payloads.push_back(payload_of(*a, o.zlib_level));
    offsets.push_back(at);
    at += payloads.back().size();
  }
  write_xml(os, np, nc, layout, o, &offsets);
  os << "  <AppendedData encoding=\"raw\">\n   _";
  for (const Payload& p : payloads) {
    os.write(p.header.data(), static_cast<std::streamsize>(p.header.size()));
    const std::string_view body = p.compressed.empty() ? p.data : std::string_view(p.compressed);
    os.write(body.data(), static_cast<std::streamsize>(body.size()));
  }
  os << "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace

void write_vtu_poly(const PolyMesh& mesh, const std::string& path,
                    const std::vector<CellField>& extra, const VtuOptions& options) {
  if (options.zlib_level < 0 || options.zlib_level > 9)
    throw UsageError("write_vtu_poly: zlib level " + std::to_string(options.zlib_level) + " outside 0..9");
  if (options.zlib_level > 0 && !options.binary && !options.appended)
    throw UsageError("write_vtu_poly: zlib compression needs binary or appended output");
  const std::size_t nc = mesh.num_cells(), np = mesh.num_points();
  std::set<std::string> names{"material", "primal_vertex"};
  for (const CellField& f : extra) {
    const std::size_t n = std::visit([](const auto& v) { return v.size(); }, f.values);
    if (n != nc)
      throw UsageError("write_vtu_poly: field '" + f.name + "' has " + std::to_string(n) +
                       " values for " + std::to_string(nc) + " cells");
    if (f.name.empty() || f.name.find_first_of("\"<>&") != std::string::npos ||
        !names.insert(f.name).second)
      throw UsageError("write_vtu_poly: bad or duplicate cell field name '" + f.name + "'");
  }

  // Assemble every array first, so the stream callback only formats.
  std::vector<double> coords;
  coords.reserve(3 * np);
  std::vector<std::int8_t> class_dim(np);
  std::vector<std::int32_t> class_tag(np);
  for (std::size_t i = 0; i < np; ++i) {
    coords.insert(coords.end(), {mesh.points[i].x, mesh.points[i].y, mesh.points[i].z});
    class_dim[i] = mesh.point_class[i].dim;
    class_tag[i] = mesh.point_class[i].tag;
  }
  std::vector<std::int64_t> conn, offsets, faces, face_offsets, primal(nc);
  std::vector<std::int32_t> face_kind, face_tag;
  for (std::size_t c = 0; c < nc; ++c) {
    const CellId cell(c);
    for (PointId p : mesh.cell_points(cell)) conn.push_back(p.idx);
    offsets.push_back(static_cast<std::int64_t>(conn.size()));
    faces.push_back(static_cast<std::int64_t>(mesh.cell(cell).size()));
    for (HalfFace h : mesh.cell(cell)) {
      const std::vector<PointId> loop = mesh.oriented_loop(h);
      faces.push_back(static_cast<std::int64_t>(loop.size()));
      for (PointId p : loop) faces.push_back(p.idx);
      face_kind.push_back(static_cast<std::int32_t>(mesh.face_kind[h.face().idx]));
      face_tag.push_back(mesh.face_tag[h.face().idx]);
    }
    face_offsets.push_back(static_cast<std::int64_t>(faces.size()));
    primal[c] = mesh.cell_primal[c].valid() ? mesh.cell_primal[c].idx : -1;
  }
  const std::vector<std::uint8_t> types(nc, kVtkPolyhedron);

  Layout l;
  l.field = {out_array("Int32", "face_kind", 1, face_kind, true), out_array("Int32", "face_tag", 1, face_tag, true)};
  l.point = {out_array("Int8", "class_dim", 1, class_dim), out_array("Int32", "class_tag", 1, class_tag)};
  l.cell = {out_array("Int32", "material", 1, mesh.cell_material), out_array("Int64", "primal_vertex", 1, primal)};
  for (const CellField& f : extra) {
    if (const auto* d = std::get_if<std::vector<double>>(&f.values)) l.cell.push_back(out_array("Float64", f.name, 1, *d));
    else l.cell.push_back(out_array("Int32", f.name, 1, std::get<std::vector<std::int32_t>>(f.values)));
  }
  l.points = {out_array("Float64", "Points", 3, coords)};
  l.cells = {out_array("Int64", "connectivity", 1, conn), out_array("Int64", "offsets", 1, offsets),
             out_array("UInt8", "types", 1, types), out_array("Int64", "faces", 1, faces),
             out_array("Int64", "faceoffsets", 1, face_offsets)};
  write_file_atomically(path, [&](std::ostream& os) { write_file(os, np, nc, l, options); },
                        options.binary || options.appended);
}

}  // namespace polydual
