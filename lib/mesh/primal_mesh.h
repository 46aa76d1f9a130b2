// The classified primal mesh of any cell type (design §14): tets, pyramids,
// prisms and hexahedra (a volume mesh), or triangles and quadrangles (a
// surface mesh), with polygonal faces (triangles and quadrangles), edges and
// vertices, each classified on the model (ModelRef). It answers what
// Algorithm 1 asks of a primal (paper §2.2): the cells around a vertex, the
// chains of cells and faces around an edge, an entity's model class. Central
// points are a rule of the dual (dual/primal_central_points.h).
//
// Built by build_primal() (classify/classify_primal.h) from a CellSoup;
// immutable afterwards. ClassifiedTetMesh stays the fast path of tet meshes.
//
// Ids: handles are 32-bit and local (a rank holds fewer than 2^32 entities of
// each kind); ids that leave a rank (the input's numbering, GlobalId) and
// offsets into per-cell rows are 64-bit, so 10^9 tets fit.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/classification.h"
#include "core/handles.h"
#include "core/vec3.h"
#include "mesh/cell_types.h"

namespace polydual {

using PrimalCellId = Handle<struct PrimalCellTag>;
using PrimalFaceId = Handle<struct PrimalFaceTag>;
using GlobalId = std::uint64_t;

// The cells of one chain around an edge (proofs/edge_chains.md), in
// right-handed order about edge(e)[0] -> edge(e)[1], with the faces between
// them: faces.size() == cells.size() + 1, faces[k] precedes cells[k] and
// faces[k+1] follows it; closed: faces.front() == faces.back().
struct EdgeChain {
  std::vector<PrimalCellId> cells;
  std::vector<PrimalFaceId> faces;
  bool closed = false;
};

class PrimalMesh {
 public:
  // --- sizes
  int dim() const { return dim_; }  // 3: volume cells; 2: surface cells
  std::size_t num_vertices() const { return points_.size(); }
  std::size_t num_cells() const { return cell_type_.size(); }
  std::size_t num_faces() const { return face_cell_.size(); }
  std::size_t num_edges() const { return edge_vertex_.size(); }
  const std::string& source() const { return source_; }

  // --- vertices
  const Point3& point(VertexId v) const { return points_[v.idx]; }
  const std::vector<Point3>& points() const { return points_; }
  // The cells around v (its star), increasing.
  std::span<const PrimalCellId> vertex_cells(VertexId v) const { return row(vstar_off_, vstar_, v.idx); }

  // --- cells
  CellType cell_type(PrimalCellId c) const { return cell_type_[c.idx]; }
  const CellDescriptor& cell_descriptor(PrimalCellId c) const { return descriptor(cell_type_[c.idx]); }
  std::span<const VertexId> cell_vertices(PrimalCellId c) const { return row(cell_off_, cell_vtx_, c.idx); }
  // Local face i of a volume cell: the face, and the side of it the cell is
  // on (0: the face's loop points out of this cell; 1: into it).
  PrimalFaceId cell_face(PrimalCellId c, int i) const { return cell_face_[cell_face_off_[c.idx] + i]; }
  int cell_face_side(PrimalCellId c, int i) const { return cell_face_side_[cell_face_off_[c.idx] + i]; }
  EdgeId cell_edge(PrimalCellId c, int k) const { return cell_edge_[cell_edge_off_[c.idx] + k]; }
  // Local index of v in c, or -1.
  int local_index(PrimalCellId c, VertexId v) const {
    const auto cv = cell_vertices(c);
    for (std::size_t i = 0; i < cv.size(); ++i)
      if (cv[i] == v) return int(i);
    return -1;
  }
  // The local indices of a and b in c (-1 where absent), in one scan.
  std::array<int, 2> local_indices(PrimalCellId c, VertexId a, VertexId b) const {
    const auto cv = cell_vertices(c);
    std::array<int, 2> out{-1, -1};
    for (std::size_t i = 0; i < cv.size(); ++i) {
      if (cv[i] == a) out[0] = int(i);
      if (cv[i] == b) out[1] = int(i);
    }
    return out;
  }
  // The neighbour across local face i (invalid on the boundary): stored per
  // local face, one load where the dual's edge walks would make three.
  PrimalCellId cell_neighbor(PrimalCellId c, int i) const { return cell_nbr_[cell_face_off_[c.idx] + i]; }

  // --- faces (volume meshes): triangles and quadrangles
  // Vertex loop, right-hand normal out of face_cell(f, 0).
  std::span<const VertexId> face_vertices(PrimalFaceId f) const { return row(face_off_, face_vtx_, f.idx); }
  // The one or two cells of f (side 1 invalid on the boundary).
  PrimalCellId face_cell(PrimalFaceId f, int side) const { return face_cell_[f.idx][side]; }

  // --- edges
  std::array<VertexId, 2> edge(EdgeId e) const { return edge_vertex_[e.idx]; }  // (a, b), a < b
  // All cells with edge e, increasing (in a surface network, every sheet's).
  std::span<const PrimalCellId> edge_cells(EdgeId e) const { return row(ecell_off_, ecell_, e.idx); }
  // Per cell of edge_cells(e), e's local edge k in it and its direction:
  // 2 * k, or 2 * k + 1 when the cell's local edge k runs from edge(e)[1] to
  // edge(e)[0] (the dual's edge walks read the cell's faces at e from it,
  // without scanning the cell's vertices).
  std::span<const std::uint8_t> edge_cell_locals(EdgeId e) const { return row(ecell_off_, ecell_local_, e.idx); }
  // The chains of cells and faces around e (volume meshes): one closed chain
  // inside the mesh, one open chain per pass of the outside. Every cell of
  // edge_cells(e) is in exactly one; the first chain holds edge_cells(e)[0],
  // the next ones follow the smallest cell not yet placed.
  std::vector<EdgeChain> edge_chains(EdgeId e) const;
  // The edge (a, b), or invalid when no cell has it.
  EdgeId find_edge(VertexId a, VertexId b) const;

  // --- classification
  ModelRef vertex_class(VertexId v) const { return vertex_class_[v.idx]; }
  ModelRef edge_class(EdgeId e) const { return edge_class_[e.idx]; }
  ModelRef face_class(PrimalFaceId f) const { return face_class_[f.idx]; }
  ModelRef cell_class(PrimalCellId c) const { return {std::int8_t(dim_), cell_region_[c.idx]}; }

  // --- the input's numbering (64-bit: it leaves the rank)
  GlobalId input_vertex(VertexId v) const { return input_vertex_.empty() ? v.idx : input_vertex_[v.idx]; }
  GlobalId input_cell(PrimalCellId c) const { return input_cell_.empty() ? c.idx : input_cell_[c.idx]; }

 private:
  friend class PrimalMeshBuilder;
  template <class T>
  static std::span<const T> row(const std::vector<std::uint64_t>& off, const std::vector<T>& data, std::size_t i) {
    return {data.data() + off[i], data.data() + off[i + 1]};
  }
  // The local faces of c through its local vertices (ia, ib), as the face
  // leading out of c right-handedly about ia -> ib (its loop runs ia -> ib)
  // and the one leading in (its loop runs ib -> ia).
  std::array<int, 2> faces_at_edge(PrimalCellId c, int ia, int ib) const;
  EdgeChain chain_from(PrimalCellId start, VertexId a, VertexId b) const;

  int dim_ = 3;
  std::string source_;
  std::vector<Point3> points_;
  std::vector<CellType> cell_type_;
  std::vector<std::int32_t> cell_region_;
  std::vector<std::uint64_t> cell_off_, cell_face_off_, cell_edge_off_;
  std::vector<VertexId> cell_vtx_;
  std::vector<PrimalFaceId> cell_face_;
  std::vector<std::uint8_t> cell_face_side_;
  std::vector<PrimalCellId> cell_nbr_;  // per local face, the cell across it
  std::vector<EdgeId> cell_edge_;
  std::vector<std::uint64_t> face_off_;
  std::vector<VertexId> face_vtx_;
  std::vector<std::array<PrimalCellId, 2>> face_cell_;
  std::vector<std::array<VertexId, 2>> edge_vertex_;  // sorted: find_edge searches it
  // Per vertex a, the edges (a, b) with b > a: edge_vertex_[vedge_off_[a] ..
  // vedge_off_[a + 1]) (find_edge searches only those).
  std::vector<std::uint64_t> vedge_off_;
  std::vector<std::uint64_t> ecell_off_, vstar_off_;
  std::vector<PrimalCellId> ecell_, vstar_;
  std::vector<std::uint8_t> ecell_local_;
  std::vector<ModelRef> vertex_class_, edge_class_, face_class_;
  std::vector<GlobalId> input_vertex_, input_cell_;
};

// The internal vertex of each input number (PrimalMesh::input_vertex; what a
// dual's cell_primal names), invalid where none.
std::vector<VertexId> internal_of_input(const PrimalMesh& m);

// Whether a vertex of vs is marked (one flag per vertex; empty: none is).
bool any_marked(std::span<const VertexId> vs, const std::vector<char>& marked);

// The mean of the vertices' points (the central point of a face or cell
// through a vertex cut whole, design §14).
Point3 vertex_mean(const PrimalMesh& m, std::span<const VertexId> vs);

struct CellSoup;

// Builds the connectivity of a PrimalMesh from a soup whose cells are known to
// be positively oriented (build_primal checks that exactly first), and
// completes the classification (see design §14). Throws InputError naming
// the source and the cells on non-conformity: a face shared by more than two
// cells, two cells on one face with the same orientation or with their
// quadrangle's vertices in different orders, and a quadrangle face against
// two triangle faces.
class PrimalMeshBuilder {
 public:
  static PrimalMesh build(const CellSoup& soup);

 private:
  // A local face of a cell, keyed by its sorted vertices (a triangle's padded
  // with ~0); matched in (key, cell) order.
  struct LocalFace {
    std::array<std::uint32_t, 4> key;
    std::uint32_t cell;
    std::uint8_t local;
  };
  static void copy_cells(PrimalMesh& m, const CellSoup& soup);
  static void build_vertex_stars(PrimalMesh& m);
  static void match_faces(PrimalMesh& m, const CellSoup& soup);
  static void check_hanging_quads(const PrimalMesh& m, const CellSoup& soup);
  static void number_edges(PrimalMesh& m);
  static void classify_faces(PrimalMesh& m, const CellSoup& soup);
  static void classify_edges(PrimalMesh& m, const CellSoup& soup);
  static void classify_vertices(PrimalMesh& m, const CellSoup& soup);
};

}  // namespace polydual
