#!/usr/bin/env bash
# End-to-end comparison with OpenFOAM's polyDualMesh on the same Gmsh meshes,
# in one run (SPEC §12). For each domain and size: polydual convert (no
# optimisation, OpenFOAM output) and gmshToFoam + polyDualMesh, both under
# /usr/bin/time -v, then checkMesh on both cases. Prints one JSON line per run
# and a Markdown table at the end.
#   bench/peer_driver.sh [polydual-binary] [sizes, default "100000"] [work dir]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../build/polydual}"
sizes="${2:-100000}"
work="${3:-$here/../bench-data/peer}"
export WM_PROJECT_DIR=/usr/share/openfoam
mkdir -p "$work"
rows=()
num() { grep -E "$1" "$2" | head -1 | sed -E 's/.*(\):|[a-z]\)?:) *//'; }
secs() {  # h:mm:ss or m:ss -> seconds
  awk -F: '{ if (NF==3) print $1*3600+$2*60+$3; else print $1*60+$2 }' <<< "$1"
}
failures() {  # checkMesh log -> number of failed checks (0 when "Mesh OK.")
  if grep -q "Mesh OK." "$1"; then echo 0; else
    grep -oE "Failed [0-9]+ mesh checks" "$1" | grep -oE "[0-9]+" || echo "?"; fi
}
for n in $sizes; do
  for d in cube twomat fichera fracture; do
    w="$work/${d}_$n"; mkdir -p "$w"
    [ -f "$w/in.msh" ] || "$bin" generate "$d" --tets "$n" -o "$w/in.msh" 2>/dev/null
    # polydual
    rm -rf "$w/pd_case"
    /usr/bin/time -v "$bin" convert "$w/in.msh" -o "$w/pd_case" --format foam --optimize none --json \
      > "$w/pd.json" 2> "$w/pd.time"
    checkMesh -case "$w/pd_case" > "$w/pd_check.log" 2>&1 || true
    # OpenFOAM polyDualMesh (needs Gmsh 2.2 input for gmshToFoam)
    rm -rf "$w/of_case"; mkdir -p "$w/of_case"
    cp -r "$w/pd_case/system" "$w/of_case/"
    [ -f "$w/in22.msh" ] || gmsh "$w/in.msh" -save -format msh22 -o "$w/in22.msh" > /dev/null 2>&1
    gmshToFoam "$w/in22.msh" -case "$w/of_case" > "$w/g2f.log" 2>&1
    /usr/bin/time -v polyDualMesh 30 -case "$w/of_case" -overwrite > "$w/pdm.log" 2> "$w/pdm.time" || true
    checkMesh -case "$w/of_case" > "$w/of_check.log" 2>&1 || true
    tets=$(/usr/bin/python3 -c "import json;print(json.load(open('$w/pd.json'))['tets'])")
    pd_cells=$(/usr/bin/python3 -c "import json;print(json.load(open('$w/pd.json'))['cells'])")
    pd_dual=$(/usr/bin/python3 -c "import json;s=json.load(open('$w/pd.json'))['seconds'];print(s['classify']+s['dual'])")
    pd_wall=$(secs "$(num 'Elapsed \(wall' "$w/pd.time")")
    pd_rss=$(num 'Maximum resident' "$w/pd.time")
    of_wall=$(secs "$(num 'Elapsed \(wall' "$w/pdm.time")")
    of_rss=$(num 'Maximum resident' "$w/pdm.time")
    of_cells=$(grep -E "^ +cells:" "$w/of_check.log" | head -1 | awk '{print $2}')
    pd_fail=$(failures "$w/pd_check.log"); of_fail=$(failures "$w/of_check.log")
    pd_zones=$(grep -cE "^ *(cellZones|faceZones)|zone" "$w/pd_check.log" || true)
    line=$(printf '{"domain":"%s","tets":%s,"polydual":{"cells":%s,"classify_dual_s":%s,"wall_s":%s,"rss_kb":%s,"checkmesh_failed":"%s"},"polyDualMesh":{"cells":"%s","wall_s":%s,"rss_kb":%s,"checkmesh_failed":"%s"}}' \
      "$d" "$tets" "$pd_cells" "$pd_dual" "$pd_wall" "$pd_rss" "$pd_fail" "$of_cells" "$of_wall" "$of_rss" "$of_fail")
    echo "$line" | tee -a "$work/results.jsonl"
    rows+=("| $d | $tets | $pd_cells | $(awk "BEGIN{printf \"%.2f\", $pd_dual*1e6/$tets}") | $pd_wall | $((pd_rss/1024)) | $pd_fail | $of_cells | $of_wall | $((of_rss/1024)) | $of_fail | $(awk "BEGIN{printf \"%.1f\", $of_wall/$pd_wall}") |")
  done
done
echo
echo "| domain | tets | polydual cells | classify+dual µs/tet | polydual wall s | RSS MB | checkMesh failed | polyDualMesh cells | polyDualMesh wall s | RSS MB | checkMesh failed | wall ratio |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
