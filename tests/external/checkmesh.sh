#!/usr/bin/env bash
# Slow external check (design §9): OpenFOAM's own checkMesh accepts the polyMesh
# that `polydual convert --format foam` writes for every volume demo domain
# (the tet domains and the boundary layers of hexahedra and prisms).
# Topology failures and missing zones fail the test; the geometry results are
# recorded in SCRATCH_DIR/<domain>_checkMesh.log and summarised, not judged.
# usage: checkmesh.sh POLYDUAL_BINARY SCRATCH_DIR
set -uo pipefail
bin=$1
out=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$out"
if [[ ! -x /usr/bin/checkMesh || ! -f /usr/share/openfoam/etc/controlDict ]]; then
  echo "checkmesh: OpenFOAM is not installed (Debian package openfoam)" >&2
  exit 1
fi
# Debian's checkMesh finds its etc/ files through WM_PROJECT_DIR; sourcing the
# full etc/bashrc is not needed for checkMesh alone.
export WM_PROJECT_DIR=/usr/share/openfoam

status=0
for d in cube twomat fichera fracture network fins layers; do
  case_dir="$out/${d}_case"
  log="$out/${d}_checkMesh.log"
  rm -rf "$case_dir" "$log"
  if ! "$bin" generate "$d" --tets 3000 -o "$out/$d.msh"; then
    echo "checkmesh $d: FAIL; polydual generate failed"; status=1; continue
  fi
  if ! "$bin" convert "$out/$d.msh" --format foam -o "$case_dir"; then
    echo "checkmesh $d: FAIL; polydual convert --format foam failed"; status=1; continue
  fi
  /usr/bin/checkMesh -case "$case_dir" -allTopology > "$log" 2>&1
  rc=$?
  /usr/bin/python3 "$here/checkmesh_summary.py" "$d" "$log" "$rc" || status=1
done
exit $status
