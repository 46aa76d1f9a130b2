#!/usr/bin/env bash
# Configures and builds polydual in ./build (Release, ccache when present).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${POLYDUAL_CMAKE_ARGS:-} > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"${JOBS:-2}" >> build.log 2>&1 || { tail -60 build.log; exit 1; }
echo "build: ok (log in build.log)"
