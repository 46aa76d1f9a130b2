// Gmsh msh 4.1: $Entities (points, curves, surfaces, volumes with physical
// tags), $Nodes and $Elements grouped in entity blocks, sparse node tags.
// Binary files store counts and tags as size_t (data size 8) and entity
// fields as int, exactly as the ASCII layout orders them.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <vector>

#include "io/msh_internal.h"
#include "io/record_checks.h"

namespace polydual::io::msh {
namespace {

constexpr std::int64_t kInt32Min = std::numeric_limits<std::int32_t>::min();
constexpr std::int64_t kInt32Max = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kMaxCount = std::numeric_limits<std::uint32_t>::max();

struct Reader {
  TextCursor& cur;
  bool binary;
  TetSoup soup;
  std::unordered_map<std::uint64_t, std::uint32_t> node_index;
  // Per dimension: entity tag -> first physical tag (if any).
  std::array<std::unordered_map<std::int32_t, std::optional<std::int32_t>>, 4> entities;
  bool have_entities = false;

  [[noreturn]] void fail(const std::string& what) const { cur.fail(what); }

  // Reads a count (size_t in binary) in [0, max].
  std::int64_t count(const char* what, std::int64_t max = kMaxCount) {
    if (!binary) return cur.integer_in(what, 0, max);
    const std::uint64_t v = cur.binary<std::uint64_t>(what);
    if (v > static_cast<std::uint64_t>(max)) fail(std::string(what) + " " + std::to_string(v) + " out of range");
    return static_cast<std::int64_t>(v);
  }
  // An entity field (int in binary).
  std::int32_t int_field(const char* what, std::int64_t lo = kInt32Min, std::int64_t hi = kInt32Max) {
    if (!binary) return static_cast<std::int32_t>(cur.integer_in(what, lo, hi));
    const std::int64_t v = cur.binary<std::int32_t>(what);
    if (v < lo || v > hi)
      fail(std::string(what) + " " + std::to_string(v) + " out of range (" + std::to_string(lo) + ".." +
           std::to_string(hi) + ")");
    return static_cast<std::int32_t>(v);
  }
  // A node or element tag (size_t in binary).
  std::uint64_t tag(const char* what) {
    if (!binary) return static_cast<std::uint64_t>(cur.integer_in(what, 0, std::numeric_limits<std::int64_t>::max()));
    return cur.binary<std::uint64_t>(what);
  }
  double coordinate(const char* what) { return binary ? binary_coordinate(cur, what) : cur.real("coordinate"); }

  void entities_section() {
    if (have_entities) cur.fail("second $Entities section");
    have_entities = true;
    if (binary) cur.skip_end_of_line();
    std::array<std::int64_t, 4> n{};
    for (int d = 0; d < 4; ++d) n[d] = count("the number of entities in $Entities");
    for (int d = 0; d < 4; ++d) {
      cur.check_count(n[d], binary ? 4 + 24 + 8 : 10, "entity");
      for (std::int64_t i = 0; i < n[d]; ++i) {
        const char* what = "the $Entities block";
        const std::int32_t tag = int_field(what);
        for (int k = 0; k < (d == 0 ? 3 : 6); ++k) coordinate(what);
        const std::int64_t nphys = count("the number of physical tags", 1 << 20);
        cur.check_count(nphys, binary ? 4 : 2, "physical tag");
        std::optional<std::int32_t> physical;
        for (std::int64_t k = 0; k < nphys; ++k) {
          const std::int32_t p = int_field("physical tag");
          if (!physical) physical = p;
        }
        if (d > 0) {
          const std::int64_t nbound = count("the number of bounding entities", 1 << 24);
          cur.check_count(nbound, binary ? 4 : 2, "bounding entity");
          for (std::int64_t k = 0; k < nbound; ++k) int_field("bounding entity tag");
        }
        if (!entities[d].emplace(tag, physical).second)
          fail("entity (" + std::to_string(d) + ", " + std::to_string(tag) + ") defined twice in $Entities");
      }
    }
    expect_end(cur, "Entities");
  }

  void nodes_section() {
    if (binary) cur.skip_end_of_line();
    const std::int64_t nblocks = count("the number of node entity blocks");
    const std::int64_t nnodes = count("the number of nodes");
    count("the minimum node tag", std::numeric_limits<std::int64_t>::max());
    count("the maximum node tag", std::numeric_limits<std::int64_t>::max());
    cur.check_count(nblocks, binary ? 20 : 8, "node entity block");
    cur.check_count(nnodes, binary ? 32 : 8, "node");
    soup.points.reserve(nnodes);
    node_index.reserve(nnodes);
    std::vector<std::uint64_t> tags;
    for (std::int64_t b = 0; b < nblocks; ++b) {
      const char* what = "a $Nodes entity block header";
      int_field("entity dimension", 0, 3);
      int_field("entity tag");
      const std::int32_t parametric = int_field("parametric flag", 0, 1);
      if (parametric != 0) fail("parametric nodes are not supported (save without parametric coordinates)");
      const std::int64_t n = count(what);
      if (n > nnodes - static_cast<std::int64_t>(soup.points.size()))
        fail("node block of " + std::to_string(n) + " nodes exceeds the " + std::to_string(nnodes) +
             " nodes announced");
      cur.check_count(n, binary ? 32 : 8, "node");
      tags.clear();
      for (std::int64_t i = 0; i < n; ++i) {
        const std::uint64_t t = tag(binary ? "the $Nodes block (expected a node tag)" : "node tag");
        if (!node_index.emplace(t, static_cast<std::uint32_t>(soup.points.size() + i)).second)
          fail("node tag " + std::to_string(t) + " defined twice");
        tags.push_back(t);
      }
      for (std::int64_t i = 0; i < n; ++i) {
        Point3 p;
        for (int k = 0; k < 3; ++k) p[k] = coordinate("the $Nodes block (expected 3 doubles)");
        soup.points.push_back(p);
      }
    }
    if (static_cast<std::int64_t>(soup.points.size()) != nnodes)
      fail("$Nodes announces " + std::to_string(nnodes) + " nodes but its blocks hold " +
           std::to_string(soup.points.size()));
    expect_end(cur, "Nodes");
  }

  template <std::size_t N>
  void check(const std::array<std::uint32_t, N>& v, std::uint64_t id, const char* what) const {
    const std::string bad = repeated_vertex(v, what);
    if (!bad.empty()) fail("element " + std::to_string(id) + ": " + bad);
  }

  std::uint32_t node(std::uint64_t element, std::uint64_t t) const {
    auto it = node_index.find(t);
    if (it == node_index.end())
      fail("element " + std::to_string(element) + ": node " + std::to_string(t) + " is not defined in $Nodes");
    return it->second;
  }

  // The tag an element of entity (dim, tag) carries: the volume's first
  // physical tag for tets (Gmsh's material), the entity tag otherwise (model
  // faces/edges/vertices are the entities themselves).
  std::int32_t element_tag(int dim, std::int32_t entity) const {
    if (!have_entities) return entity;
    auto it = entities[dim].find(entity);
    if (it == entities[dim].end())
      fail("entity (" + std::to_string(dim) + ", " + std::to_string(entity) + ") is not in $Entities");
    if (dim == 3 && it->second) return *it->second;
    return entity;
  }

  void elements_section() {
    if (binary) cur.skip_end_of_line();
    const std::int64_t nblocks = count("the number of element entity blocks");
    const std::int64_t nelements = count("the number of elements");
    count("the minimum element tag", std::numeric_limits<std::int64_t>::max());
    count("the maximum element tag", std::numeric_limits<std::int64_t>::max());
    cur.check_count(nblocks, binary ? 20 : 8, "element entity block");
    cur.check_count(nelements, binary ? 16 : 4, "element");
    std::int64_t seen = 0;
    std::array<std::uint32_t, 4> v{};
    for (std::int64_t b = 0; b < nblocks; ++b) {
      const std::int32_t dim = int_field("entity dimension", 0, 3);
      const std::int32_t entity = int_field("entity tag");
      const std::int32_t type = int_field("element type", 0, kInt32Max);
      const std::int64_t n = count("the number of elements in a block");
      const Use use = element_use(cur, type);
      const int nn = node_count(type);
      const int expected_dim = use == Use::tet ? 3 : use == Use::triangle ? 2 : use == Use::line ? 1 : 0;
      if (use != Use::ignore && expected_dim != dim)
        fail("element type " + std::to_string(type) + " in an entity block of dimension " + std::to_string(dim));
      if (n > nelements - seen)
        fail("element block of " + std::to_string(n) + " elements exceeds the " + std::to_string(nelements) +
             " elements announced");
      cur.check_count(n, binary ? 8 * (1 + nn) : 2 * (1 + nn), "element");
      const std::int32_t t = use == Use::ignore ? 0 : element_tag(dim, entity);
      for (std::int64_t e = 0; e < n; ++e) {
        const char* what = binary ? "the $Elements block (expected an element record)" : "element tag";
        const std::uint64_t id = tag(what);
        for (int k = 0; k < nn; ++k) {
          const std::uint64_t nt = tag(binary ? what : "node tag");
          if (k < 4 && use != Use::ignore) v[k] = node(id, nt);
        }
        switch (use) {
          case Use::tet:
            soup.tets.push_back(v);
            soup.tet_region.push_back(t);
            break;
          case Use::triangle:
            soup.triangles.push_back({{v[0], v[1], v[2]}, t});
            check(soup.triangles.back().v, id, "triangle");
            break;
          case Use::line:
            soup.edges.push_back({{v[0], v[1]}, t});
            check(soup.edges.back().v, id, "line");
            break;
          case Use::point: soup.corners.push_back({v[0], t}); break;
          case Use::ignore: break;
        }
      }
      seen += n;
    }
    if (seen != nelements)
      fail("$Elements announces " + std::to_string(nelements) + " elements but its blocks hold " +
           std::to_string(seen));
    expect_end(cur, "Elements");
  }

  void physical_names() {
    const std::int64_t n = cur.integer_in("number of physical names", 0, 1 << 30);
    cur.check_count(n, 6, "physical name");
    for (std::int64_t i = 0; i < n; ++i) {
      cur.integer_in("physical dimension", 0, 3);
      cur.integer("physical tag");
      if (cur.rest_of_line().find('"') == std::string_view::npos) cur.fail("expected a quoted physical name");
    }
    expect_end(cur, "PhysicalNames");
  }
};

}  // namespace

TetSoup read_msh4(TextCursor& cur, bool binary) {
  Reader r{cur, binary, {}, {}, {}, false};
  bool have_nodes = false;
  read_sections(cur, [&](std::string_view name) {
    if (name == "Entities") {
      if (have_nodes) cur.fail("$Entities after $Nodes");
      r.entities_section();
    } else if (name == "Nodes") {
      r.nodes_section();
      have_nodes = true;
    } else if (name == "Elements") {
      r.elements_section();
    } else if (name == "PhysicalNames") {
      r.physical_names();
    } else {
      return false;
    }
    return true;
  });
  r.soup.full_classification = r.have_entities && !r.soup.triangles.empty();
  return std::move(r.soup);
}

}  // namespace polydual::io::msh
