// write_vtu_surface: arrays as little-endian bytes, then ASCII or base64.
#include "io/vtu_surface_writer.h"

#include <bit>
#include <charconv>
#include <cstring>
#include <ostream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/vtk_xml.h"

namespace polydual {
namespace {

static_assert(std::endian::native == std::endian::little, "vtu binary mode assumes little endian");

enum class Type { Int8, Int32, Int64, UInt8, Float64 };

struct Array {
  const char* type;
  std::string name;
  int components;
  Type t;
  std::string bytes;  // little-endian values
};

template <class T, class Src>
Array make_array(const char* type, Type t, std::string name, int components, const Src& values) {
  Array a{type, std::move(name), components, t, {}};
  a.bytes.resize(values.size() * sizeof(T));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const T v = static_cast<T>(values[i]);
    std::memcpy(a.bytes.data() + i * sizeof(T), &v, sizeof(T));
  }
  return a;
}

template <class T>
void put_ascii(std::ostream& os, const std::string& bytes) {
  const std::size_t n = bytes.size() / sizeof(T);
  char buf[32];
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    const auto r = std::to_chars(buf, buf + sizeof buf, std::conditional_t<sizeof(T) == 1, int, T>(v));
    os.write(buf, r.ptr - buf);
    os.put(i + 1 == n || (i + 1) % 12 == 0 ? '\n' : ' ');
  }
}

void put_values(std::ostream& os, const Array& a, const VtuOptions& o) {
  if (!o.binary && !o.appended) {
    switch (a.t) {
      case Type::Int8: put_ascii<std::int8_t>(os, a.bytes); break;
      case Type::UInt8: put_ascii<std::uint8_t>(os, a.bytes); break;
      case Type::Int32: put_ascii<std::int32_t>(os, a.bytes); break;
      case Type::Int64: put_ascii<std::int64_t>(os, a.bytes); break;
      case Type::Float64: put_ascii<double>(os, a.bytes); break;
    }
    return;
  }
  using io::vtkxml::encode_base64;
  if (o.zlib_level > 0) {
    const auto z = io::vtkxml::zlib_compress(a.bytes, o.zlib_level, true);
    os << encode_base64(z.header) << encode_base64(z.blocks) << '\n';
    return;
  }
  const std::uint64_t n = a.bytes.size();
  os << encode_base64(std::string(reinterpret_cast<const char*>(&n), sizeof n)) << encode_base64(a.bytes) << '\n';
}

void put_array(std::ostream& os, const Array& a, const VtuOptions& o) {
  os << "        <DataArray type=\"" << a.type << "\" Name=\"" << a.name << "\"";
  if (a.components != 1) os << " NumberOfComponents=\"" << a.components << "\"";
  os << " format=\"" << (o.binary || o.appended ? "binary" : "ascii") << "\">\n";
  put_values(os, a, o);
  os << "        </DataArray>\n";
}

struct Layout {
  std::vector<Array> point_data, cell_data, points, cells;
};

Layout layout_of(const PolySurface& s, const std::vector<CellField>& extra) {
  const std::size_t np = s.num_points(), nc = s.num_polygons();
  std::vector<std::int8_t> dim(np);
  std::vector<std::int32_t> tag(np), surface(nc);
  std::vector<std::int64_t> primal(nc), conn(s.num_corners()), offsets(nc);
  std::vector<double> xyz(3 * np);
  for (std::size_t p = 0; p < np; ++p) {
    dim[p] = s.point_class(p).dim, tag[p] = s.point_class(p).tag;
    for (int k = 0; k < 3; ++k) xyz[3 * p + k] = s.point(p)[k];
  }
  std::size_t at = 0;
  for (std::size_t i = 0; i < nc; ++i) {
    surface[i] = s.surface(i), primal[i] = std::int64_t(s.primal_vertex(i));
    for (std::uint32_t p : s.polygon(i)) conn[at++] = p;
    offsets[i] = std::int64_t(at);
  }
  Layout l;
  l.point_data = {make_array<std::int8_t>("Int8", Type::Int8, "class_dim", 1, dim),
                  make_array<std::int32_t>("Int32", Type::Int32, "class_tag", 1, tag)};
  l.cell_data = {make_array<std::int32_t>("Int32", Type::Int32, "surface", 1, surface),
                 make_array<std::int64_t>("Int64", Type::Int64, "primal_vertex", 1, primal)};
  for (const CellField& f : extra) {
    if (const auto* d = std::get_if<std::vector<double>>(&f.values))
      l.cell_data.push_back(make_array<double>("Float64", Type::Float64, f.name, 1, *d));
    else
      l.cell_data.push_back(make_array<std::int32_t>("Int32", Type::Int32, f.name, 1, std::get<1>(f.values)));
  }
  l.points = {make_array<double>("Float64", Type::Float64, "Points", 3, xyz)};
  l.cells = {make_array<std::int64_t>("Int64", Type::Int64, "connectivity", 1, conn),
             make_array<std::int64_t>("Int64", Type::Int64, "offsets", 1, offsets),
             make_array<std::uint8_t>("UInt8", Type::UInt8, "types", 1, std::vector<std::uint8_t>(nc, 7))};
  return l;
}

void check_options(const PolySurface& s, const std::vector<CellField>& extra, const VtuOptions& o) {
  if (o.zlib_level < 0 || o.zlib_level > 9)
    throw UsageError("write_vtu_surface: zlib level " + std::to_string(o.zlib_level) + " outside 0..9");
  if (o.zlib_level > 0 && !o.binary && !o.appended)
    throw UsageError("write_vtu_surface: zlib compression needs binary or appended arrays, not ASCII");
  for (const CellField& f : extra) {
    const std::size_t n = std::visit([](const auto& v) { return v.size(); }, f.values);
    if (n != s.num_polygons())
      throw UsageError("write_vtu_surface: cell array '" + f.name + "' has " + std::to_string(n) + " values for " +
                       std::to_string(s.num_polygons()) + " polygons");
    if (f.name == "surface" || f.name == "primal_vertex")
      throw UsageError("write_vtu_surface: cell array name '" + f.name + "' is built in");
  }
}

void write_file(std::ostream& os, const PolySurface& s, const Layout& l, const VtuOptions& o) {
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\""
     << (o.zlib_level > 0 ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n  <UnstructuredGrid>\n"
     << "    <Piece NumberOfPoints=\"" << s.num_points() << "\" NumberOfCells=\"" << s.num_polygons() << "\">\n";
  auto section = [&](const char* name, const std::vector<Array>& arrays) {
    os << "      <" << name << ">\n";
    for (const Array& a : arrays) put_array(os, a, o);
    os << "      </" << name << ">\n";
  };
  section("PointData", l.point_data);
  section("CellData", l.cell_data);
  section("Points", l.points);
  section("Cells", l.cells);
  os << "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

}  // namespace

void write_vtu_surface(const PolySurface& s, const std::string& path, const std::vector<CellField>& extra,
                       const VtuOptions& options) {
  check_options(s, extra, options);
  const Layout l = layout_of(s, extra);
  write_file_atomically(path, [&](std::ostream& os) { write_file(os, s, l, options); });
}

}  // namespace polydual
