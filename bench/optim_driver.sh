#!/usr/bin/env bash
# Optimiser comparison on the paper's domains (paper 3.3): for each domain, the
# default local scheme (analytic derivatives), the paper's finite differences,
# ceres::Jet derivatives and the global Ceres L-BFGS, each through
# `polydual convert --json`. Prints a Markdown table: invalid cells before and
# after (exact), quality before/after, optimiser seconds, vertex updates per
# second, and where the remaining invalid cells sit.
#   bench/optim_driver.sh [polydual-binary] [tets, default 100000] [work dir] [variants]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../build/polydual}"
n="${2:-100000}"
work="${3:-$here/../bench-data/optim}"
variants="${4:-local:analytic local:fd local:exact global:analytic}"
mkdir -p "$work"
echo "| domain | tets | cells | method | derivatives | invalid before | invalid after | remaining at (vertex/edge/face/interior) | mean κ/3 before | after | optimiser s | updates/s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for d in cube twomat fichera fracture; do
  msh="$work/${d}_$n.msh"
  [ -f "$msh" ] || "$bin" generate "$d" --tets "$n" -o "$msh" 2>/dev/null
  for v in $variants; do
    m="${v%%:*}"; der="${v##*:}"
    out="$work/${d}_${n}_${m}_${der}"
    timeout 1800 "$bin" convert "$msh" -o "$out.vtu" --optimize "$m" --derivatives "$der" --json > "$out.json" || {
      echo "| $d | $n | | $m | $der | (failed or timed out) | | | | | | |"; continue; }
    /usr/bin/python3 - "$out.json" "$d" "$m" "$der" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); o = j["optimize"]
b = j["invalid_by_class"]
secs = o["seconds"]
ups = o["vertex_updates_per_second"]
qb, qa = o["quality_before"]["mean"], o["quality_after"]["mean"]
print(f"| {sys.argv[2]} | {j['tets']} | {j['cells']} | {sys.argv[3]} | {sys.argv[4]} | {j['invalid_before']} | "
      f"{j['invalid_after']} | {b['model_vertex']}/{b['model_edge']}/{b['model_face']}/{b['interior']} | "
      f"{qb:.3f} | {qa:.3f} | {secs:.1f} | {ups:.0f} |")
PY
  done
done
