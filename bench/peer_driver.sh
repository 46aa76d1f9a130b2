#!/usr/bin/env bash
# End-to-end comparison with OpenFOAM's polyDualMesh on the same Gmsh meshes,
# in one run (design §12). For each domain and size: polydual convert without
# and with its default optimisation (OpenFOAM output), and gmshToFoam +
# polyDualMesh, all under /usr/bin/time -v, then checkMesh on every case.
# Prints one JSON line per run and a Markdown table at the end.
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
jget() { /usr/bin/python3 -c "import json,sys;j=json.load(open(sys.argv[1]));print(eval(sys.argv[2]))" "$1" "$2"; }
polydual_run() {  # polydual_run <work> <name> [convert options]: case, json, time, checkMesh log
  local w="$1" name="$2"; shift 2
  rm -rf "$w/$name"
  /usr/bin/time -v "$bin" convert "$w/in.msh" -o "$w/$name" --format foam --json "$@" \
    > "$w/$name.json" 2> "$w/$name.time"
  checkMesh -case "$w/$name" > "$w/$name.check" 2>&1 || true
}
for n in $sizes; do
  for d in cube twomat fichera fracture; do
    w="$work/${d}_$n"; mkdir -p "$w"
    [ -f "$w/in.msh" ] || "$bin" generate "$d" --tets "$n" -o "$w/in.msh" 2>/dev/null
    polydual_run "$w" pd --optimize none --no-optimize-tets
    polydual_run "$w" pdo
    # OpenFOAM polyDualMesh (gmshToFoam reads Gmsh 2.2)
    rm -rf "$w/of_case"; mkdir -p "$w/of_case"
    cp -r "$w/pd/system" "$w/of_case/"
    [ -f "$w/in22.msh" ] || gmsh "$w/in.msh" -save -format msh22 -o "$w/in22.msh" > /dev/null 2>&1
    gmshToFoam "$w/in22.msh" -case "$w/of_case" > "$w/g2f.log" 2>&1
    (cd "$w" && /usr/bin/time -v polyDualMesh 30 -case of_case -overwrite > pdm.log 2> pdm.time) || true
    checkMesh -case "$w/of_case" > "$w/of.check" 2>&1 || true
    tets=$(jget "$w/pd.json" "j['tets']")
    pd_cells=$(jget "$w/pd.json" "j['cells']")
    pd_dual=$(jget "$w/pd.json" "j['seconds']['classify']+j['seconds']['dual']")
    pd_wall=$(secs "$(num 'Elapsed \(wall' "$w/pd.time")")
    pd_rss=$(num 'Maximum resident' "$w/pd.time")
    pdo_wall=$(secs "$(num 'Elapsed \(wall' "$w/pdo.time")")
    pdo_invalid=$(jget "$w/pdo.json" "j['invalid_after']")
    of_wall=$(secs "$(num 'Elapsed \(wall' "$w/pdm.time")")
    of_rss=$(num 'Maximum resident' "$w/pdm.time")
    of_cells=$(grep -E "^ +cells:" "$w/of.check" | head -1 | awk '{print $2}')
    pd_fail=$(failures "$w/pd.check"); pdo_fail=$(failures "$w/pdo.check"); of_fail=$(failures "$w/of.check")
    printf '{"domain":"%s","tets":%s,"polydual":{"cells":%s,"classify_dual_s":%s,"wall_s":%s,"rss_kb":%s,"checkmesh_failed":"%s"},"polydual_optimised":{"wall_s":%s,"invalid_cells":%s,"checkmesh_failed":"%s"},"polyDualMesh":{"cells":"%s","wall_s":%s,"rss_kb":%s,"checkmesh_failed":"%s"}}\n' \
      "$d" "$tets" "$pd_cells" "$pd_dual" "$pd_wall" "$pd_rss" "$pd_fail" "$pdo_wall" "$pdo_invalid" "$pdo_fail" \
      "$of_cells" "$of_wall" "$of_rss" "$of_fail" | tee -a "$work/results.jsonl"
    rows+=("| $d | $tets | $pd_cells | $(awk "BEGIN{printf \"%.2f\", $pd_dual*1e6/$tets}") | $pd_wall | $((pd_rss/1024)) | $pd_fail | $pdo_wall | $pdo_invalid | $pdo_fail | $of_cells | $of_wall | $((of_rss/1024)) | $of_fail |")
  done
done
echo
echo "| domain | tets | polydual cells | classify+dual µs/tet | polydual wall s | RSS MB | checkMesh failed | optimised: wall s | invalid (exact star test) | checkMesh failed | polyDualMesh cells | polyDualMesh wall s | RSS MB | checkMesh failed |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
