#!/usr/bin/env bash
# Builds the fuzzers (fuzz/CMakeLists.txt: the readers, the VTU polyhedron
# reader, and the whole pipeline) with clang++-14 and runs each
# for a bounded time on a seed corpus made from tests/data. Exits non-zero when
# a fuzzer finds a crash (its reproducer is left in the work directory).
# Usage: fuzz/run.sh [seconds per target, default 20] [work dir, default build-fuzz]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
seconds="${1:-20}"
work="${2:-$root/build-fuzz}"
if ! command -v clang++-14 >/dev/null 2>&1; then
  echo "fuzz/run.sh: clang++-14 not found, skipping the fuzzers"
  exit 0
fi
cmake -S "$here" -B "$work" -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
cmake --build "$work" -j"${FUZZ_JOBS:-2}" >/dev/null

data="$root/tests/data"
seeds() {  # seeds <format>: fills $work/corpus_<format>
  local dir="$work/corpus_$1"
  mkdir -p "$dir"
  # Inputs that once failed are replayed first (fuzz/regressions/<format>_*).
  cp "$here"/regressions/"$1"_* "$dir"/ 2>/dev/null || true
  case "$1" in
    msh) cp "$data"/*.msh "$dir"/ ;;
    medit) cp "$data"/*.mesh "$dir"/ ;;
    vtu) cp "$data"/cube5*.vtu "$dir"/ ;;
    vtu_poly) cp "$data"/poly_*.vtu "$dir"/ ;;
    pipeline)  # first byte: the reader ('m' Medit, 'g' Gmsh)
      cp "$here"/seeds_pipeline/* "$dir"/
      for f in "$data"/cube5.mesh "$data"/cube5.msh "$data"/cube5_v2.msh; do
        case "$f" in *.mesh) p=m ;; *) p=g ;; esac
        { printf '%s' "$p"; cat "$f"; } > "$dir/$(basename "$f")"
      done ;;
    tetgen)
      { cat "$data/cube5.node"; printf '\0'; cat "$data/cube5.ele"; printf '\0'; cat "$data/cube5.face"; } \
        > "$dir/cube5"
      { cat "$data/cube5.node"; printf '\0'; cat "$data/cube5.ele"; } > "$dir/cube5_noface" ;;
  esac
}

status=0
for format in msh medit tetgen vtu vtu_poly pipeline; do
  seeds "$format"
  mkdir -p "$work/artifacts_$format"
  echo "== fuzz_$format for ${seconds}s"
  if ! "$work/fuzz_$format" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
      -artifact_prefix="$work/artifacts_$format/" "$work/corpus_$format" > "$work/fuzz_$format.log" 2>&1; then
    echo "fuzz_$format FOUND A CRASH: see $work/fuzz_$format.log and $work/artifacts_$format/"
    tail -40 "$work/fuzz_$format.log"
    status=1
  else
    grep -E "^#[0-9]+.*DONE|Done [0-9]+ runs" "$work/fuzz_$format.log" | tail -1 || true
  fi
done
exit $status
