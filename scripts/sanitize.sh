#!/usr/bin/env bash
# The library, the polydual command and the unit/property tests built with
# AddressSanitizer (+ LeakSanitizer) and UndefinedBehaviorSanitizer in
# ./build-asan, then `ctest -LE slow` there. Any finding fails the run: UBSan
# does not recover (-fno-sanitize-recover=undefined), ASan halts on the first
# error, LSan reports leaks at exit (no suppressions). The prebuilt
# dependencies (Ceres, Gmsh, TBB, GMP) are not instrumented: errors inside
# them are not seen, but their allocations are (malloc is intercepted).
# Usage: scripts/sanitize.sh [build dir, default build-asan]
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
work="${1:-build-asan}"
san="-fsanitize=address,undefined -fno-sanitize-recover=undefined"
# RelWithDebInfo at -O1: line numbers in the reports, about 3x faster tests
# than -O0. No benchmarks (they need Release timings) and no fuzzers.
mkdir -p "$work"
log="$work/sanitize-build.log"
cmake -S . -B "$work" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$san -fno-omit-frame-pointer" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_EXE_LINKER_FLAGS="$san" \
  -DPOLYDUAL_BUILD_BENCH=OFF ${POLYDUAL_CMAKE_ARGS:-} > "$log" 2>&1 || { cat "$log"; exit 1; }
cmake --build "$work" -j"${JOBS:-2}" >> "$log" 2>&1 || { tail -60 "$log"; exit 1; }
echo "sanitizer build: ok (log in $log)"
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:report_error_type=1"
export LSAN_OPTIONS="print_suppressions=0"
# The CGAL Mesh_3 generators are not built here (they make test input, they
# are not code under test): the test that runs one uses the Release build's,
# so that it runs under POLYDUAL_REQUIRE_TOOLS=1 too.
gen="$root/build/tests/meshgen/labelled_image_medit"
if [[ -z "${POLYDUAL_LABELLED_IMAGE_MEDIT:-}" && -x "$gen" ]]; then
  export POLYDUAL_LABELLED_IMAGE_MEDIT="$gen"
fi
cd "$work"
ctest --output-on-failure -j"${JOBS:-2}" --timeout 1800 -LE slow
