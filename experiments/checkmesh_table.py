"""Summarises and tabulates the checkMesh logs of experiments/checkmesh_compare.sh.

usage: checkmesh_table.py summarise LOG_DIR TETS > SUMMARY.json
       checkmesh_table.py render SUMMARY.json         (prints Markdown on stdout)

summarise reads LOG_DIR/<domain>_<variant>.log for the variants polydual, pdm
(polyDualMesh) and pdm_concave (polyDualMesh -concaveMultiCells), as written by
checkMesh -allTopology -allGeometry (OpenFOAM v1912 wording), and prints one
JSON record per log found: its counts, or why checkMesh stopped early. A check
that passed prints no count, so its count is 0. render makes the table from
such a summary alone; the paper's is paper/data/checkmesh.json (the logs
themselves are not kept in the source tree).
"""
import json
import os
import re
import sys

DOMAINS = ["cube", "twomat", "fichera", "fracture", "network", "fins",
           "fractures3", "piston_fins"]  # the last two: tests/data/geo models meshed by gmsh itself
VARIANTS = [("polydual", "polydual"), ("pdm", "polyDualMesh"), ("pdm_concave", "polyDualMesh -concaveMultiCells")]


def first(pattern, text, default="0"):
    m = re.search(pattern, text, re.M)
    return m.group(1) if m else default


def parse(text):
    if "Checking geometry..." not in text:
        return None
    return {
        "cells": first(r"^\s+cells:\s+(\d+)", text, "?"),
        "negative": first(r"Number of negative volume cells:\s*(\d+)", text),
        "face_tets": first(r"Error in face pyramids:\s*(\d+) faces", text),
        "low_tets": first(r"Error in face tets:\s*(\d+) faces", text),
        "concave": first(r"Concave cells \(using face planes\) found, number of cells:\s*(\d+)", text),
        "nonorth_max": first(r"Mesh non-orthogonality Max:\s*([-\d.eE+]+)", text, "?"),
        "nonorth_mean": first(r"Mesh non-orthogonality Max:\s*[-\d.eE+]+\s+average:\s*([-\d.eE+]+)", text, "?"),
        "skew_max": first(r"Max skewness = ([-\d.eE+]+)", text, "?"),
        "errors": "0" if "Mesh OK." in text else first(r"Failed (\d+) mesh checks", text, "?"),
    }


def fmt(v):
    try:
        return f"{float(v):.3g}" if "." in v or "e" in v else v
    except ValueError:
        return v


def summarise(log_dir, tets):
    """The records of every log in log_dir, in the table's order."""
    rows = []
    for d in DOMAINS:
        for key, _ in VARIANTS:
            path = os.path.join(log_dir, f"{d}_{key}.log")
            if not os.path.exists(path):
                continue
            text = open(path, errors="replace").read()
            r = parse(text)
            if r is None:
                why = ("checkMesh crashed (segmentation fault) in its topology checks" if "sigSegv" in text
                       else "checkMesh did not reach the geometry checks")
                r = {"failure": why}
            rows.append({"domain": d, "variant": key, **r})
    return {"tets": int(tets), "source": "experiments/checkmesh_compare.sh", "rows": rows}


def render(summary):
    labels = dict(VARIANTS)
    print(f"checkMesh -allTopology -allGeometry on the domains at ~{summary['tets']} tets and on two models meshed by "
          "gmsh from tests/data/geo (fractures3: three crossing fractures; piston_fins: two wall fins) "
          "(experiments/checkmesh_compare.sh; recorded in paper/data/checkmesh.json).\n")
    print("| domain | mesh | cells | negative volumes | incorrectly oriented face pyramids | "
          "faces with bad decomposition tets (face tets) | concave cells | "
          "non-orthogonality max | non-orthogonality mean | skewness max | failed checks |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in summary["rows"]:
        d, label = r["domain"], labels[r["variant"]]
        if "failure" in r:
            print(f"| {d} | {label} | {r['failure']} | | | | | | | | |")
            continue
        print(f"| {d} | {label} | {r['cells']} | {r['negative']} | {r['face_tets']} | {r['low_tets']} | {r['concave']} | "
              f"{fmt(r['nonorth_max'])} | {fmt(r['nonorth_mean'])} | {fmt(r['skew_max'])} | {r['errors']} |")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "summarise":
        json.dump(summarise(sys.argv[2], sys.argv[3]), sys.stdout, indent=1)
        print()
    elif len(sys.argv) == 3 and sys.argv[1] == "render":
        render(json.load(open(sys.argv[2])))
    else:
        sys.exit(__doc__)
