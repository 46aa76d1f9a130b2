#!/usr/bin/python3
"""Records and tabulates the split: every domain with and without
splitting, with the default optimiser and without it, and draws the split
cells.

    /usr/bin/python3 experiments/split_compare.py [--polydual build/polydual]
        [--out results_split] [--sizes 20000] [--domains cube,...]
        [--variants nosplit,split,nosplit_none,split_none] [--paper] [--force]

STEP 1 generates each domain with `polydual generate`; STEP 2 converts every
variant with `polydual convert --json` and records the command, its wall time
and the JSON summary in OUT/records/<domain>_<size>_<variant>.json (reused for
the same command unless --force); STEP 3 renders the table from the records
only into OUT/tables/split.md and, with --paper, paper/split_tables.md, and
(VTK, off-screen: run under xvfb-run) one figure per sheet domain of the split
cells (cells sharing their `split_from` with another) into OUT/figures/ and,
with --paper, paper/figures/. Run with Debian's /usr/bin/python3.
"""
import argparse
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import tetopt_compare as tc  # noqa: E402  (one copy of the record, table and option helpers)

DOMAINS = ["cube", "twomat", "fichera", "fracture", "network", "fins"]
VARIANTS = {
    "nosplit": ["--no-split"],
    "split": [],
    "nosplit_none": ["--no-split", "--optimize", "none"],
    "split_none": ["--optimize", "none"],
}
FIGURE_DOMAINS = ["fichera", "fracture", "network", "fins"]


def final_quality(s):
    """Mean and max κ/3 of the mesh written: the split's last optimisation if
    it ran, else the optimiser's; None without an optimiser."""
    sp = s.get("split") or {}
    o = sp.get("optimize") or s.get("optimize") or {}
    q = o.get("quality_after") or {}
    return q.get("mean"), q.get("max")


def row(r):
    s = r["summary"]
    sp = s.get("split") or {}
    causes = sp.get("cells_split") or {}
    q_mean, q_max = final_quality(s)
    whole = sp["rounds"][-1]["vertices_whole"] if sp.get("rounds") else 0
    return [r["domain"], s["tets"], r["variant"], s["cells"], s["invalid_before"], s["invalid_after"], q_mean, q_max,
            r["wall_seconds"], len(sp.get("rounds", [])) if sp else None, whole if sp else None,
            causes.get("free_edge"), causes.get("sheet_crossing"),
            (causes.get("concave_edge") or 0) + (causes.get("concave_vertex") or 0) if causes else None,
            causes.get("invalid_after_optimisation")]


def table(recs):
    order = {v: i for i, v in enumerate(VARIANTS)}
    recs = sorted(recs, key=lambda r: (r["size"], DOMAINS.index(r["domain"]) if r["domain"] in DOMAINS else 99,
                                       order.get(r["variant"], 99)))
    return tc.md(["domain", "tets", "variant", "cells", "invalid before", "invalid after", "mean κ/3", "max κ/3",
               "wall s", "rounds", "vertices cut whole", "split: free edge", "sheet crossing", "concave edge/vertex",
               "invalid after optimisation"], [row(r) for r in recs])


def split_flags(grid):
    """Per cell 1 if another cell shares its split_from (a cell that was split), else 0."""
    import numpy as np
    from vtk.util import numpy_support
    a = grid.GetCellData().GetArray("split_from")
    if a is None:
        return None
    o = numpy_support.vtk_to_numpy(a)
    counts = np.bincount(o[o >= 0]) if (o >= 0).any() else np.zeros(1, dtype=int)
    flags = np.where(o >= 0, counts[np.maximum(o, 0)] > 1, False).astype(np.int32)
    arr = numpy_support.numpy_to_vtk(flags, deep=1)
    arr.SetName("split")
    grid.GetCellData().AddArray(arr)
    return int(flags.sum())


def figures(args, recs, fig_dir):
    import render as R
    os.makedirs(fig_dir, exist_ok=True)
    made = []
    for d in FIGURE_DOMAINS:
        pngs, titles = [], []
        for v, label in (("split", "default (optimised, then split)"), ("split_none", "--optimize none (split only)")):
            r = next((x for x in recs if x["domain"] == d and x["variant"] == v), None)
            if r is None or not os.path.exists(r.get("vtu", "")):
                continue
            g = R.read_vtu(r["vtu"])
            n = split_flags(g)
            if n is None:
                continue
            c = R.cut(g, axis=1, value=0.5)
            png = os.path.join(fig_dir, f"split_{d}_{v}.png")
            R.render(c, png, "material", f"{d}: {n} split cells (orange)", g.GetBounds(), highlight="split")
            pngs.append(png)
            titles.append(f"{label}: {r['summary']['cells']} cells, {r['summary']['invalid_after']} invalid")
        if pngs:
            out = os.path.join(fig_dir, f"fig_split_{d}.png")
            R.compose(pngs, titles, out, f"{d}: cells split (orange), cut at y = 0.5")
            made.append(out)
    return made


def render_all(args):
    recs = tc.load(args.out)
    body = table(recs)
    tdir = os.path.join(args.out, "tables")
    os.makedirs(tdir, exist_ok=True)
    with open(os.path.join(tdir, "split.md"), "w") as f:
        f.write(body)
    figs = figures(args, recs, os.path.join(args.out, "figures")) if not args.no_figures else []
    if args.paper:
        text = ("# With and without splitting\n\n"
                "Generated by `experiments/split_compare.py --paper` from its records; do not edit by hand.\n"
                "Invalid cells by the exact star test; quality is mean/max κ/3 (1 best) of the mesh written\n"
                "(none without an optimiser); wall seconds of the whole `convert` on a shared 2-core machine.\n"
                "Split cells are counted per uncut cell, by the cause of its vertex.\n\n" + body)
        for p in figs:
            dst = os.path.join(REPO, "paper", "figures", os.path.basename(p))
            shutil.copyfile(p, dst)
            text += f"\n![{os.path.basename(p)}](figures/{os.path.basename(p)})\n"
        with open(os.path.join(REPO, "paper", "split_tables.md"), "w") as f:
            f.write(text)
    print(body)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    tc.add_common_args(ap, os.path.join(REPO, "build", "results_split"), "20000", DOMAINS, VARIANTS)
    ap.add_argument("--no-figures", action="store_true")
    ap.add_argument("--paper", action="store_true", help="write paper/split_tables.md and its figures")
    args = tc.parse_common_args(ap, argv, VARIANTS)
    if not args.render_only:
        tc.measure(args, VARIANTS)
    render_all(args)


if __name__ == "__main__":
    main()
