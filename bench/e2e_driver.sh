#!/usr/bin/env bash
# End-to-end benchmark, file to file (design §12): per
# domain and size, in the same run and interleaved,
#   raw      polydual convert IN.msh -o OUT.vtu --optimize none --no-optimize-tets (the bare dual)
#   default  polydual convert IN.msh -o OUT.vtu          (certified valid, smoothed)
#   untangle polydual convert IN.msh -o OUT.vtu --optimize untangle (certified
#            valid): its optimiser seconds against a budget, the same run's
#            classify + dual + star test seconds (seconds.classify, .dual,
#            .star_test of its --json; the free-edge cuts are not counted in):
#            untangling should cost no more than building and checking the dual
#   pdm      OpenFOAM polyDualMesh 30 on the case gmshToFoam made from the same
#            mesh (gmshToFoam timed and reported apart, not counted)
# each under /usr/bin/time (wall clock, peak RSS). raw, untangle and pdm run
# REPEATS times (median wall, max RSS; untangle: the median of the runs'
# optimiser / budget ratios); default once (it is slow). From the default
# run's --json: optimiser seconds, vertex updates per second per core, and the
# time to valid (optimiser seconds until the first sweep with 0 invalid cells).
# Prints one JSON line per domain and size (also appended to WORK/results.jsonl)
# and a Markdown table at the end.
#   bench/e2e_driver.sh [--sizes 100000[,1000000]] [--domains cube,twomat,fichera,fracture]
#                       [--repeats 3] [--no-default] [--threads N] [--bin build/polydual] [--work DIR]
# Meshes are generated once (polydual generate) and cached in WORK.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="$here/../build/polydual"
work="$here/../bench-data/e2e"
sizes="100000"
domains="cube,twomat,fichera,fracture"
repeats=3
with_default=1
threads=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes) sizes="$2"; shift 2 ;;
    --domains) domains="$2"; shift 2 ;;
    --repeats) repeats="$2"; shift 2 ;;
    --no-default) with_default=0; shift ;;
    --threads) threads="$2"; shift 2 ;;
    --bin) bin="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "e2e_driver: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$bin" ] || { echo "e2e_driver: no polydual binary at $bin (--bin)" >&2; exit 2; }
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
for tool in polyDualMesh gmshToFoam gmsh; do
  command -v "$tool" > /dev/null || { echo "e2e_driver: $tool not found (scripts/install-deps.sh installs it)" >&2; exit 2; }
done
mkdir -p "$work"
py=/usr/bin/python3

# timed OUT_PREFIX CMD...: runs CMD under /usr/bin/time; OUT_PREFIX.time gets
# "wall_s rss_kb"; stdout to OUT_PREFIX.out, stderr to OUT_PREFIX.err.
timed() {
  local p="$1"; shift
  /usr/bin/time -o "$p.time" -f "%e %M" "$@" > "$p.out" 2> "$p.err" ||
    { echo "e2e_driver: failed: $* (see $p.err)" >&2; tail -5 "$p.err" >&2; return 1; }
}
# median / max of the first / second fields of files
median_wall() { cat "$@" | awk '{print $1}' | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
max_rss() { cat "$@" | awk '{print $2}' | sort -g | tail -1; }

# prepare W: the mesh, its Gmsh 2.2 copy, and the OpenFOAM case of gmshToFoam
# (its polyMesh saved as polyMesh.orig, restored before each polyDualMesh run).
prepare() {
  local w="$1" d="$2" n="$3"
  mkdir -p "$w"
  [ -s "$w/in.msh" ] || "$bin" generate "$d" --tets "$n" -o "$w/in.msh" 2> /dev/null
  [ -s "$w/in22.msh" ] || gmsh "$w/in.msh" -save -format msh22 -o "$w/in22.msh" > /dev/null 2>&1
  rm -rf "$w/of" "$w/sys"
  "$bin" convert "$w/in.msh" -o "$w/sys" --format foam --optimize none --no-optimize-tets --quiet > /dev/null
  mkdir -p "$w/of"
  cp -r "$w/sys/system" "$w/of/"
  timed "$w/g2f" gmshToFoam "$w/in22.msh" -case "$w/of"
  rm -rf "$w/of/constant/polyMesh.orig"
  cp -r "$w/of/constant/polyMesh" "$w/of/constant/polyMesh.orig"
}

run_pdm() {  # run_pdm W I
  local w="$1" i="$2"
  rm -rf "$w/of/constant/polyMesh"
  cp -r "$w/of/constant/polyMesh.orig" "$w/of/constant/polyMesh"
  timed "$w/pdm.$i" polyDualMesh 30 -case "$w/of" -overwrite
}

rows=()
IFS=, read -ra size_list <<< "$sizes"
IFS=, read -ra domain_list <<< "$domains"
for n in "${size_list[@]}"; do
  for d in "${domain_list[@]}"; do
    w="$work/${d}_$n"
    prepare "$w" "$d" "$n"
    for i in $(seq 1 "$repeats"); do  # interleaved: the machine's drift hits both
      timed "$w/raw.$i" "$bin" convert "$w/in.msh" -o "$w/raw.vtu" --optimize none --no-optimize-tets --json --quiet --threads "$threads"
      timed "$w/untangle.$i" "$bin" convert "$w/in.msh" -o "$w/untangle.vtu" --optimize untangle --json --quiet --threads "$threads"
      run_pdm "$w" "$i"
    done
    if [ "$with_default" = 1 ]; then
      timed "$w/default" "$bin" convert "$w/in.msh" -o "$w/default.vtu" --json --quiet --threads "$threads"
    fi
    out=$($py - "$w" "$d" "$repeats" "$with_default" "$threads" \
      "$(median_wall "$w"/raw.*.time)" "$(max_rss "$w"/raw.*.time)" \
      "$(median_wall "$w"/pdm.*.time)" "$(max_rss "$w"/pdm.*.time)" "$(cat "$w/g2f.time")" <<'PY'
import json, sys
w, d, repeats, with_default, threads = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4] == "1", int(sys.argv[5])
raw_wall, raw_rss, pdm_wall, pdm_rss = float(sys.argv[6]), int(sys.argv[7]), float(sys.argv[8]), int(sys.argv[9])
g2f_wall, g2f_rss = (float(x) for x in sys.argv[10].split())
raw = json.load(open(f"{w}/raw.1.out"))
tets = raw["tets"]
r = {"domain": d, "tets": tets, "cells": raw["cells"], "repeats": repeats, "threads": threads,
     "raw": {"wall_s": raw_wall, "rss_kb": raw_rss, "bytes_per_tet": raw_rss * 1024 / tets,
             "invalid": raw["invalid_after"], "seconds": raw["seconds"]},
     "polyDualMesh": {"wall_s": pdm_wall, "rss_kb": pdm_rss},
     "gmshToFoam": {"wall_s": g2f_wall, "rss_kb": int(g2f_rss)},
     "raw_speedup": pdm_wall / raw_wall}
runs = [json.load(open(f"{w}/untangle.{i}.out")) for i in range(1, repeats + 1)]
def budget(j):
    s = j["seconds"]
    return s["classify"] + s["dual"] + s["star_test"]
ratios = sorted(j["optimize"]["seconds"] / budget(j) for j in runs)
med = lambda xs: xs[len(xs) // 2] if len(xs) % 2 else (xs[len(xs) // 2 - 1] + xs[len(xs) // 2]) / 2
r["untangle"] = {"optimize_s": med(sorted(j["optimize"]["seconds"] for j in runs)),
                 "budget_s": med(sorted(budget(j) for j in runs)), "ratio": med(ratios),
                 "ratio_max": ratios[-1], "invalid_after": max(j["invalid_after"] for j in runs),
                 "max_quality": runs[0]["optimize"]["quality_after"]["max"]}
if with_default:
    wall, rss = open(f"{w}/default.time").read().split()
    j = json.load(open(f"{w}/default.out"))
    o = j["optimize"]
    valid_at = next((it["seconds"] for it in o["iterations"] if it["invalid"] == 0), None)
    r["default"] = {"wall_s": float(wall), "rss_kb": int(rss), "bytes_per_tet": int(rss) * 1024 / tets,
                    "optimize_s": o["seconds"], "invalid_before": j["invalid_before"],
                    "invalid_after": j["invalid_after"], "mean_quality": o["quality_after"]["mean"],
                    "vertex_updates": o["vertex_updates"],
                    "updates_per_s_per_core": o["vertex_updates_per_second"] / threads,
                    "time_to_valid_s": valid_at}
print(json.dumps(r))
f = r.get("default")
if f:
    ttv = "never" if f["time_to_valid_s"] is None else f"{f['time_to_valid_s']:.2f}"
    dflt = (f"{f['wall_s']:.2f} | {f['bytes_per_tet']:.0f} | {f['invalid_before']}→{f['invalid_after']} | "
            f"{f['mean_quality']:.3f} | {f['updates_per_s_per_core']:.0f} | {ttv}")
else:
    dflt = "– | – | – | – | – | –"
u = r["untangle"]
print(f"| {d} | {tets} | {r['cells']} | {raw_wall:.2f} | {r['raw']['bytes_per_tet']:.0f} | {pdm_wall:.2f} | "
      f"{pdm_rss * 1024 / tets:.0f} | **{r['raw_speedup']:.2f}×** | {g2f_wall:.2f} | "
      f"{u['optimize_s']:.3f} / {u['budget_s']:.3f} = **{u['ratio']:.2f}** (max {u['ratio_max']:.2f}) | {dflt} |")
PY
)
    head -1 <<< "$out" | tee -a "$work/results.jsonl"
    rows+=("$(tail -1 <<< "$out")")
  done
done
echo
echo "| domain | tets | cells | raw wall s | raw B/tet | polyDualMesh wall s | pDM B/tet | raw speed-up | gmshToFoam s (apart) | untangle optimiser / budget s (ratio) | default wall s | default B/tet | invalid before→after | mean κ/3 | updates/s/core | time to valid s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
