#!/usr/bin/env bash
# Slow external check: models nobody here meshed, written by the
# gmsh command itself from OpenCASCADE booleans (tests/data/geo): a block with
# three crossing fractures and a construction point, a cylinder with two fins
# attached to its wall, a box with two spherical holes and an inclusion. Each
# is converted with the default options and with --optimize none, both with
# --require-valid: every cell must pass the exact star test (exit 0), the
# split must have run, and the summary must say 0 invalid cells.
# The poles of holes_inclusion's spheres are model vertices at the end of a
# seam edge inside a face (lib/dual/build_dual.cpp, add_cap): the summary must
# list no defect at all (validate(): closed cells, model entities present).
# usage: real_models.sh POLYDUAL_BINARY SCRATCH_DIR
set -uo pipefail
bin=$1
out=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
geo="$here/../data/geo"
mkdir -p "$out"
if ! command -v gmsh >/dev/null; then
  echo "real_models: the gmsh command is not installed (Debian package gmsh)" >&2
  exit 1
fi
status=0
for g in fractures3 piston_fins holes_inclusion; do
  gmsh -3 "$geo/$g.geo" -format msh4 -o "$out/$g.msh" > "$out/$g.gmsh.log" 2>&1 \
    || { echo "real_models: gmsh failed on $g"; tail -5 "$out/$g.gmsh.log"; exit 1; }
  for opt in "" "--optimize none"; do
    # shellcheck disable=SC2086
    "$bin" convert "$out/$g.msh" -o "$out/$g.vtu" --force --require-valid --json --quiet $opt > "$out/$g.json" 2> "$out/$g.err"
    rc=$?
    if [[ $rc -ne 0 ]]; then
      echo "real_models: $g ${opt:-default}: exit $rc"; cat "$out/$g.err"; status=1; continue
    fi
    /usr/bin/python3 - "$out/$g.json" "$g ${opt:-default}" <<'PY' || status=1
import json, sys
d = json.load(open(sys.argv[1]))
s = d["split"]
print(f"real_models: {sys.argv[2]}: {d['tets']} tets, {d['cells']} cells, invalid {d['invalid_before']} -> "
      f"{d['invalid_after']}, rounds {len(s['rounds'])}, split {s['cells_split']}")
if d["invalid_after"] != 0 or s["cells_split"]["still_invalid"] != 0:
    sys.exit("real_models: invalid cells remain")
if d["invalid_before"] == 0:
    sys.exit("real_models: nothing to repair, the check is vacuous")
if d["defects"] or not d["topology_ok"]:
    sys.exit(f"real_models: defects {d['defects']}")
PY
  done
done
exit $status
