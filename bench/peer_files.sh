#!/usr/bin/env bash
# File to file against OpenFOAM's polyDualMesh on meshes that other tools
# wrote, in one run: what a user waits for.
#   polydual:      `polydual convert MESH -o case --format foam` (the default
#                  command), with --threads 1 and with the default threads;
#   polyDualMesh:  gmshToFoam (msh 2.2) + `polyDualMesh 30` with
#                  `writeFormat binary` (its fastest setting).
# Each command runs R times (default 3); the best and the mean wall seconds
# are printed. Then checkMesh -allGeometry -allTopology on both results.
# Inputs that gmshToFoam cannot read are first saved as msh 2.2 (untimed):
# Medit by gmsh, TetGen .ele by bench/ele_to_msh22.py.
#   bench/peer_files.sh [polydual-binary] [work dir] MESH...
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="$(readlink -f "${1:?polydual binary}")"; work="${2:?work dir}"; shift 2
runs="${RUNS:-3}"
export WM_PROJECT_DIR=/usr/share/openfoam
mkdir -p "$work"

wall() {  # wall <log> <cmd...>: run, append wall seconds to <log>
  local log="$1"; shift
  local t0 t1; t0=$(date +%s.%N)
  "$@" > /dev/null 2>&1 || { echo "failed: $*" >&2; return 1; }
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l >> "$log"
}
stats() {  # best and mean of the numbers in a file
  awk 'NR==1||$1<m{m=$1} {s+=$1} END{printf "%.2f %.2f", m, s/NR}' "$1"
}
failures() {
  if grep -q "Mesh OK." "$1"; then echo 0; else
    grep -oE "Failed [0-9]+ mesh checks" "$1" | grep -oE "[0-9]+" || echo "?"; fi
}
cells() { grep -E "^ +cells:" "$1" | head -1 | awk '{print $2}'; }
to_msh22() {  # to_msh22 <mesh> <out.msh>
  case "$1" in
    *.ele) /usr/bin/python3 "$here/ele_to_msh22.py" "$1" "$2" ;;
    *) gmsh "$1" -save -format msh22 -o "$2" > /dev/null 2>&1 ;;
  esac
}
controldict() {  # controldict <case> <polydual case>: its system/, writing binary
  mkdir -p "$1"; cp -r "$2/system" "$1/"
  sed -i -E 's/^writeFormat .*/writeFormat     binary;/' "$1/system/controlDict"
}

echo "| mesh | tets | polydual cells | polydual wall s, 1 thread (best / mean) | default threads | checkMesh failed | polyDualMesh cells | gmshToFoam + polyDualMesh wall s (best / mean) | checkMesh failed | ratio (best, 1 thread) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for mesh in "$@"; do
  name=$(basename "$mesh"); name="${name%%.*}"
  # TetGen's X.1.ele: named after its directory when it has one (X is the PLC's).
  case "$mesh" in */*.1.ele) name="$(basename "$(dirname "$mesh")")" ;; esac
  w="$work/$name"; rm -rf "$w"; mkdir -p "$w"
  to_msh22 "$mesh" "$w/in22.msh"
  for ((i = 0; i < runs; i++)); do
    rm -rf "$w/pd1" "$w/pd"
    wall "$w/pd1.t" "$bin" convert "$mesh" -o "$w/pd1" --format foam --threads 1 --quiet
    wall "$w/pd.t" "$bin" convert "$mesh" -o "$w/pd" --format foam --quiet
    rm -rf "$w/of"; controldict "$w/of" "$w/pd"
    wall "$w/of.t" bash -c "gmshToFoam '$w/in22.msh' -case '$w/of' && polyDualMesh 30 -case '$w/of' -overwrite"
  done
  "$bin" convert "$mesh" -o "$w/pdj" --format foam --json --quiet > "$w/pd.json"
  checkMesh -allGeometry -allTopology -case "$w/pd" > "$w/pd.check" 2>&1 || true
  checkMesh -allGeometry -allTopology -case "$w/of" > "$w/of.check" 2>&1 || true
  tets=$(/usr/bin/python3 -c "import json;print(json.load(open('$w/pd.json'))['tets'])")
  read -r b1 m1 <<< "$(stats "$w/pd1.t")"; read -r b m <<< "$(stats "$w/pd.t")"
  read -r bo mo <<< "$(stats "$w/of.t")"
  echo "| $name | $tets | $(cells "$w/pd.check") | $b1 / $m1 | $b / $m | $(failures "$w/pd.check") | $(cells "$w/of.check") | $bo / $mo | $(failures "$w/of.check") | $(awk "BEGIN{printf \"%.2f\", $b1/$bo}") |"
done
