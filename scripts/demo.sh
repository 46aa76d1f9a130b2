#!/usr/bin/env bash
# The main job: install, build, then run the built-in demo (the paper's four
# domains generated, converted, optimised, written and re-checked).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
exec ./build/polydual demo "$@"
