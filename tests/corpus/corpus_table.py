#!/usr/bin/python3
"""Prints the corpus table that run_corpus.py recorded, in markdown (for
bench/README.md): per mesh its tets, the uncut and final cells, the targets
(max kappa/3, cells the split added, worst per-material volume
error, CPU seconds per 1000 tets of the --threads 1 run, the cells of
--optimize none over the uncut dual) with the ones missed marked, the
summary's wall seconds and the cells --optimize untangle's split added; then the producers' versions,
the meshes that were skipped, and the run's failures and notes (a target met
or improved: passing ctest runs do not show them).

  corpus_table.py WORK/corpus_table.json
"""
import json
import sys


def cell(v, bound, fmt):
    text = format(v, fmt)
    return f"**{text}**" if not v <= bound else text


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    t = json.load(open(argv[1]))
    b = t["targets"]
    print(f"| mesh | tets | uncut cells | cells | split added % (<= {b['split_added_pct']:g}) "
          f"| max κ/3 (<= {b['max_kappa3']:g}) | mean κ/3 | volume error %, caps "
          f"| volume error %, keep (<= {b['keep_volume_error_pct']:g}) "
          f"| CPU s / 1000 tets (<= {b['seconds_per_ktets']:g}) | wall s "
          f"| `--optimize none`: cells / uncut (<= {b['none_cells_ratio']:g}) "
          f"| `--optimize untangle`: split added % |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in t["meshes"]:
        print(f"| {r['mesh']} | {r['tets']} | {r['uncut_cells']} | {r['cells']} "
              f"| {cell(r['split_added_pct'], b['split_added_pct'], '.1f')} "
              f"| {cell(r['max_kappa3'], b['max_kappa3'], '.3g')} | {r['mean_kappa3']:.3f} "
              f"| {r['volume_error_pct']:.2g} "
              f"| {cell(r['keep_volume_error_pct'], b['keep_volume_error_pct'], '.2g')} "
              f"| {cell(r['seconds_per_ktets'], b['seconds_per_ktets'], '.3f')} | {r['seconds']:.2f} "
              f"| {cell(r['none_cells_ratio'], b['none_cells_ratio'], '.2f')} "
              f"| {r['untangle_split_added_pct']:.1f} |")
    missed = {k: sum(1 for r in t["meshes"] if not r[k] <= b[k]) for k in b}
    print(f"\n{len(t['meshes'])} meshes; bold: target missed (" +
          ", ".join(f"{k} {n}" for k, n in missed.items()) + ")")
    if t.get("producers"):
        print("producers (Debian packages): " + ", ".join(f"{k} {v}" for k, v in t["producers"].items()))
    if t.get("skipped"):
        print(f"skipped (tool missing): {', '.join(t['skipped'])}")
    for key in ("failures", "notes"):
        for line in t.get(key, []):
            print(f"- {key[:-1]}: {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
