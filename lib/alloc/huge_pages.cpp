// Large allocations backed by transparent huge pages (linked into the polydual
// executable and the benchmarks only, never into the library: replacing the
// global operator new is the program's decision, not a library's).
//
// Why: the dual construction touches a few hundred bytes per tet of fresh
// memory (adjacency, the dual's loops) exactly once or twice. With 4 KiB pages
// each first touch is a page fault, and on a virtual machine with memory
// cgroups a fault costs about as much as the work done on the page (measured:
// ~12% of classify + dual at 1M tets). Debian's default THP mode is "madvise",
// so large blocks are advised here, before anything touches them.
//
// Only the advice is added: the memory still comes from malloc and goes back
// with free, so operator delete needs no bookkeeping. A kernel without THP
// ignores the advice (madvise fails; nothing else changes). malloc is also told
// to keep freed memory for reuse (no per-block mmap/munmap, no trimming): the
// stages free and reallocate arrays of similar sizes, and reused memory does
// not fault again. The peak resident size stays that of the live data.
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {
// Below this a block gains nothing from 2 MiB pages.
constexpr std::size_t kHugeThreshold = std::size_t(256) << 10;

struct MallocTuning {
  MallocTuning() {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    // The heap grows in steps of at least 64 MiB. malloc writes the new top
    // chunk's header into each extension before allocate() can advise it, so
    // the 2 MiB around that header gets 4 KiB pages: fewer, larger steps
    // leave fewer such spots (measured at 1M tets: 11k -> 5k page faults per
    // conversion). Untouched pad costs address space, not memory.
    mallopt(M_TOP_PAD, 64 << 20);
    // One arena for every thread: TBB's workers allocate per-block scratch
    // (the dual's edge-face blocks, the cut blocks) that, in arenas of their
    // own, is memory the main heap cannot reuse (measured: ~1.5 MB more peak
    // resident at 100k tets, ~10 MB at 1M). The blocks are few and large, so
    // the shared lock costs nothing measurable (convert default and raw at
    // 100k and 1M, 2 threads: same wall time within noise).
    mallopt(M_ARENA_MAX, 1);
  }
} const malloc_tuning;

void* allocate(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (!p) throw std::bad_alloc();
  if (n >= kHugeThreshold) {
    // The whole 4 KiB pages from the block to the heap's top (madvise needs
    // page alignment): the block, and the free top chunk (M_TOP_PAD) from which
    // the small allocations that follow are carved.
    const std::uintptr_t page = 4096, at = reinterpret_cast<std::uintptr_t>(p),
                         top = reinterpret_cast<std::uintptr_t>(sbrk(0));
    const std::uintptr_t b = (at + page - 1) & ~(page - 1), e = (at < top ? top : at + n) & ~(page - 1);
    if (e > b) (void)madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
  }
  return p;
}
}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
