#include "io/vtu_writer.h"

#include <iomanip>
#include <ostream>

#include "core/atomic_file.h"

namespace polydual {

void write_vtu(const TetSoup& soup, const std::string& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    const std::size_t ncells = soup.tets.size() + soup.triangles.size();
    out << std::setprecision(17);
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
           "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << soup.points.size() << "\" NumberOfCells=\"" << ncells << "\">\n"
        << "      <Points>\n"
           "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Point3& p : soup.points) out << "          " << p.x << ' ' << p.y << ' ' << p.z << "\n";
    out << "        </DataArray>\n      </Points>\n      <Cells>\n"
           "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& t : soup.tets) out << "          " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << "\n";
    for (const auto& t : soup.triangles) out << "          " << t.v[0] << ' ' << t.v[1] << ' ' << t.v[2] << "\n";
    out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    std::size_t offset = 0;
    for (std::size_t i = 0; i < soup.tets.size(); ++i) out << "          " << (offset += 4) << "\n";
    for (std::size_t i = 0; i < soup.triangles.size(); ++i) out << "          " << (offset += 3) << "\n";
    out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < soup.tets.size(); ++i) out << "          10\n";
    for (std::size_t i = 0; i < soup.triangles.size(); ++i) out << "          5\n";
    out << "        </DataArray>\n      </Cells>\n      <CellData Scalars=\"region\">\n"
           "        <DataArray type=\"Int32\" Name=\"region\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < soup.tets.size(); ++i)
      out << "          " << (i < soup.tet_region.size() ? soup.tet_region[i] : 1) << "\n";
    for (const auto& t : soup.triangles) out << "          " << t.tag << "\n";
    out << "        </DataArray>\n      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

}  // namespace polydual
