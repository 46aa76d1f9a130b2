// Feature edges (design §3, proofs/classification.md L15): which of the
// primal edges that bend above the feature angle inside one model-face sheet
// are features of the model, and which are the facets of a coarse curved
// surface. A feature is a line: a chain of sharp edges, linked through
// vertices where exactly two of them meet, that keeps the same two sides (the
// triangles' normals on each side change by at most the feature angle from one
// edge to the next, the bend keeps its sign, the line turns by at most the
// strong angle); a chain is kept when it is long enough, or joins kept
// features at both ends, or holds an edge above the strong angle (a CAD
// box's 90° edges always stay). Isolated and zigzag sharp edges are noise.
// All of this is double geometry: an angle threshold is a modelling choice,
// not a sign that must be exact (proofs/classification.md L15).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace polydual {

// A primal edge between exactly two model-face triangles of one grouping key,
// where the feature angle applies.
struct BendEdge {
  std::uint32_t a = 0, b = 0;  // its vertices, the edge directed a -> b
  Vec3 dir{};                  // point(b) - point(a)
  // Unit normals, oriented consistently over the sheet (out of its first
  // region), of the triangle whose oriented boundary runs a -> b ("left") and
  // of the other; both zero when the two triangles' orientations disagree
  // (such an edge links into no chain).
  Vec3 left{}, right{};
  double bend = 0;  // degrees between the triangles' planes: 0 = flat, 180 = folded back
};

enum class FeatureVerdict : std::uint8_t {
  Smooth,  // bend within the feature angle: not a feature
  Strong,  // bend above the strong angle: always a feature
  Chain,   // in a kept chain of consistently sharp edges
  Noise,   // sharp but isolated, zigzag or in a short loose chain: dropped
};

struct FeatureRule {
  double feature_deg = 30;        // sharp above this
  double strong_deg = 60;         // always a feature above this (>= feature_deg)
  std::size_t min_chain_edges = 3;  // a chain this long is a feature
};

// One verdict per edge, deterministic (depends only on the list and the rule).
std::vector<FeatureVerdict> select_feature_edges(const std::vector<BendEdge>& edges, const FeatureRule& rule);

// Angle in degrees between two vectors (0 for a zero vector).
double angle_deg(const Vec3& u, const Vec3& v);

}  // namespace polydual
