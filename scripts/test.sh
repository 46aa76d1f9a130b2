#!/usr/bin/env bash
# Every test: install, build, run all ctest tests (unit, property, external
# VTK/OpenFOAM checks), then the bounded libFuzzer runs, then the library and
# the unit/property tests again built with ASan+LSan+UBSan in build-asan
# (scripts/sanitize.sh; any sanitizer finding fails the run).
set -euo pipefail
cd "$(dirname "$0")/.."
# The tools are installed below, so a test that finds one missing fails
# instead of skipping (tests/require_tool.h, tests/corpus/run_corpus.py).
export POLYDUAL_REQUIRE_TOOLS=1
scripts/install-deps.sh
scripts/build.sh
(cd build && ctest --output-on-failure -j"${JOBS:-2}" --timeout 1800)
bash fuzz/run.sh
scripts/sanitize.sh
