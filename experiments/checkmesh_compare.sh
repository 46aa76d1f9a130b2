#!/usr/bin/env bash
# checkMesh comparison: on each domain at ~TETS tets, runs
# checkMesh -allTopology -allGeometry on polydual's OpenFOAM case (default
# optimiser), on OpenFOAM's polyDualMesh and on polyDualMesh -concaveMultiCells
# of the same Gmsh mesh, keeps the logs in OUT/ and writes the table
# paper/tables/checkmesh.md (experiments/checkmesh_table.py).
#   experiments/checkmesh_compare.sh [polydual-binary] [tets, default 20000] [out dir] [domains]
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../build/polydual}"
tets="${2:-20000}"
out="${3:-$here/checkmesh}"
# A domain is a built-in one (polydual generate) or a .geo file meshed by the
# gmsh command (a model nobody here meshed; its own mesh sizes).
domains="${4:-cube twomat fichera fracture network fins $here/../tests/data/geo/fractures3.geo $here/../tests/data/geo/piston_fins.geo}"
export WM_PROJECT_DIR=/usr/share/openfoam
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for src in $domains; do
  d=$(basename "$src" .geo)
  w="$work/$d"; mkdir -p "$w"
  if [[ "$src" == *.geo ]]; then
    gmsh -3 "$src" -format msh4 -o "$w/in.msh" > "$w/gmsh.log" 2>&1 || { echo "$d: gmsh failed"; continue; }
  else
    "$bin" generate "$d" --tets "$tets" -o "$w/in.msh" 2>/dev/null || { echo "$d: generate failed"; continue; }
  fi
  "$bin" convert "$w/in.msh" -o "$w/pd" --format foam --json --quiet > "$out/${d}_polydual.json" 2>&1
  checkMesh -case "$w/pd" -allTopology -allGeometry > "$out/${d}_polydual.log" 2>&1
  gmsh "$w/in.msh" -save -format msh22 -o "$w/in22.msh" > /dev/null 2>&1
  for variant in pdm pdm_concave; do
    c="$w/$variant"; rm -rf "$c"; mkdir -p "$c"
    cp -r "$w/pd/system" "$c/"
    gmshToFoam "$w/in22.msh" -case "$c" > "$out/${d}_${variant}_gmshToFoam.log" 2>&1
    extra=(); [ "$variant" = pdm_concave ] && extra=(-concaveMultiCells)
    polyDualMesh 30 "${extra[@]}" -case "$c" -overwrite > "$out/${d}_${variant}_polyDualMesh.log" 2>&1
    checkMesh -case "$c" -allTopology -allGeometry > "$out/${d}_${variant}.log" 2>&1
  done
  echo "$d done"
done
# The logs name the temporary work directory: recorded as WORK so that reruns
# differ only where the meshes do.
sed -i "s#$work#WORK#g" "$out"/*.log "$out"/*.json
/usr/bin/python3 "$here/checkmesh_table.py" "$out" "$tets" > "$here/../paper/tables/checkmesh.md"
