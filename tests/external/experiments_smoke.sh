#!/usr/bin/env bash
# Smoke test of the experiments harness (design §11): experiments/run.py --smoke
# regenerates, at ~2k tets and with the fast variants only, every record, table
# and figure; this checks that they all exist and are not empty. A few minutes.
# Needs Debian's /usr/bin/python3 (python3-vtk9, matplotlib, meshio), gmsh's
# libgmsh, xvfb-run, and OpenFOAM (polyDualMesh, gmshToFoam, checkMesh).
# usage: experiments_smoke.sh POLYDUAL_BINARY SCRATCH_DIR
set -uo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
out=$2/results
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
rm -rf "$out"
mkdir -p "$out"
if ! /usr/bin/python3 "$repo/experiments/run.py" --smoke --polydual "$bin" --out "$out"; then
  echo "experiments_smoke: FAIL; run.py --smoke failed" >&2
  exit 1
fi
status=0
need() {
  if [[ ! -s "$1" ]]; then echo "experiments_smoke: missing or empty $1" >&2; status=1; fi
}
for t in meshes optimisers timing derivatives tetopt peer; do
  need "$out/tables/$t.md"
  # a generated table has a header, a rule and at least one row
  if [[ -s "$out/tables/$t.md" && $(grep -c '^|' "$out/tables/$t.md") -lt 3 ]]; then
    echo "experiments_smoke: table $t has no rows" >&2; status=1
  fi
done
for d in cube twomat fichera fracture network fins; do
  need "$out/records/${d}_2000_none.json"
  need "$out/records/${d}_2000_peer_polyDualMesh.json"
  for p in a_tets b_initial_cut c_optimised_cut d_optimised; do
    need "$out/figures/${d}_$p.png"
  done
  need "$out/figures/fig_$d.png"
done
# the initial duals must have been checked by the exact test and recorded
if ! grep -q '"invalid_before"' "$out/records/twomat_2000_none.json"; then
  echo "experiments_smoke: twomat record has no invalid_before" >&2; status=1
fi
if [[ $status -eq 0 ]]; then echo "experiments_smoke: ok ($out)"; fi
exit $status
