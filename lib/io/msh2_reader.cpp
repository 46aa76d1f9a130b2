// Gmsh msh 2.x: $Nodes "id x y z", $Elements "id type ntags tags... nodes...".
// Binary files keep the counts as text lines but the records as native ints and
// doubles; binary $Elements come in blocks headed by (type, count, ntags).
// Versions 2.0 and 2.1 are read as 2.2 (Gmsh's own reader does the same): only
// the third and later element tags (partitions, not read) and 2.0's
// $PhysicalNames without dimensions differ. Netgen's "Gmsh2 Format" export
// writes "2.000000 0 8" with 2.2's layout.
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include <algorithm>
#include <map>
#include <set>

#include "io/msh_internal.h"
#include "io/record_checks.h"
#include "io/unattached.h"

namespace polydual::io::msh {
namespace {

struct Reader {
  TextCursor& cur;
  bool binary;
  TetSoup soup;
  NodeTags node_index;  // msh 2.2 ids as unsigned (a negative id is a huge tag)
  ElementOrigins origins;  // the elementary tag of every triangle, edge, corner
  std::map<std::pair<int, std::int32_t>, std::string> names;
  std::map<std::pair<int, std::int32_t>, std::set<std::int32_t>> physicals;  // (dim, tag) -> soup tags
  int max_order = 1;
  int minor = 2;                   // the x of version 2.x
  std::vector<ElementRun> runs;    // consecutive elements of one (dim, physical, elementary)

  [[noreturn]] void fail(const std::string& what) const { cur.fail(what); }

  void nodes() {
    const std::int64_t n = cur.integer_in("number of nodes", 0, std::numeric_limits<std::uint32_t>::max());
    cur.check_count(n, binary ? 4 + 3 * 8 : 8, "node");
    if (binary) cur.skip_end_of_line();
    soup.points.reserve(n);
    node_index.reserve(std::uint64_t(n), std::numeric_limits<std::uint64_t>::max());
    for (std::int64_t i = 0; i < n; ++i) {
      std::int64_t id;
      Point3 p;
      if (binary) {
        id = cur.binary<std::int32_t>("the $Nodes block (expected a node id and 3 doubles)");
        for (int k = 0; k < 3; ++k) p[k] = binary_coordinate(cur, "the $Nodes block (expected 3 doubles)");
      } else {
        id = cur.integer("node number");
        for (int k = 0; k < 3; ++k) p[k] = cur.real("coordinate");
      }
      if (node_index.insert(std::uint64_t(id), static_cast<std::uint32_t>(soup.points.size())) != NodeTags::kNone)
        fail("node " + std::to_string(id) + " defined twice");
      soup.points.push_back(p);
    }
    expect_end(cur, "Nodes");
  }

  std::uint32_t node(std::int64_t element, std::int64_t id) const {
    const std::uint32_t at = node_index.find(std::uint64_t(id));
    if (at == NodeTags::kNone)
      fail("element " + std::to_string(element) + ": node " + std::to_string(id) + " is not defined in $Nodes");
    return at;
  }

  // tags[0] is the physical tag, tags[1] the elementary one (Gmsh 2.2 manual).
  static std::int32_t tag_of(const std::vector<std::int64_t>& tags) {
    if (!tags.empty() && tags[0] != 0) return static_cast<std::int32_t>(tags[0]);
    return tags.size() > 1 ? static_cast<std::int32_t>(tags[1]) : 0;
  }
  static std::int32_t elementary_of(const std::vector<std::int64_t>& tags) {
    return tags.size() > 1 ? static_cast<std::int32_t>(tags[1]) : tag_of(tags);
  }

  static std::size_t count_of_dim(const TetSoup& s, int dim) {
    return dim == 3 ? s.tets.size() : dim == 2 ? s.triangles.size() : dim == 1 ? s.edges.size() : s.corners.size();
  }

  // Extends the run of the previous element or starts one (the element is
  // about to be appended at the end of its kind's vector).
  void note_run(int dim, const std::vector<std::int64_t>& tags) {
    if (tags.empty() || tags[0] == 0) return;  // in no physical group: never a chain
    const std::int32_t group = std::int32_t(tags[0]), entity = elementary_of(tags);
    const std::size_t at = count_of_dim(soup, dim);
    if (!runs.empty()) {
      ElementRun& r = runs.back();
      if (r.dim == dim && r.group == group && r.entity == entity && r.end == at) return void(++r.end);
    }
    runs.push_back({dim, entity, group, at, at + 1});
  }

  // Pyramids, prisms, hexahedra and quads (never in a homology chain's run).
  bool add_mixed(Use use, std::int64_t id, const std::int64_t* nodes, std::int32_t tag) {
    if (use == Use::quad) {
      soup.quads.push_back({{node(id, nodes[0]), node(id, nodes[1]), node(id, nodes[2]), node(id, nodes[3])}, tag});
      return true;
    }
    if (use != Use::pyramid && use != Use::prism && use != Use::hex) return false;
    SoupCell c{use_cell_type(use), {}, tag, std::uint64_t(id)};
    for (int k = 0; k < use_corners(use); ++k) c.v[k] = node(id, nodes[k]);
    soup.other_cells.push_back(c);
    return true;
  }

  void add(Use use, std::int64_t type, std::int64_t id, const std::int64_t* nodes, const std::vector<std::int64_t>& tags) {
    if (use == Use::ignore) return;
    const std::int32_t tag = tag_of(tags);
    const int dim = use_dim(use);
    if (!tags.empty() && tags[0] != 0) physicals[{dim, tag}].insert(tag);
    max_order = std::max(max_order, element_order(type));
    if (add_mixed(use, id, nodes, tag)) return;
    note_run(dim, tags);
    switch (use) {
      case Use::tet:
        soup.tets.push_back({node(id, nodes[0]), node(id, nodes[1]), node(id, nodes[2]), node(id, nodes[3])});
        soup.tet_region.push_back(tag);
        break;
      case Use::triangle: {
        soup.triangles.push_back({{node(id, nodes[0]), node(id, nodes[1]), node(id, nodes[2])}, tag});
        origins.triangle.push_back(elementary_of(tags));
        const std::string bad = repeated_vertex(soup.triangles.back().v, "triangle");
        if (!bad.empty()) fail("element " + std::to_string(id) + ": " + bad);
        break;
      }
      case Use::line:  // degenerate lines (a collapsed curve) are dropped by drop_unattached
        soup.edges.push_back({{node(id, nodes[0]), node(id, nodes[1])}, tag});
        origins.edge.push_back(elementary_of(tags));
        break;
      case Use::point:
        soup.corners.push_back({node(id, nodes[0]), tag});
        origins.corner.push_back(elementary_of(tags));
        break;
      case Use::pyramid: case Use::prism: case Use::hex: case Use::quad:  // add_mixed
      case Use::ignore: break;
    }
  }

  std::int64_t tag_value(std::int64_t v) const {
    if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
      fail("tag " + std::to_string(v) + " does not fit in 32 bits");
    return v;
  }

  void elements_ascii(std::int64_t n) {
    std::vector<std::int64_t> tags, nodes;
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t id = cur.integer("element number");
      const std::int64_t type = cur.integer("element type");
      const Use use = element_use(cur, type);
      const std::int64_t ntags = cur.integer_in("number of tags", 0, 1000);
      tags.clear();
      for (std::int64_t k = 0; k < ntags; ++k) tags.push_back(tag_value(cur.integer("tag")));
      nodes.clear();
      for (int k = 0; k < node_count(type); ++k) nodes.push_back(cur.integer("node number"));
      add(use, type, id, nodes.data(), tags);
    }
  }

  void elements_binary(std::int64_t n) {
    cur.skip_end_of_line();
    std::vector<std::int64_t> tags, nodes;
    std::int64_t done = 0;
    while (done < n) {
      const char* what = "the $Elements block (expected an element header of 3 ints)";
      const std::int64_t type = cur.binary<std::int32_t>(what);
      const std::int64_t count = cur.binary<std::int32_t>(what);
      const std::int64_t ntags = cur.binary<std::int32_t>(what);
      const Use use = element_use(cur, type);
      if (count <= 0 || count > n - done)
        fail("element block of " + std::to_string(count) + " elements does not fit the " +
             std::to_string(n - done) + " elements left");
      if (ntags < 0 || ntags > 1000) fail("number of tags " + std::to_string(ntags) + " out of range (0..1000)");
      const int nn = node_count(type);
      cur.check_count(count, 4 * (1 + ntags + nn), "element");
      for (std::int64_t e = 0; e < count; ++e) {
        const char* rec = "the $Elements block (expected an element record)";
        const std::int64_t id = cur.binary<std::int32_t>(rec);
        tags.clear();
        for (std::int64_t k = 0; k < ntags; ++k) tags.push_back(cur.binary<std::int32_t>(rec));
        nodes.clear();
        for (int k = 0; k < nn; ++k) nodes.push_back(cur.binary<std::int32_t>(rec));
        add(use, type, id, nodes.data(), tags);
      }
      done += count;
    }
  }

  void elements() {
    const std::int64_t n = cur.integer_in("number of elements", 0, std::numeric_limits<std::uint32_t>::max());
    cur.check_count(n, binary ? 12 : 8, "element");
    if (binary) elements_binary(n); else elements_ascii(n);
    expect_end(cur, "Elements");
  }

  // $PhysicalNames is text even in binary files: "n" then "dim tag "name""
  // (2.1, 2.2) or "tag "name"" (2.0, whose names hold for every dimension;
  // the 2.1 layout is accepted there too). Unknown dimension: kAnyDim.
  static constexpr int kAnyDim = -1;
  void physical_names() {
    const std::int64_t n = cur.integer_in("number of physical names", 0, 1 << 30);
    cur.check_count(n, minor == 0 ? 4 : 6, "physical name");
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t first = cur.integer(minor == 0 ? "physical tag" : "physical dimension");
      int dim = kAnyDim;
      std::int64_t t = first;
      if (minor > 0 || cur.peek().substr(0, 1) != "\"") {
        if (first < 0 || first > 3) fail("physical dimension " + std::to_string(first) + " out of range (0..3)");
        dim = static_cast<int>(first);
        t = cur.integer("physical tag");
      }
      names[{dim, static_cast<std::int32_t>(tag_value(t))}] = physical_name(cur);
    }
    expect_end(cur, "PhysicalNames");
  }

  // 2.0's names without a dimension name the groups of that tag in every
  // dimension that has one (a name no element uses names nothing).
  void resolve_dimensionless_names() {
    for (auto it = names.begin(); it != names.end() && it->first.first == kAnyDim;) {
      for (int d = 0; d <= 3; ++d)
        if (physicals.count({d, it->first.second})) names.try_emplace({d, it->first.second}, it->second);
      it = names.erase(it);
    }
  }

  // Gmsh's homology and cohomology chains: runs whose physical group has a
  // chain's name (io/unattached.h).
  std::vector<ElementRun> chain_runs() const {
    std::vector<ElementRun> out;
    for (const ElementRun& r : runs) {
      const auto n = names.find({r.dim, r.group});
      if (n != names.end() && is_chain_name(n->second)) out.push_back(r);
    }
    return out;
  }

  // Chains named in $PhysicalNames that no element is in: msh 2 saved with
  // -save_all gives every element physical tag 0, so the chains' elements
  // cannot be told from the model's and are read as model entities.
  void warn_unmarked_chains(const std::vector<ElementRun>& chains) {
    std::string unmarked;
    for (const auto& entry : names) {  // not a structured binding: clang 14's lambdas cannot capture one
      if (!is_chain_name(entry.second)) continue;
      const bool marked = std::any_of(chains.begin(), chains.end(),
                                      [&](const ElementRun& r) { return r.dim == entry.first.first && r.group == entry.first.second; });
      if (!marked) unmarked += (unmarked.empty() ? "" : ", ") + entry.second;
    }
    if (!unmarked.empty())
      soup.warnings.push_back(soup.source + ": names homology or cohomology chains (" + unmarked +
                              ") that no element is in (msh 2 saved with -save_all): their elements, if any, are read "
                              "as model entities (save without -save_all, or as msh 4, to have them dropped)");
  }

  // Groups from the physical tags the elements carry (each is its own soup
  // tag) and the names; then the unattached elements are dropped.
  void finish() {
    resolve_dimensionless_names();
    for (const auto& [key, name] : names) physicals[key];
    for (const auto& [key, tags] : physicals) {
      auto n = names.find(key);
      soup.groups.push_back({key.first, key.second, n == names.end() ? std::string() : n->second,
                             std::vector<std::int32_t>(tags.begin(), tags.end())});
    }
    if (const std::string w = high_order_warning(soup.source, max_order); !w.empty()) soup.warnings.push_back(w);
    const std::vector<ElementRun> chains = chain_runs();
    warn_unmarked_chains(chains);
    drop_chains(soup, origins, chains);
    drop_unattached(soup, origins);
  }
};

}  // namespace

TetSoup read_msh2(TextCursor& cur, bool binary, int minor, bool surfaces) {
  Reader r{cur, binary, {}, {}, {}, {}, {}, 1, minor, {}};
  r.soup.source = cur.source();
  const std::string elements_place = read_sections(cur, [&](std::string_view name) {
    if (name == "Nodes") r.nodes();
    else if (name == "Elements") r.elements();
    else if (name == "PhysicalNames") r.physical_names();
    else return false;
    return true;
  });
  require_tets(r.soup, cur, elements_place, surfaces);
  r.finish();
  return std::move(r.soup);
}

}  // namespace polydual::io::msh
