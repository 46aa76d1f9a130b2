#!/usr/bin/env python3
"""Keep against caps (DualParams::boundary, design §4.10): converts each mesh
with `polydual convert --json --boundary MODE [extra options]` and prints one
markdown row per (mesh, mode): cells, faces, invalid cells, the final max and
mean kappa/3 (as the summary records them), the largest relative volume error of a material, and wall seconds.

usage: boundary_compare.py POLYDUAL OUTDIR MESH... [-- EXTRA CONVERT OPTIONS]
"""
import json
import os
import subprocess
import sys
import time

TIMEOUT = 900  # seconds per conversion


def final_quality(j):
    """The quality record of the mesh as written: the split's optimiser when it ran, else the optimiser's."""
    split_opt = j.get("split", {}).get("optimize")
    if split_opt and "quality_after" in split_opt:
        return split_opt["quality_after"]
    opt = j.get("optimize", {})
    return opt.get("quality_after") or opt.get("quality_before") or {}


def volume_error(j):
    worst, per = 0.0, []
    for m in j.get("materials", []):
        rel = abs(m["volume"] - m["primal_volume"]) / abs(m["primal_volume"])
        per.append(rel)
        worst = max(worst, rel)
    return worst, per


def run(polydual, outdir, mesh, mode, extra):
    name = os.path.basename(mesh).split(".")[0]
    out = os.path.join(outdir, f"{name}_{mode}.vtu")
    t0 = time.time()
    try:
        p = subprocess.run([polydual, "convert", mesh, "-o", out, "--json", "--boundary", mode] + extra,
                           capture_output=True, text=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return f"| {name} | {mode} | over {TIMEOUT} s |"
    secs = time.time() - t0
    if p.returncode != 0:
        return f"| {name} | {mode} | exit {p.returncode}: {p.stderr.strip()[:80]} |"
    j = json.loads(p.stdout)
    q = final_quality(j)
    worst, per = volume_error(j)
    return (f"| {name} | {mode} | {j['cells']} | {j['faces']} | {j['invalid_cells']} | "
            f"{q.get('max', float('nan')):.3g} | {q.get('mean', float('nan')):.3g} | "
            f"{worst:.2g} | {min(per) if per else 0:.2g} | {secs:.2f} |")


def main():
    args = sys.argv[1:]
    extra = []
    if "--" in args:
        k = args.index("--")
        args, extra = args[:k], args[k + 1:]
    if len(args) < 3 or args[0] in ("-h", "--help"):
        sys.exit(__doc__)
    polydual, outdir, meshes = args[0], args[1], args[2:]
    os.makedirs(outdir, exist_ok=True)
    print("| mesh | boundary | cells | faces | invalid | max k/3 | mean k/3 | worst vol. err | least vol. err | s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for mesh in meshes:
        for mode in ("caps", "keep"):
            print(run(polydual, outdir, mesh, mode, extra), flush=True)


if __name__ == "__main__":
    main()
