#!/usr/bin/env bash
# Every test: install, build, run all ctest tests (unit, property, external
# VTK/OpenFOAM checks), then the bounded libFuzzer runs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
(cd build && ctest --output-on-failure -j"${JOBS:-2}" --timeout 1800)
bash fuzz/run.sh
