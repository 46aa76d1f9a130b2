// The polyhedral (dual) mesh: face-based, like OpenFOAM and OpenVolumeMesh.
//  - a face is a loop of points; its right-hand normal points OUT of its owner;
//  - an interior face has a neighbour (which sees the loop reversed); a face on
//    the external boundary has none;
//  - a cell is a list of half-faces (HalfFace{f, 0} for an owned face,
//    HalfFace{f, 1} for a face it neighbours), so every half-face's loop, read in
//    the cell's sense, has an outward normal.
// A face with owner == neighbour is a "slit" face (both sides of a fracture
// triangle fan belong to one cell at a fracture tip); validate() reports it.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/classification.h"
#include "core/handles.h"
#include "core/vec3.h"

namespace polydual {

// FaceKind (lib/core/classification.h): what a dual face lies on.
// What primal entity a dual point was made from: dim 3 tet, 2 triangle, 1 edge,
// 0 vertex, with its id; dim -1 for a point made later (split, optimiser).
// Packed in 4 bytes (one per dual point, alive at the dual's memory peak): ids
// up to kMaxId, which build_dual_draft() checks.
struct PointOrigin {
  static constexpr std::uint32_t kMaxId = (std::uint32_t(1) << 29) - 1;
  std::int8_t dim : 3 = -1;
  std::uint32_t id : 29 = 0;
  friend constexpr bool operator==(PointOrigin, PointOrigin) = default;
};
static_assert(sizeof(PointOrigin) == 4);

struct PolyMesh {
  // Points
  std::vector<Point3> points;
  std::vector<ModelRef> point_class;  // dim 0..3 and model tag of each point
  // The primal entity each point was made from (the dual builder; kept by the
  // cleanup, a merged point keeps its representative's): a tet centre, a
  // triangle centre, an edge midpoint or a vertex, in the ClassifiedTetMesh's
  // internal numbering. Lets a rebuilt dual (new cuts, lib/split) start from
  // the positions of an optimised one. Empty: unknown (a mesh read from file).
  std::vector<PointOrigin> point_origin;

  // Faces (CSR loops)
  std::vector<std::uint32_t> face_offsets{0};
  std::vector<PointId> face_points;
  std::vector<CellId> face_owner, face_neighbour;  // neighbour invalid on the boundary
  std::vector<FaceKind> face_kind;
  std::vector<std::int32_t> face_tag;  // model face tag (kind != Interior), else 0

  // Cells (CSR half-face lists)
  std::vector<std::uint32_t> cell_offsets{0};
  std::vector<HalfFace> cell_faces;
  std::vector<std::int32_t> cell_material;  // model region tag
  std::vector<VertexId> cell_primal;        // source primal vertex
  // The cell each cell was split from (split/split.h); empty: every cell is
  // its own origin (no split ran).
  std::vector<CellId> cell_origin;

  std::size_t num_points() const { return points.size(); }
  std::size_t num_faces() const { return face_owner.size(); }
  std::size_t num_cells() const { return cell_material.size(); }

  std::span<const PointId> face(FaceId f) const {
    return {face_points.data() + face_offsets[f.idx], face_points.data() + face_offsets[f.idx + 1]};
  }
  std::span<const HalfFace> cell(CellId c) const {
    return {cell_faces.data() + cell_offsets[c.idx], cell_faces.data() + cell_offsets[c.idx + 1]};
  }
  CellId half_face_cell(HalfFace h) const {
    return h.side() == 0 ? face_owner[h.face().idx] : face_neighbour[h.face().idx];
  }

  // Appenders used by the builders; return the new handle.
  PointId add_point(const Point3& p, ModelRef cls) {
    points.push_back(p);
    point_class.push_back(cls);
    if (!point_origin.empty()) point_origin.push_back(PointOrigin{});
    return PointId(points.size() - 1);
  }
  FaceId add_face(std::span<const PointId> loop, CellId owner, CellId neighbour, FaceKind kind,
                  std::int32_t tag) {
    face_points.insert(face_points.end(), loop.begin(), loop.end());
    return close_face(owner, neighbour, kind, tag);
  }
  // Ends a face whose loop was appended to face_points directly.
  FaceId close_face(CellId owner, CellId neighbour, FaceKind kind, std::int32_t tag) {
    face_offsets.push_back(static_cast<std::uint32_t>(face_points.size()));
    face_owner.push_back(owner);
    face_neighbour.push_back(neighbour);
    face_kind.push_back(kind);
    face_tag.push_back(tag);
    return FaceId(face_owner.size() - 1);
  }
  CellId add_cell(std::span<const HalfFace> faces, std::int32_t material, VertexId primal) {
    cell_faces.insert(cell_faces.end(), faces.begin(), faces.end());
    cell_offsets.push_back(static_cast<std::uint32_t>(cell_faces.size()));
    cell_material.push_back(material);
    cell_primal.push_back(primal);
    return CellId(cell_material.size() - 1);
  }

  // Distinct points of a cell, in first-seen order (deterministic).
  std::vector<PointId> cell_points(CellId c) const;
  // The loop of half-face h as its cell sees it (reversed for side 1).
  std::vector<PointId> oriented_loop(HalfFace h) const;
};

// The distinct points of cells in cell_points' order, without its linear
// search (quadratic in a cell's size): one stamp per mesh point, kept between
// calls. Not shared between threads; one per thread. The stamps are 2 bytes
// (every 65535 cells they are all cleared): the scans of check_split's
// validation run while the whole dual is alive, at the memory peak.
class CellPointScan {
 public:
  explicit CellPointScan(const PolyMesh& mesh) : mesh_(&mesh), stamp_(mesh.num_points(), 0) {}
  // Cell c's distinct points; valid until the next call.
  std::span<const PointId> operator()(CellId c);

 private:
  const PolyMesh* mesh_;
  std::vector<std::uint16_t> stamp_;  // == gen_: already among the current cell's points
  std::vector<PointId> out_;
  std::uint16_t gen_ = 0;
};

}  // namespace polydual
