// The VTU writer's memory: appended raw output (the default) streams every
// array from the mesh to the file, so writing holds no copy of the mesh; the
// encodings that need an array whole (base64, zlib, ascii) hold one array at
// a time. Measured by counting the bytes live through operator new in this
// test program, and checked on a block whose `faces` array alone is ~50 MB.
#include <gtest/gtest.h>
#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>

#include "generate/hex_block.h"
#include "io/vtu_poly_reader.h"
#include "io/vtu_poly_writer.h"

namespace {
std::atomic<long long> g_live{0}, g_peak{0};

void note(long long delta) {
  const long long now = g_live.fetch_add(delta) + delta;
  long long peak = g_peak.load();
  while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
  }
}
}  // namespace

void* operator new(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  note(static_cast<long long>(malloc_usable_size(p)));
  return p;
}
void operator delete(void* p) noexcept {
  if (!p) return;
  note(-static_cast<long long>(malloc_usable_size(p)));
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
// The nothrow forms too: otherwise a library's nothrow new would be served by
// another allocator (AddressSanitizer's) and freed by the delete above.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  void* p = std::malloc(n ? n : 1);
  if (p) note(static_cast<long long>(malloc_usable_size(p)));
  return p;
}
void operator delete(void* p, const std::nothrow_t&) noexcept { operator delete(p); }

namespace polydual {
namespace {

// Peak bytes live above the start while writing `mesh` with `o`.
long long write_peak(const PolyMesh& mesh, const std::string& path, const VtuOptions& o) {
  const long long base = g_live.load();
  g_peak.store(base);
  write_vtu_poly(mesh, path, {}, o);
  return g_peak.load() - base;
}

std::uint64_t faces_bytes(const PolyMesh& m) {
  std::uint64_t n = m.num_cells();
  for (std::size_t c = 0; c < m.num_cells(); ++c)
    for (HalfFace h : m.cell(CellId(c))) n += 1 + m.face(h.face()).size();
  return 8 * n;
}

TEST(VtuWriterMemory, AppendedRawStreamsAndOthersHoldOneArray) {
  const PolyMesh mesh = hex_block(56, 1.0 / 56, true);
  const std::uint64_t faces = faces_bytes(mesh);
  ASSERT_GT(faces, 40u << 20);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("polydual_vtu_memory_" + std::to_string(::getpid()) + ".vtu")).string();
  // Streaming: the per-cell offsets (16 B per cell) and a 1 MiB buffer.
  const long long raw = write_peak(mesh, path, VtuOptions{true, true, 0});
  EXPECT_LT(raw, static_cast<long long>(16 * mesh.num_cells() + (4u << 20))) << raw << " B for faces of " << faces;
  const PolyMesh back = read_vtu_poly(path);
  EXPECT_EQ(back.num_cells(), mesh.num_cells());
  EXPECT_EQ(back.points, mesh.points);
  // base64: one array, its byte-count header and its base64 text (4/3) at a time.
  const long long b64 = write_peak(mesh, path, VtuOptions{true, false, 0});
  EXPECT_LT(b64, static_cast<long long>(2.5 * faces + 16 * mesh.num_cells())) << b64;
  EXPECT_GT(b64, static_cast<long long>(faces));  // it does hold the array whole
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace polydual
