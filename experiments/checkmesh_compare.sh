#!/usr/bin/env bash
# checkMesh comparison: on each domain at ~TETS tets, runs
# checkMesh -allTopology -allGeometry on polydual's OpenFOAM case (default
# optimiser), on OpenFOAM's polyDualMesh and on polyDualMesh -concaveMultiCells
# of the same Gmsh mesh, keeps the logs and each conversion's --json in OUT,
# and writes their summary OUT/checkmesh.json and its table OUT/checkmesh.md
# (experiments/checkmesh_table.py). With --paper as the fifth argument the
# summary is also recorded as paper/data/checkmesh.json and the table as
# paper/tables/checkmesh.md.
#   experiments/checkmesh_compare.sh [polydual-binary] [tets, default 20000]
#       [out dir, default build/results/checkmesh] [domains] [--paper]
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../build/polydual}"
tets="${2:-20000}"
out="${3:-$here/../build/results/checkmesh}"
# A domain is a built-in one (polydual generate) or a .geo file meshed by the
# gmsh command (a model nobody here meshed; its own mesh sizes).
domains="${4:-cube twomat fichera fracture network fins $here/../tests/data/geo/fractures3.geo $here/../tests/data/geo/piston_fins.geo}"
paper="${5:-}"
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
/usr/bin/python3 "$here/checkmesh_table.py" summarise "$out" "$tets" > "$out/checkmesh.json"
/usr/bin/python3 "$here/checkmesh_table.py" render "$out/checkmesh.json" > "$out/checkmesh.md"
echo "summary in $out/checkmesh.json, table in $out/checkmesh.md"
if [[ "$paper" == --paper ]]; then
  cp "$out/checkmesh.json" "$here/../paper/data/checkmesh.json"
  cp "$out/checkmesh.md" "$here/../paper/tables/checkmesh.md"
fi
