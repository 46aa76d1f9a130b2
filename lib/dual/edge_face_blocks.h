// The fan faces of every primal edge (Algorithm 1 steps 5-6), built in
// blocks of edges: each block apart (face arrays only, numbered from 0) and
// appended in edge order, so the faces are the same for any thread count.
// Shared by the tet builder (dual/build_dual.cpp) and the builder on any
// primal (dual/primal_dual.cpp).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "mesh/poly_mesh.h"

namespace polydual {

// The faces of a block of edges, and those of them that end on a model face
// (the cleanup's scan list), both numbered from 0 within the block.
struct EdgeFaceBlock {
  PolyMesh faces;
  std::vector<std::uint32_t> model_faces;
  std::size_t walked = 0;  // cells visited by the walks round the block's edges
};

// Room for one face of 6 points per edge of a block of n edges (every tet
// is in the rings of its 6 edges, and a mesh has more edges than tets); a
// block that needs more grows.
void reserve_block(PolyMesh& faces, std::size_t n);

// Appends block b's faces to pm, renumbered after pm's own.
void append_faces(PolyMesh& pm, std::vector<std::uint32_t>& model_faces, const EdgeFaceBlock& b);

// Calls make(e0, e1, block) for blocks of `block_size` edges of [0, ne) in
// parallel and appends them to pm in order; two blocks per thread in flight
// at a time, so the copies stay small. They are made while the dual's arrays
// are at their largest, and land above them in the heap: 8 blocks of 8192
// edges, their arrays grown by doubling, raised the process's memory peak
// ~2 MB above the live data (twomat 100k, the split's final build). Returns
// the sum of the blocks' `walked`.
template <class Make>
std::size_t make_faces_in_blocks(std::size_t ne, std::size_t block_size, PolyMesh& pm,
                                 std::vector<std::uint32_t>& model_faces, Make&& make) {
  const std::size_t tokens = 2 * std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  std::size_t next = 0, walked = 0;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& fc) -> std::size_t {
                                            if (next >= ne) fc.stop();
                                            const std::size_t e0 = next;
                                            next += block_size;
                                            return e0;
                                          }) &
          tbb::make_filter<std::size_t, std::shared_ptr<EdgeFaceBlock>>(
              tbb::filter_mode::parallel,
              [&](std::size_t e0) {
                auto b = std::make_shared<EdgeFaceBlock>();
                const std::size_t e1 = std::min(ne, e0 + block_size);
                reserve_block(b->faces, e1 - e0);
                make(e0, e1, *b);
                return b;
              }) &
          tbb::make_filter<std::shared_ptr<EdgeFaceBlock>, void>(
              tbb::filter_mode::serial_in_order, [&](const std::shared_ptr<EdgeFaceBlock>& b) {
                append_faces(pm, model_faces, *b);
                walked += b->walked;
              }));
  return walked;
}

}  // namespace polydual
