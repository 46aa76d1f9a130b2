// Gmsh msh 4.1: $Entities (points, curves, surfaces, volumes with physical
// tags), $PartitionedEntities (partition pieces of those, with their parent),
// $Nodes and $Elements grouped in entity blocks, sparse node tags. Binary
// files store counts and tags as size_t (data size 8) and entity fields as
// int, exactly as the ASCII layout orders them.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "io/msh_internal.h"
#include "io/record_checks.h"
#include "io/unattached.h"

namespace polydual::io::msh {
namespace {

constexpr std::int64_t kInt32Min = std::numeric_limits<std::int32_t>::min();
constexpr std::int64_t kInt32Max = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kMaxCount = std::numeric_limits<std::uint32_t>::max();

// A model entity of $Entities.
struct Entity {
  std::vector<std::int32_t> physicals;
  std::array<double, 6> box{};  // min xyz, max xyz (a point: its xyz twice)
};
// A partition piece of $PartitionedEntities: its parent model entity.
struct Piece {
  int parent_dim = 0;
  std::int32_t parent = 0;
  std::vector<std::int32_t> physicals;
};
// What the elements of one entity block become.
struct Target {
  enum Kind { keep, partition_boundary, ghost } kind = keep;
  std::int32_t model = 0;  // the model entity (of the block's dimension)
  std::int32_t tag = 0;    // the soup tag: region for tets, the model entity otherwise
};

struct Reader {
  TextCursor& cur;
  bool binary;
  TetSoup soup;
  NodeTags node_index;
  std::array<std::map<std::int32_t, Entity>, 4> entities;
  bool have_entities = false;
  std::array<std::unordered_map<std::int32_t, Piece>, 4> pieces;
  std::unordered_set<std::int32_t> ghosts;  // ghost entities (of the top dimension)
  std::size_t partitions = 0;
  bool partitioned = false;
  std::map<std::pair<int, std::int32_t>, std::string> names;
  std::array<std::set<std::int32_t>, 4> with_elements;  // model entities given elements
  std::size_t boundary_elements = 0, ghost_elements = 0, merged_nodes = 0;
  int max_order = 1;
  std::vector<ElementRun> runs;  // the kept elements of each block (group set in finish)

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

  // "numPhysicalTags physicalTag..." of an entity record.
  std::vector<std::int32_t> physical_tags() {
    const std::int64_t n = count("the number of physical tags", 1 << 20);
    cur.check_count(n, binary ? 4 : 2, "physical tag");
    std::vector<std::int32_t> tags(n);
    for (auto& p : tags) p = int_field("physical tag");
    return tags;
  }
  // "numBounding tag..." of a curve, surface or volume record: tags of
  // entities of dimension d - 1, signed by orientation (a curve's end point
  // is negative). In $Entities (`check`) each must be declared there, and
  // is, since points come first, then curves, then surfaces; partition pieces
  // are bounded by other pieces and are not checked. The tags are not used.
  void bounding_entities(int d, std::int32_t t, bool check) {
    static constexpr const char* kDim[] = {"point", "curve", "surface", "volume"};
    const std::int64_t n = count("the number of bounding entities", 1 << 24);
    cur.check_count(n, binary ? 4 : 2, "bounding entity");
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t b = int_field("bounding entity tag");
      const std::int64_t a = b < 0 ? -b : b;
      if (check && (a > kInt32Max || !entities[d - 1].count(static_cast<std::int32_t>(a))))
        fail(std::string(kDim[d]) + " " + std::to_string(t) + " is bounded by " + kDim[d - 1] + " " +
             std::to_string(b) + ", which is not in $Entities (no " + kDim[d - 1] + " " + std::to_string(a) +
             " is declared)");
    }
  }
  std::array<double, 6> box(int d, const char* what) {
    std::array<double, 6> b{};
    for (int k = 0; k < (d == 0 ? 3 : 6); ++k) b[k] = coordinate(what);
    if (d == 0) std::copy(b.begin(), b.begin() + 3, b.begin() + 3);
    return b;
  }
  std::array<std::int64_t, 4> entity_counts(const char* what) {
    std::array<std::int64_t, 4> n{};
    for (int d = 0; d < 4; ++d) n[d] = count(what);
    return n;
  }

  void entities_section() {
    if (have_entities) fail("second $Entities section");
    have_entities = true;
    if (binary) cur.skip_end_of_line();
    const std::array<std::int64_t, 4> n = entity_counts("the number of entities in $Entities");
    for (int d = 0; d < 4; ++d) {
      cur.check_count(n[d], binary ? 4 + 24 + 8 : 10, "entity");
      for (std::int64_t i = 0; i < n[d]; ++i) {
        const std::int32_t t = int_field("the $Entities block");
        Entity e;
        e.box = box(d, "the $Entities block");
        e.physicals = physical_tags();
        if (d > 0) bounding_entities(d, t, true);
        if (!entities[d].emplace(t, std::move(e)).second)
          fail("entity (" + std::to_string(d) + ", " + std::to_string(t) + ") defined twice in $Entities");
      }
    }
    expect_end(cur, "Entities");
  }

  // Gmsh's layout: partitions, ghost entities (tag, partition), then per
  // dimension "tag parentDim parentTag numPartitions partition... box
  // numPhysicals physical... [numBounding bounding...]".
  void partitioned_entities_section() {
    if (!have_entities) fail("$PartitionedEntities before $Entities");
    if (partitioned) fail("second $PartitionedEntities section");
    partitioned = true;
    if (binary) cur.skip_end_of_line();
    partitions = static_cast<std::size_t>(count("the number of partitions"));
    const std::int64_t nghosts = count("the number of ghost entities");
    cur.check_count(nghosts, binary ? 8 : 4, "ghost entity");
    for (std::int64_t i = 0; i < nghosts; ++i) {
      ghosts.insert(int_field("ghost entity tag"));
      int_field("ghost entity partition");
    }
    const std::array<std::int64_t, 4> n = entity_counts("the number of partitioned entities");
    for (int d = 0; d < 4; ++d) {
      cur.check_count(n[d], binary ? 12 + 8 + 24 + 8 : 14, "partitioned entity");
      for (std::int64_t i = 0; i < n[d]; ++i) {
        const std::int32_t t = int_field("partitioned entity tag");
        Piece p;
        p.parent_dim = int_field("parent dimension", 0, 3);
        p.parent = int_field("parent tag");
        const std::int64_t np = count("the number of partitions of an entity", 1 << 24);
        cur.check_count(np, binary ? 4 : 2, "partition tag");
        for (std::int64_t k = 0; k < np; ++k) int_field("partition tag");
        box(d, "the $PartitionedEntities block");
        p.physicals = physical_tags();
        if (d > 0) bounding_entities(d, t, false);
        if (p.parent_dim < d)
          fail("partitioned entity (" + std::to_string(d) + ", " + std::to_string(t) + ") has a parent of dimension " +
               std::to_string(p.parent_dim));
        if (p.parent_dim == d && !entities[d].count(p.parent))
          fail("partitioned entity (" + std::to_string(d) + ", " + std::to_string(t) + "): parent entity (" +
               std::to_string(d) + ", " + std::to_string(p.parent) + ") is not in $Entities");
        if (!pieces[d].emplace(t, std::move(p)).second)
          fail("entity (" + std::to_string(d) + ", " + std::to_string(t) + ") defined twice in $PartitionedEntities");
      }
    }
    expect_end(cur, "PartitionedEntities");
  }

  // Node tags of one block; a tag seen before is an error, except in a
  // partitioned file, which may repeat the nodes partitions share: those are
  // merged into the first when their coordinates agree (checked once read).
  void node_block_tags(std::int64_t n, std::vector<std::pair<std::uint32_t, std::uint32_t>>& repeats) {
    for (std::int64_t i = 0; i < n; ++i) {
      const std::uint64_t t = tag(binary ? "the $Nodes block (expected a node tag)" : "node tag");
      const std::uint32_t at = static_cast<std::uint32_t>(soup.points.size() + i);
      const std::uint32_t had = node_index.insert(t, at);
      if (had == NodeTags::kNone) continue;
      if (!partitioned) fail("node tag " + std::to_string(t) + " defined twice");
      repeats.emplace_back(at, had);
    }
  }

  void nodes_section() {
    if (binary) cur.skip_end_of_line();
    const std::int64_t nblocks = count("the number of node entity blocks");
    const std::int64_t nnodes = count("the number of nodes");
    count("the minimum node tag", std::numeric_limits<std::int64_t>::max());
    const std::int64_t max_tag = count("the maximum node tag", std::numeric_limits<std::int64_t>::max());
    cur.check_count(nblocks, binary ? 20 : 8, "node entity block");
    cur.check_count(nnodes, binary ? 32 : 8, "node");
    soup.points.reserve(nnodes);
    node_index.reserve(std::uint64_t(nnodes), std::uint64_t(max_tag));
    std::vector<std::pair<std::uint32_t, std::uint32_t>> repeats;  // (this copy, first copy)
    for (std::int64_t b = 0; b < nblocks; ++b) {
      int_field("entity dimension", 0, 3);
      int_field("entity tag");
      const std::int32_t parametric = int_field("parametric flag", 0, 1);
      if (parametric != 0) fail("parametric nodes are not supported (save without parametric coordinates)");
      const std::int64_t n = count("a $Nodes entity block header");
      if (n > nnodes - static_cast<std::int64_t>(soup.points.size()))
        fail("node block of " + std::to_string(n) + " nodes exceeds the " + std::to_string(nnodes) +
             " nodes announced");
      cur.check_count(n, binary ? 32 : 8, "node");
      repeats.clear();
      node_block_tags(n, repeats);
      for (std::int64_t i = 0; i < n; ++i) {
        Point3 p;
        for (int k = 0; k < 3; ++k) p[k] = coordinate("the $Nodes block (expected 3 doubles)");
        soup.points.push_back(p);
      }
      for (const auto& [copy, first] : repeats)
        if (!(soup.points[copy] == soup.points[first]))
          fail("node " + std::to_string(first + 1) + " (in file order) is repeated with other coordinates");
      merged_nodes += repeats.size();
    }
    if (static_cast<std::int64_t>(soup.points.size()) != nnodes)
      fail("$Nodes announces " + std::to_string(nnodes) + " nodes but its blocks hold " +
           std::to_string(soup.points.size()));
    expect_end(cur, "Nodes");
  }

  std::uint32_t node(std::uint64_t element, std::uint64_t t) const {
    const std::uint32_t at = node_index.find(t);
    if (at == NodeTags::kNone)
      fail("element " + std::to_string(element) + ": node " + std::to_string(t) + " is not defined in $Nodes");
    return at;
  }

  // The model entity of block entity (dim, tag) and the tag its elements get:
  // the volume's first physical tag for tets (Gmsh's material), the model
  // entity otherwise. Partition pieces map to their parent; pieces of a higher
  // dimensional parent are partition boundaries, not model entities.
  // A dimension $Entities declares nothing of (meshio writes $Entities from
  // its nodes' gmsh:dim_tags only) is not checked against it.
  Target target(int dim, std::int32_t entity) const {
    if (!have_entities || (entities[dim].empty() && pieces[dim].empty())) return {Target::keep, entity, entity};
    Target t{Target::keep, entity, entity};
    if (partitioned && dim == 3 && ghosts.count(entity)) return {Target::ghost, entity, entity};
    if (auto p = pieces[dim].find(entity); p != pieces[dim].end()) {
      if (p->second.parent_dim != dim) return {Target::partition_boundary, entity, entity};
      t.model = t.tag = p->second.parent;
    }
    auto it = entities[dim].find(t.model);
    if (it == entities[dim].end())
      fail("entity (" + std::to_string(dim) + ", " + std::to_string(entity) + ") is not in $Entities" +
           (partitioned ? " nor in $PartitionedEntities" : ""));
    if (dim == 3 && !it->second.physicals.empty()) t.tag = it->second.physicals.front();
    return t;
  }

  void add(Use use, const std::array<std::uint32_t, 8>& v, std::int32_t t, std::uint64_t id) {
    switch (use) {
      case Use::pyramid: case Use::prism: case Use::hex:
        soup.other_cells.push_back({use_cell_type(use), v, t, id});
        break;
      case Use::quad: soup.quads.push_back({{v[0], v[1], v[2], v[3]}, t}); break;
      case Use::tet:
        soup.tets.push_back({v[0], v[1], v[2], v[3]});
        soup.tet_region.push_back(t);
        break;
      case Use::triangle: {
        soup.triangles.push_back({{v[0], v[1], v[2]}, t});
        const std::string bad = repeated_vertex(soup.triangles.back().v, "triangle");
        if (!bad.empty()) fail("element " + std::to_string(id) + ": " + bad);
        break;
      }
      case Use::line: soup.edges.push_back({{v[0], v[1]}, t}); break;  // degenerate ones: drop_unattached
      case Use::point: soup.corners.push_back({v[0], t}); break;
      case Use::ignore: break;
    }
  }

  // One entity block: "dim entity type n" then n records "id node...".
  void element_block(std::int64_t& seen, std::int64_t nelements) {
    const std::int32_t dim = int_field("entity dimension", 0, 3);
    const std::int32_t entity = int_field("entity tag");
    const std::int32_t type = int_field("element type", 0, kInt32Max);
    const std::int64_t n = count("the number of elements in a block");
    const Use use = element_use(cur, type);
    const int nn = node_count(type);
    const int expected_dim = use_dim(use);
    if (use != Use::ignore && expected_dim != dim)
      fail("element type " + std::to_string(type) + " in an entity block of dimension " + std::to_string(dim));
    if (n > nelements - seen)
      fail("element block of " + std::to_string(n) + " elements exceeds the " + std::to_string(nelements) +
           " elements announced");
    cur.check_count(n, binary ? 8 * (1 + nn) : 2 * (1 + nn), "element");
    const Target t = use == Use::ignore ? Target{} : target(dim, entity);
    const bool keep = use != Use::ignore && t.kind == Target::keep;
    const bool mixed = use == Use::pyramid || use == Use::prism || use == Use::hex || use == Use::quad;
    if (keep && n > 0 && mixed) {  // never in a homology chain's run
      with_elements[dim].insert(t.model);
    } else if (keep && n > 0) {
      with_elements[dim].insert(t.model);
      max_order = std::max(max_order, element_order(type));
      const std::size_t at = dim == 3 ? soup.tets.size() : dim == 2 ? soup.triangles.size()
                             : dim == 1 ? soup.edges.size() : soup.corners.size();
      runs.push_back({dim, t.model, 0, at, at + std::size_t(n)});
    }
    if (use != Use::ignore && t.kind == Target::partition_boundary) boundary_elements += n;
    if (use != Use::ignore && t.kind == Target::ghost) ghost_elements += n;
    std::array<std::uint32_t, 8> v{};
    const int corners = use_corners(use);
    for (std::int64_t e = 0; e < n; ++e) {
      const char* what = binary ? "the $Elements block (expected an element record)" : "element tag";
      const std::uint64_t id = tag(what);
      for (int k = 0; k < nn; ++k) {
        const std::uint64_t nt = tag(binary ? what : "node tag");
        if (k < corners) v[k] = node(id, nt);
      }
      if (keep) add(use, v, t.tag, id);
    }
    seen += n;
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
    for (std::int64_t b = 0; b < nblocks; ++b) element_block(seen, nelements);
    if (seen != nelements)
      fail("$Elements announces " + std::to_string(nelements) + " elements but its blocks hold " +
           std::to_string(seen));
    expect_end(cur, "Elements");
  }

  void physical_names() {
    const std::int64_t n = cur.integer_in("number of physical names", 0, 1 << 30);
    cur.check_count(n, 6, "physical name");
    for (std::int64_t i = 0; i < n; ++i) {
      const int dim = static_cast<int>(cur.integer_in("physical dimension", 0, 3));
      const std::int32_t t = static_cast<std::int32_t>(cur.integer_in("physical tag", kInt32Min, kInt32Max));
      names[{dim, t}] = physical_name(cur);
    }
    expect_end(cur, "PhysicalNames");
  }

  void finish();
  bool warn_missing();
  void make_groups();
  bool is_chain(int dim, std::int32_t entity) const;
  std::vector<ElementRun> chain_runs() const;
};

// A model entity that Gmsh's homology solver made: every physical group it
// is in has a chain's name (io/unattached.h).
bool Reader::is_chain(int dim, std::int32_t entity) const {
  const auto e = entities[dim].find(entity);
  if (e == entities[dim].end() || e->second.physicals.empty()) return false;
  for (std::int32_t p : e->second.physicals) {
    const auto n = names.find({dim, p});
    if (n == names.end() || !is_chain_name(n->second)) return false;
  }
  return true;
}

std::vector<ElementRun> Reader::chain_runs() const {
  std::vector<ElementRun> out;
  for (ElementRun r : runs)
    if (is_chain(r.dim, r.entity)) {
      r.group = entities[r.dim].at(r.entity).physicals.front();
      out.push_back(r);
    }
  return out;
}

// A curve Gmsh collapsed to a point (as at a sphere's pole) gets no element;
// its $Entities box is then within Gmsh's tolerance of a point.
bool is_degenerate(const Entity& e, double model_size) {
  double extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, e.box[k + 3] - e.box[k]);
  return extent <= 1e-6 * model_size;
}

// Entities of $Entities that the file gives no element (Gmsh writes only
// physical groups unless -save_all): volumes missing from the mesh, and a
// boundary classification that cannot be taken as complete. True when none.
bool Reader::warn_missing() {
  std::array<double, 6> all{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                            std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for (const auto& [t, e] : entities[0])
    for (int k = 0; k < 3; ++k) all[k] = std::min(all[k], e.box[k]), all[k + 3] = std::max(all[k + 3], e.box[k]);
  const double size = std::max({all[3] - all[0], all[4] - all[1], all[5] - all[2], 0.0});
  std::array<std::size_t, 4> missing{};
  for (int d = 1; d < 4; ++d)
    for (const auto& [t, e] : entities[d])
      if (!with_elements[d].count(t) && !(d == 1 && is_degenerate(e, size))) ++missing[d];
  if (missing[1] + missing[2] + missing[3] == 0) return true;
  std::string w = soup.source + ": $Entities lists " + count_of(missing[3], "volume", "volumes") + ", " +
                  count_of(missing[2], "surface", "surfaces") + " and " + count_of(missing[1], "curve", "curves") +
                  " with no element in the file (Gmsh without -save_all writes only physical groups)";
  if (missing[3] > 0) w += ": the tets of those volumes are missing from the mesh";
  w += std::string(missing[3] > 0 ? ";" : ":") + " the classification is completed from the tets";
  soup.warnings.push_back(std::move(w));
  return false;
}

// Physical groups as the soup carries them: a volume by its region tag, a
// lower-dimensional entity by its own tag; named by $PhysicalNames.
void Reader::make_groups() {
  std::map<std::pair<int, std::int32_t>, std::set<std::int32_t>> held;
  for (int d = 0; d < 4; ++d)
    for (const auto& [t, e] : entities[d]) {
      if (!with_elements[d].count(t)) continue;
      for (std::int32_t p : e.physicals) held[{d, p}].insert(d == 3 ? e.physicals.front() : t);
    }
  for (const auto& [key, name] : names) held[key];
  for (const auto& [key, tags] : held) {
    auto n = names.find(key);
    soup.groups.push_back({key.first, key.second, n == names.end() ? std::string() : n->second,
                           std::vector<std::int32_t>(tags.begin(), tags.end())});
  }
}

void Reader::finish() {
  const bool complete = have_entities && !entities[2].empty() && !entities[3].empty() && warn_missing();
  if (have_entities) make_groups();
  if (partitioned)
    soup.warnings.push_back(soup.source + ": partitioned mesh (" + count_of(partitions, "partition", "partitions") +
                            ") read as one, partition pieces mapped to their model entities; dropped " +
                            count_of(boundary_elements, "element", "elements") + " on partition boundaries and " +
                            count_of(ghost_elements, "ghost element", "ghost elements") + ", merged " +
                            count_of(merged_nodes, "repeated node", "repeated nodes"));
  if (const std::string w = high_order_warning(soup.source, max_order); !w.empty()) soup.warnings.push_back(w);
  ElementOrigins origins;
  for (int d = 0; d < 3; ++d)
    for (const auto& [t, e] : entities[d])
      if (!is_chain(d, t)) origins.declared[d].push_back(t);
  drop_chains(soup, origins, chain_runs());
  drop_unattached(soup, origins);
  soup.full_classification = complete && !soup.triangles.empty();
}

}  // namespace

TetSoup read_msh4(TextCursor& cur, bool binary, bool surfaces) {
  Reader r{cur, binary, {}, {}, {}, false, {}, {}, 0, false, {}, {}, 0, 0, 0, 1, {}};
  r.soup.source = cur.source();
  bool have_nodes = false;
  const std::string elements_place = read_sections(cur, [&](std::string_view name) {
    if (name == "Entities" || name == "PartitionedEntities") {
      if (have_nodes) cur.fail("$" + std::string(name) + " after $Nodes");
      if (name == "Entities") r.entities_section(); else r.partitioned_entities_section();
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
  require_tets(r.soup, cur, elements_place, surfaces);
  r.finish();
  return std::move(r.soup);
}

}  // namespace polydual::io::msh
