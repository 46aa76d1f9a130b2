// Pieces shared by the msh 2.2 and msh 4.1 readers (not a public header).
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "io/text_cursor.h"
#include "mesh/tet_soup.h"

namespace polydual::io::msh {

// Node tag -> the node's index in file order. Gmsh numbers nodes 1..N (or
// nearly), so tags below a bound are kept in a plain array (one load per
// lookup; the elements' ~4 lookups per tet dominated the reading of large
// files with a hash map); any other tag (sparse numbering, a negative msh 2.2
// id seen as a huge unsigned) goes to a hash map. Same answers either way.
// The array grows with the nodes inserted (to at most 4 slots per node read
// plus 1024), so a header that announces many nodes, or one huge tag, costs
// nothing until nodes back it; a tag stored in the map before the array grew
// past it is still found there.
class NodeTags {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  // Tags below min(max_tag, 4 * count + 1024) + 1 may be held densely.
  void reserve(std::uint64_t count, std::uint64_t max_tag) {
    bound_ = std::min<std::uint64_t>(max_tag, 4 * count + 1024) + 1;
  }
  // Records tag -> at; returns kNone when the tag is new, else the index it
  // already had (which is kept).
  std::uint32_t insert(std::uint64_t tag, std::uint32_t at) {
    ++inserted_;
    if (tag >= dense_.size() && tag < std::min(bound_, 4 * inserted_ + 1024)) grow(tag);
    if (tag < dense_.size()) {
      std::uint32_t& slot = dense_[tag];
      if (slot != kNone) return slot;
      if (const std::uint32_t had = find_sparse(tag); had != kNone) return had;
      slot = at;
      return kNone;
    }
    const auto [it, fresh] = sparse_.emplace(tag, at);
    return fresh ? kNone : it->second;
  }
  // The index of tag, or kNone.
  std::uint32_t find(std::uint64_t tag) const {
    if (tag < dense_.size() && dense_[tag] != kNone) return dense_[tag];
    return find_sparse(tag);
  }

 private:
  void grow(std::uint64_t tag) {
    dense_.resize(std::min<std::uint64_t>(bound_, std::max<std::uint64_t>(tag + 1, 2 * dense_.size())), kNone);
  }
  std::uint32_t find_sparse(std::uint64_t tag) const {
    if (sparse_.empty()) return kNone;
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? kNone : it->second;
  }
  std::vector<std::uint32_t> dense_;
  std::uint64_t bound_ = 0, inserted_ = 0;
  std::unordered_map<std::uint64_t, std::uint32_t> sparse_;
};

// What the reader does with one Gmsh element type. pyramid, prism, hex and
// quad (a mixed or quadrangle mesh) go to TetSoup::other_cells / quads.
enum class Use { tet, triangle, line, point, pyramid, prism, hex, quad, ignore };

// The dimension of what a Use reads (-1 for ignore), and the number of
// corner vertices kept (high-order elements list their corners first).
int use_dim(Use u);
int use_corners(Use u);
// The cell type of a pyramid, prism or hex use.
CellType use_cell_type(Use u);

// Number of nodes of a Gmsh element type, or -1 when the type is unknown.
int node_count(std::int64_t type);
// Classifies the type, failing (at the cursor's place) for unknown types and
// for 3D types other than tets, pyramids, prisms and hexahedra. High-order
// elements (Gmsh lists their corner vertices first) are read by those corners.
Use element_use(const TextCursor& cur, std::int64_t type);
// The polynomial order of a tet, triangle or line type (1 for linear ones).
int element_order(std::int64_t type);
// The warning for a file with elements of order > 1 ("" when max_order <= 1).
std::string high_order_warning(const std::string& source, int max_order);

// Skips an unrecognised section up to and including "$End<name>".
void skip_section(TextCursor& cur, std::string_view name);
// Reads the token that must close section `name`.
void expect_end(TextCursor& cur, std::string_view name);

// The section loop both versions share: for every "$Name" until the end of
// the file, calls read(name), which returns false for a section it does not
// know (skipped up to $EndName); $Nodes must come once and before the one
// $Elements, and both must be present (else the file holds no tetrahedra).
// Returns the place of $Elements.
template <class ReadSection>
std::string read_sections(TextCursor& cur, ReadSection&& read) {
  bool have_nodes = false, have_elements = false;
  std::string elements_place;
  while (!cur.at_end()) {
    std::string_view name = cur.token("section name");
    if (name.size() < 2 || name[0] != '$') cur.fail("expected a section such as $Nodes, got '" + quoted(name) + "'");
    name.remove_prefix(1);
    if (name == "Nodes") {
      if (have_nodes) cur.fail("second $Nodes section");
      have_nodes = true;
    } else if (name == "Elements") {
      if (!have_nodes) cur.fail("$Elements before $Nodes");
      if (have_elements) cur.fail("second $Elements section");
      have_elements = true;
      elements_place = cur.is_binary() ? "byte " + std::to_string(cur.offset() - name.size() - 1) : cur.line_place();
    }
    if (!read(name)) skip_section(cur, name);
  }
  // Gmsh writes an empty model as $MeshFormat (and $Entities) alone.
  if (!have_nodes && !have_elements)
    throw InputError(cur.source(), "end of file", "the file holds no tetrahedra (no $Nodes and no $Elements section)");
  if (!have_elements)
    throw InputError(cur.source(), "end of file",
                     "the file holds no tetrahedra (no $Elements section after $Nodes: is it cut short?)");
  return elements_place;
}

// A file whose sections are present but hold no tet is empty as a tet mesh
// (a surface mesh, or $Nodes and $Elements with no records): an error at
// `elements_place`, before anything is dropped as unattached.
// A mesh with pyramids, prisms or hexahedra passes (the tet path refuses it
// later, naming its cells); with `surfaces`, so does a surface mesh of
// triangles and quadrangles.
void require_tets(const TetSoup& soup, const TextCursor& cur, const std::string& elements_place,
                  bool surfaces = false);

// Section loops after $MeshFormat (the cursor stands after $EndMeshFormat).
// msh 2.0, 2.1 and 2.2 share their layout (Gmsh reads all three with one
// reader); `minor` (0, 1 or 2) selects what differs: 2.0's $PhysicalNames
// records have no dimension, and a third element tag is a partition before
// 2.2 but a partition count in 2.2 (neither is read).
// `surfaces`: a file with no volume cell is read as a surface mesh.
TetSoup read_msh2(TextCursor& cur, bool binary, int minor, bool surfaces = false);
TetSoup read_msh4(TextCursor& cur, bool binary, bool surfaces = false);

// The name of a $PhysicalNames record (the rest of the line, between the
// first and the last double quote); fails when it is not quoted.
std::string physical_name(TextCursor& cur);

// Reads a binary value and rejects non-finite coordinates at their byte.
double binary_coordinate(TextCursor& cur, const char* what);

}  // namespace polydual::io::msh
