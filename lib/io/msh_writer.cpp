#include "io/msh_writer.h"

#include <algorithm>
#include <iomanip>
#include <limits>
#include <map>
#include <ostream>
#include <vector>

#include "core/atomic_file.h"

namespace polydual {
namespace {

struct Box {
  Point3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Point3 hi{-std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
  void add(const Point3& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
};

// What $Entities needs of one entity: its bounding box and, for model
// vertices, the point.
struct Entity {
  Box box;
  std::uint32_t first_vertex = 0;
};

}  // namespace

void write_msh(const TetSoup& soup, const std::string& path) {
  // Keyed by model tag; std::map keeps the output deterministic.
  std::map<std::int32_t, Entity> volumes, surfaces, curves, points;
  auto add = [&](std::map<std::int32_t, Entity>& to, std::int32_t tag, std::initializer_list<std::uint32_t> nodes) {
    auto [it, fresh] = to.try_emplace(tag);
    if (fresh) it->second.first_vertex = *nodes.begin();
    for (std::uint32_t v : nodes) it->second.box.add(soup.points.at(v));
  };
  for (std::size_t i = 0; i < soup.tets.size(); ++i) {
    const auto& t = soup.tets[i];
    add(volumes, i < soup.tet_region.size() ? soup.tet_region[i] : 1, {t[0], t[1], t[2], t[3]});
  }
  for (const TaggedTriangle& t : soup.triangles) add(surfaces, t.tag, {t.v[0], t.v[1], t.v[2]});
  for (const TaggedEdge& e : soup.edges) add(curves, e.tag, {e.v[0], e.v[1]});
  for (const TaggedVertex& c : soup.corners) add(points, c.tag, {c.v});

  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n"
        << points.size() << ' ' << curves.size() << ' ' << surfaces.size() << ' ' << volumes.size() << "\n";
    auto box = [&](const Box& b) {
      out << b.lo.x << ' ' << b.lo.y << ' ' << b.lo.z << ' ' << b.hi.x << ' ' << b.hi.y << ' ' << b.hi.z;
    };
    for (const auto& [tag, e] : points) {
      const Point3& p = soup.points[e.first_vertex];
      out << tag << ' ' << p.x << ' ' << p.y << ' ' << p.z << " 1 " << tag << "\n";
    }
    for (const auto* group : {&curves, &surfaces}) {
      for (const auto& [tag, e] : *group) {
        out << tag << ' ';
        box(e.box);
        out << " 1 " << tag << " 0\n";
      }
    }
    // Volume entity tags are 1..k (regions may be 0 or negative); the region
    // itself is the physical tag, which the reader prefers.
    std::int32_t volume_tag = 0;
    for (const auto& [region, e] : volumes) {
      out << ++volume_tag << ' ';
      box(e.box);
      out << " 1 " << region << " 0\n";
    }
    out << "$EndEntities\n$Nodes\n";
    const std::size_t n = soup.points.size();
    if (n == 0) {
      out << "0 0 0 0\n";
    } else {
      out << "1 " << n << " 1 " << n << "\n3 1 0 " << n << "\n";
      for (std::size_t i = 0; i < n; ++i) out << i + 1 << "\n";
      for (const Point3& p : soup.points) out << p.x << ' ' << p.y << ' ' << p.z << "\n";
    }
    out << "$EndNodes\n$Elements\n";
    // Elements keep the soup's order (error messages and determinism count on
    // "tet N"): one block per run of consecutive elements of one entity.
    std::map<std::int32_t, std::int32_t> volume_of;
    for (const auto& [region, e] : volumes) volume_of.emplace(region, static_cast<std::int32_t>(volume_of.size() + 1));
    struct Run {
      int dim, type;
      std::int32_t entity;
      std::size_t first, count;
    };
    std::vector<Run> runs;
    auto add_runs = [&](std::size_t n, int dim, int type, auto entity_of) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t entity = entity_of(i);
        if (!runs.empty() && runs.back().dim == dim && runs.back().entity == entity) ++runs.back().count;
        else runs.push_back({dim, type, entity, i, 1});
      }
    };
    add_runs(soup.corners.size(), 0, 15, [&](std::size_t i) { return soup.corners[i].tag; });
    add_runs(soup.edges.size(), 1, 1, [&](std::size_t i) { return soup.edges[i].tag; });
    add_runs(soup.triangles.size(), 2, 2, [&](std::size_t i) { return soup.triangles[i].tag; });
    add_runs(soup.tets.size(), 3, 4, [&](std::size_t i) {
      return volume_of.at(i < soup.tet_region.size() ? soup.tet_region[i] : 1);
    });
    const std::size_t nelem = soup.corners.size() + soup.edges.size() + soup.triangles.size() + soup.tets.size();
    out << runs.size() << ' ' << nelem << ' ' << (nelem ? 1 : 0) << ' ' << nelem << "\n";
    std::size_t id = 0;
    for (const Run& r : runs) {
      out << r.dim << ' ' << r.entity << ' ' << r.type << ' ' << r.count << "\n";
      for (std::size_t i = r.first; i < r.first + r.count; ++i) {
        out << ++id;
        switch (r.dim) {
          case 0: out << ' ' << soup.corners[i].v + 1; break;
          case 1: out << ' ' << soup.edges[i].v[0] + 1 << ' ' << soup.edges[i].v[1] + 1; break;
          case 2: for (std::uint32_t v : soup.triangles[i].v) out << ' ' << v + 1; break;
          default: for (std::uint32_t v : soup.tets[i]) out << ' ' << v + 1; break;
        }
        out << "\n";
      }
    }
    out << "$EndElements\n";
  });
}

}  // namespace polydual
