// The virtual cuts of the split stage (design §8, proofs/split.md): which
// interior triangles through a primal vertex v cut v's star (dual/vertex_cuts.h)
// so that the dual builder gives v several cells, each one star-shaped or
// closer to it. Pure topology of the ClassifiedTetMesh plus exact orientation
// signs (lib/predicates); no dual is read.
//
// Every generator labels the tets of v's star and cuts v's star exactly at the
// interior triangles (through v, on no model face) whose two tets have
// different labels. Hence (proofs/split.md, L1) no cut triangle ever has the
// same side on both of its tets: a cut never makes a new slit.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

// Why a vertex got cuts (the JSON's "cells split by cause").
enum class CutCause : std::uint8_t { None, FreeEdge, SheetCrossing, ConcaveEdge, ConcaveVertex, Other };
const char* cut_cause_name(CutCause c);

// Slit cells: for every vertex v whose side (its star joined across triangles
// on no model face) holds both tets of a model-face triangle through v, cut(v)
// separates the two tets of every such triangle. Per slit side, the tets of
// the sheet triangles are seeded by their side of the coherently oriented
// sheet (exact orient3d), and a multi-source breadth-first growth over the
// side's tets gives every other tet the label of the nearer seed: the cut is
// the bisector between the two faces of the sheet, which continues the sheet
// across the cell. Repeated until no side of v holds both tets of a
// model-face triangle (each pass splits one side: ends).
// slit (may be null) receives the vertices cut, increasing.
VertexCuts free_edge_cuts(const ClassifiedTetMesh& m, std::vector<VertexId>* slit = nullptr);

// Cells at sheet crossings and concave model edges or vertices: for each given
// vertex, the planes of the model faces at v (per model face tag, the plane of
// its lowest-numbered triangle at v) are continued through v's star: a tet is
// labelled by its sign against each plane (exact orient3d of its three
// vertices other than v, the sign of their sum of signs), and v's star is cut
// where the labels of the two tets differ. Each piece then lies, as far as
// the tets allow, in one wedge of the model faces' planes: convex wedges
// where the faces were concave.
VertexCuts plane_cuts(const ClassifiedTetMesh& m, std::span<const VertexId> vertices);

// Every interior triangle through each given vertex, and the vertex marked
// whole (VertexCuts::whole): one cell per tet of its star, the barycentric
// corner of the tet, convex by construction (proofs/dual_cuts.md, C5). The
// split loop's certificate.
VertexCuts fallback_cuts(const ClassifiedTetMesh& m, std::span<const VertexId> vertices);

// free merged with fallback_cuts of the vertices marked in `whole` (one flag
// per vertex of m): the cuts of a split round.
VertexCuts with_whole_cuts(const ClassifiedTetMesh& m, const VertexCuts& free, std::span<const char> whole);

// The cause of an invalid cell of v that has no free-edge cut, by v's class:
// model vertex -> ConcaveVertex; model edge -> SheetCrossing when >= 3 model
// faces (distinct tags of model-face triangles) meet at v, else ConcaveEdge;
// otherwise Other.
CutCause invalid_cause(const ClassifiedTetMesh& m, VertexId v);

// The sides of v's star cut by the model faces and by cuts (null: none): a
// component label per tet of vertex_tets(v), 0-based, in order of first
// appearance. The reference the tests and the generators share.
std::vector<std::uint32_t> star_sides(const ClassifiedTetMesh& m, VertexId v, const VertexCuts* cuts);

}  // namespace polydual
