#!/usr/bin/env bash
# Slow external check: with --no-split, the slit faces of the fracture domain's
# dual (owner == neighbour, at the fracture tip) reach the OpenFOAM case as
# baffles, two boundary faces of the slit cell in the patch face_<fracture tag>,
# and checkMesh accepts the topology (closed cells, one baffle per slit face).
# usage: foam_slit.sh POLYDUAL_BINARY SCRATCH_DIR
set -uo pipefail
bin=$1
out=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$out"
if [[ ! -x /usr/bin/checkMesh || ! -f /usr/share/openfoam/etc/controlDict ]]; then
  echo "foam_slit: OpenFOAM is not installed (Debian package openfoam)" >&2
  exit 1
fi
export WM_PROJECT_DIR=/usr/share/openfoam
for d in fracture network; do
  case_dir="$out/${d}_case"
  rm -rf "$case_dir"
  "$bin" generate $d --tets 3000 -o "$out/$d.msh" 2>/dev/null || { echo "foam_slit: generate $d failed"; exit 1; }
  "$bin" convert "$out/$d.msh" --format foam -o "$case_dir" --no-split --json --quiet > "$out/$d.json" \
    || { echo "foam_slit: convert $d failed"; exit 1; }
  /usr/bin/checkMesh -case "$case_dir" -allTopology > "$out/$d.log" 2>&1
  rc=$?
  /usr/bin/python3 "$here/checkmesh_summary.py" $d "$out/$d.log" "$rc" || exit 1
  /usr/bin/python3 - "$out/$d.json" "$out/$d.log" "$case_dir/constant/polyMesh/boundary" <<'PY' || exit 1
import json, re, sys
summary, log, boundary = json.load(open(sys.argv[1])), open(sys.argv[2]).read(), open(sys.argv[3]).read()
slits = summary["dual"]["slit_faces"]
if slits == 0:
    sys.exit("foam_slit: the dual has no slit face, nothing is tested")
m = re.search(r"identical duplicate faces \(baffle faces\): (\d+)", log)
baffles = int(m.group(1)) if m else 0
# Patches that hold only slit faces: every fracture face tag is not an external one,
# so the sum of their sizes is twice the number of slit faces.
tags = {f["tag"] for f in summary["model"]["face_list"] if f["kind"] == "fracture"}
sizes = {int(t): int(n) for t, n in re.findall(r"face_(\d+)\s*\{[^}]*?nFaces\s+(\d+);", boundary)}
in_patches = sum(n for t, n in sizes.items() if t in tags)
print(f"foam_slit: {slits} slit faces; checkMesh baffles {baffles}; faces in fracture patches {in_patches}")
if baffles != slits or in_patches != 2 * slits:
    sys.exit("foam_slit: FAIL; every slit face must be one baffle of two boundary faces")
PY
done
