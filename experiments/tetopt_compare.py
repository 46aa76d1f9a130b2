#!/usr/bin/python3
"""Records and tabulates polydual's own tet pre-optimisation (`convert
--optimize-tets`) and the local against the global optimiser,
per domain and size.

    /usr/bin/python3 experiments/tetopt_compare.py [--polydual build/polydual]
        [--out results_tetopt] [--sizes 20000,100000] [--domains cube,...]
        [--variants none,local,global,tetopt_none,tetopt_local,tetopt_noflip_none,...]
        [--paper] [--force]

STEP 1 generates each domain with `polydual generate`; STEP 2 converts every
variant with `polydual convert --json` and records the command, its wall time
and the JSON summary in OUT/records/<domain>_<size>_<variant>.json (a record
for the same command is reused unless --force); STEP 3 renders Markdown tables
from the records only into OUT/tables/, and with --paper into
paper/tetopt_tables.md. Run with Debian's /usr/bin/python3.
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
DOMAINS = ["cube", "twomat", "fichera", "fracture"]
# variant -> extra convert options
VARIANTS = {
    "none": ["--no-optimize-tets", "--optimize", "none"],
    "local": ["--no-optimize-tets", "--optimize", "local"],
    "global": ["--no-optimize-tets", "--optimize", "global"],
    # --optimize-tets: the moves, then the Delaunay flips (the default) ...
    "tetopt_none": ["--optimize-tets", "--optimize", "none"],
    "tetopt_local": ["--optimize-tets", "--optimize", "local"],
    "tetopt_global": ["--optimize-tets", "--optimize", "global"],
    # ... or the moves alone (--tet-flips off), as before the flip pass.
    "tetopt_noflip_none": ["--optimize-tets", "--tet-flips", "off", "--optimize", "none"],
    "tetopt_noflip_local": ["--optimize-tets", "--tet-flips", "off", "--optimize", "local"],
    # ... or N rounds of moves then flips (--tet-flip-rounds N).
    "tetopt_r2_none": ["--optimize-tets", "--tet-flip-rounds", "2", "--optimize", "none"],
    "tetopt_r3_none": ["--optimize-tets", "--tet-flip-rounds", "3", "--optimize", "none"],
    # The face-flatness term, local scheme.
    "planarity_1": ["--no-optimize-tets", "--optimize", "local", "--planarity", "1"],
    "planarity_10": ["--no-optimize-tets", "--optimize", "local", "--planarity", "10"],
    "planarity_100": ["--no-optimize-tets", "--optimize", "local", "--planarity", "100"],
}
DEFAULT_VARIANTS = [v for v in VARIANTS if not v.startswith("planarity") and v != "tetopt_global"]


def write_json(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(obj, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def run_step(record, cmd, force, parse_json):
    """Runs cmd unless `record` holds the same command; returns the record."""
    if not force and os.path.exists(record):
        with open(record) as f:
            rec = json.load(f)
        if rec.get("command") == cmd:
            return rec
    start = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True)
    rec = {"command": cmd, "returncode": p.returncode, "wall_seconds": time.monotonic() - start}
    if p.returncode != 0:
        rec["stderr"] = p.stderr[-4000:]
    elif parse_json:
        rec["summary"] = json.loads(p.stdout)
    write_json(record, rec)
    return rec


def measure(args, variants=None):
    """Generates every domain and size, then converts each variant of
    `variants` (name -> extra convert options; default VARIANTS), recording
    each step in OUT/records/ (the VTU's path with it)."""
    variants = VARIANTS if variants is None else variants
    rec_dir = os.path.join(args.out, "records")
    mesh_dir = os.path.join(args.out, "meshes")
    os.makedirs(rec_dir, exist_ok=True)
    os.makedirs(mesh_dir, exist_ok=True)
    for size in args.sizes:
        for d in args.domains:
            msh = os.path.join(mesh_dir, f"{d}_{size}.msh")
            gen = [args.polydual, "generate", d, "--tets", str(size), "-o", msh]
            r = run_step(os.path.join(rec_dir, f"generate_{d}_{size}.json"), gen, args.force or not os.path.exists(msh), False)
            print(f"generate {d} {size}: rc {r['returncode']}", flush=True)
            for v in args.variants:
                vtu = os.path.join(mesh_dir, f"{d}_{size}_{v}.vtu")
                cmd = [args.polydual, "convert", msh, "-o", vtu, "--force", "--json", "--quiet"] + variants[v]
                rec = os.path.join(rec_dir, f"{d}_{size}_{v}.json")
                r = run_step(rec, cmd, args.force or not os.path.exists(vtu), True)
                r.update({"domain": d, "size": size, "variant": v, "vtu": vtu})
                write_json(rec, r)
                print(f"  {v}: rc {r['returncode']} {r['wall_seconds']:.1f}s", flush=True)


def load(out):
    recs = []
    rec_dir = os.path.join(out, "records")
    for name in sorted(os.listdir(rec_dir)):
        with open(os.path.join(rec_dir, name)) as f:
            r = json.load(f)
        if "variant" in r and "summary" in r:
            recs.append(r)
    return recs


def get(recs, d, size, v):
    for r in recs:
        if r["domain"] == d and r["size"] == size and r["variant"] == v:
            return r["summary"]
    return None


def fmt(x, nd=3):
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:.{nd}f}"
    return str(x)


def md(header, rows):
    out = "| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n"
    for row in rows:
        out += "| " + " | ".join(fmt(c) for c in row) + " |\n"
    return out


def opt_quality(s):
    o = s.get("optimize") or {}
    return (o.get("quality_after") or {}).get("mean"), o.get("seconds")


def updates(s):
    """The local optimiser's vertex updates: its work, free of the machine's load."""
    return ((s or {}).get("optimize") or {}).get("vertex_updates")


def keys(recs):
    ks = sorted({(r["size"], r["domain"]) for r in recs}, key=lambda k: (k[0], DOMAINS.index(k[1]) if k[1] in DOMAINS else 99))
    return ks


def table_tetopt(recs):
    """Moves alone (tetopt_noflip_*) and moves + flips (tetopt_*) against the
    raw input: tet quality, invalid cells before the dual's optimiser, and the
    local optimiser's final quality, invalid cells and time."""
    rows = []
    for size, d in keys(recs):
        raw, loc = get(recs, d, size, "none"), get(recs, d, size, "local")
        if not raw:
            continue
        for label, pre_v, loc_v in (("moves", "tetopt_noflip_none", "tetopt_noflip_local"),
                                    ("moves + flips", "tetopt_none", "tetopt_local"),
                                    ("2 rounds", "tetopt_r2_none", None), ("3 rounds", "tetopt_r3_none", None)):
            pre, ploc = get(recs, d, size, pre_v), get(recs, d, size, loc_v) if loc_v else None
            loc = get(recs, d, size, "local") if loc_v else None  # rounds rows: no local columns
            if not pre:
                continue
            t = pre.get("optimize_tets", {})
            fl = t.get("flips")
            rows.append([d, raw["tets"], label, pre["tets"], t["before"]["mean"], t["after"]["mean"], t["after"]["max"],
                         fl["non_delaunay_before"]["free"] if fl else None,
                         fl["non_delaunay_after"]["free"] if fl else None,
                         fl["non_delaunay_after"]["constrained"] if fl else None,
                         fl["flips23"] + fl["flips32"] if fl else None, t["seconds"],
                         raw["invalid_before"], pre["invalid_before"],
                         opt_quality(loc)[0] if loc else None, opt_quality(ploc)[0] if ploc else None,
                         opt_quality(loc)[1] if loc else None, opt_quality(ploc)[1] if ploc else None,
                         updates(loc), updates(ploc),
                         loc["invalid_after"] if loc else None, ploc["invalid_after"] if ploc else None])
    return md(["domain", "tets (raw)", "pre-opt", "tets (pre-opt)", "tet q mean before", "after", "tet q max after",
               "non-Delaunay free faces before flips", "after", "non-Delaunay model faces after", "flips",
               "tet opt s", "invalid cells (raw)", "invalid cells (pre-opt)", "local mean κ/3 (raw)", "(pre-opt)",
               "local s (raw)", "(pre-opt)", "local vertex updates (raw)", "(pre-opt)",
               "local invalid after (raw)", "(pre-opt)"], rows)


def table_local_global(recs):
    rows = []
    for size, d in keys(recs):
        loc, glo = get(recs, d, size, "local"), get(recs, d, size, "global")
        if not loc or not glo:
            continue
        (ql, tl), (qg, tg) = opt_quality(loc), opt_quality(glo)
        rows.append([d, loc["tets"], loc["invalid_before"], ql, loc["invalid_after"], tl, qg, glo["invalid_after"], tg,
                     100.0 * (qg / ql - 1.0) if ql and qg else None, tg / tl if tl and tg else None])
    return md(["domain", "tets", "invalid before", "local mean κ/3", "local invalid after", "local s",
               "global mean κ/3", "global invalid after", "global s", "global vs local %", "time global/local"], rows)


def table_flatness(recs):
    rows = []
    for size, d in keys(recs):
        for v in ("none", "local", "global", "tetopt_local", "tetopt_noflip_local"):
            s = get(recs, d, size, v)
            if not s or "face_flatness" not in s:
                continue
            f = s["face_flatness"]
            rows.append([d, s["tets"], v, f["min"], f["mean"], f["warped"], f["max_plane_deviation"], f["mean_plane_deviation"]])
    return md(["domain", "tets", "variant", "flatness min", "flatness mean", "warped (<0.8)", "plane dev max", "plane dev mean"], rows)


def table_planarity(recs):
    rows = []
    for size, d in keys(recs):
        for v, w in (("local", 0), ("planarity_1", 1), ("planarity_10", 10), ("planarity_100", 100)):
            s = get(recs, d, size, v)
            if not s or "face_flatness" not in s:
                continue
            f = s["face_flatness"]
            q = (s.get("optimize") or {}).get("quality_after") or {}
            rows.append([d, s["tets"], w, q.get("mean"), q.get("max"), s["invalid_after"], f["min"], f["mean"],
                         f["warped"], f["max_plane_deviation"], f["mean_plane_deviation"], (s.get("optimize") or {}).get("seconds")])
    return md(["domain", "tets", "--planarity W", "mean κ/3", "max κ/3", "invalid after", "flatness min", "flatness mean",
               "warped (<0.8)", "plane dev max", "plane dev mean", "optimise s"], rows)


def face_flatness_values(vtu):
    """OpenFOAM's flatness (projected / actual area, fan around the
    area-weighted centre, as quality/flatness.cpp) of every face of a polydual
    VTU, each face once (keyed by its sorted point ids)."""
    import numpy as np
    import vtk
    from vtk.util import numpy_support
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(vtu)
    r.Update()
    g = r.GetOutput()
    pts = numpy_support.vtk_to_numpy(g.GetPoints().GetData())
    faces = numpy_support.vtk_to_numpy(g.GetFaces())
    seen, out, i = set(), [], 0
    for _ in range(g.GetNumberOfCells()):
        nf = int(faces[i]); i += 1
        for _ in range(nf):
            n = int(faces[i]); ids = faces[i + 1:i + 1 + n]; i += 1 + n
            key = tuple(sorted(ids.tolist()))
            if key in seen:
                continue
            seen.add(key)
            p = pts[ids]
            m = p.mean(axis=0)
            q = np.roll(p, -1, axis=0)
            tri = 0.5 * np.cross(q - p, m - p)
            S = tri.sum(axis=0)
            s = np.linalg.norm(S)
            if n == 3 or s == 0:
                out.append(1.0)
                continue
            u = S / s
            w = tri @ u
            c = ((w[:, None] * (p + q + m) / 3.0).sum(axis=0) / w.sum()) if w.sum() != 0 else m
            actual = 0.5 * np.linalg.norm(np.cross(q - p, c - p), axis=1).sum()
            out.append(min(1.0, s / actual) if actual > 0 else 1.0)
    return np.array(out)


def flatness_figure(args, recs, out_png):
    """Histograms of face flatness per planarity weight, one panel per domain."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    doms = sorted({r["domain"] for r in recs if r["variant"].startswith("planarity")},
                  key=lambda d: DOMAINS.index(d) if d in DOMAINS else 99)
    if not doms:
        return None
    fig, axes = plt.subplots(1, len(doms), figsize=(4.6 * len(doms), 3.6), dpi=120, squeeze=False)
    for ax, d in zip(axes[0], doms):
        for v, w in (("local", 0), ("planarity_10", 10), ("planarity_100", 100)):
            r = next((x for x in recs if x["domain"] == d and x["variant"] == v), None)
            if r is None:
                continue
            vtu = os.path.join(args.out, "meshes", f"{d}_{r['size']}_{v}.vtu")
            if not os.path.exists(vtu):
                continue
            f = face_flatness_values(vtu)
            ax.hist(f, bins=60, range=(0.8, 1.0), histtype="step", log=True, label=f"W = {w} (min {f.min():.3f})")
        ax.set_title(f"{d}: face flatness (OpenFOAM)", fontsize=10)
        ax.set_xlabel("projected / actual area")
        ax.legend(fontsize=8, loc="upper left")
    axes[0][0].set_ylabel("faces")
    fig.tight_layout()
    fig.savefig(out_png, metadata={"Software": None})
    plt.close(fig)
    return out_png


def render(args):
    recs = load(args.out)
    tables = {"tetopt_pre": table_tetopt(recs), "local_global": table_local_global(recs), "flatness": table_flatness(recs),
              "planarity": table_planarity(recs)}
    tdir = os.path.join(args.out, "tables")
    os.makedirs(tdir, exist_ok=True)
    for name, body in tables.items():
        with open(os.path.join(tdir, name + ".md"), "w") as f:
            f.write(body)
    if args.paper:
        text = ("# Tet pre-optimisation, local against global, face flatness\n\n"
                "Generated by `experiments/tetopt_compare.py --paper` from its records; do not edit by hand.\n"
                "Quality is mean κ/3 (1 best). Times are wall seconds of the stage on a shared 2-core machine.\n\n"
                "## With and without `--optimize-tets`\n\n"
                "pre-opt: `moves` is `--optimize-tets --tet-flips off` (condition-number moves alone), `moves + flips` "
                "`--optimize-tets` (the default: the moves, then Delaunay flips), `N rounds` `--tet-flip-rounds N`. "
                "Invalid cells are those of the initial dual (before the dual's optimiser); the local vertex updates "
                "count the local optimiser's work, which the machine's load does not change.\n\n" + tables["tetopt_pre"] +
                "\n## Local against global optimiser\n\n" + tables["local_global"] +
                "\n## Face flatness of the dual (OpenFOAM's measure; best-fit plane deviation / diameter)\n\n" +
                tables["flatness"])
        # Each paper file only from a run that holds its records (a planarity-only
        # run leaves tetopt_tables.md as it was, and the reverse).
        if any(r["variant"].startswith("tetopt") for r in recs):
            with open(os.path.join(REPO, "paper", "tetopt_tables.md"), "w") as f:
                f.write(text)
        if any(r["variant"].startswith("planarity") for r in recs):
            with open(os.path.join(REPO, "paper", "planarity_tables.md"), "w") as f:
                f.write("# Quality against flatness against time: the planarity weight\n\n"
                        "Generated by `experiments/tetopt_compare.py --variants local,planarity_1,planarity_10,"
                        "planarity_100 --paper` from its records; do not edit by hand. `--planarity W` adds W x the\n"
                        "flatness deficit of the faces around each point (optim/planarity.h) to the local scheme's\n"
                        "objective; flatness is OpenFOAM's (projected / actual area), plane deviation the largest\n"
                        "distance from the best-fit plane over the face's diameter; optimise s: wall seconds of the\n"
                        "stage on a shared 2-core machine.\n\n" + tables["planarity"])
            png = flatness_figure(args, recs, os.path.join(REPO, "paper", "figures", "fig_flatness.png"))
            if png:
                with open(os.path.join(REPO, "paper", "planarity_tables.md"), "a") as f:
                    f.write("\n![face flatness per weight](figures/fig_flatness.png)\n")
    for name, body in tables.items():
        print(f"## {name}\n{body}")


def add_common_args(ap, out, sizes, domains, variants, variants_help=None):
    """The options every compare script shares (variants: the default list)."""
    ap.add_argument("--polydual", default=os.path.join(REPO, "build", "polydual"))
    ap.add_argument("--out", default=out, help="results directory (default under build/)")
    ap.add_argument("--sizes", default=sizes)
    ap.add_argument("--domains", default=",".join(domains))
    ap.add_argument("--variants", default=",".join(variants), help=variants_help)
    ap.add_argument("--render-only", action="store_true")
    ap.add_argument("--force", action="store_true")


def parse_common_args(ap, argv, variants):
    """Parses argv; sizes, domains and variants become lists, unknown variants an error."""
    args = ap.parse_args(argv)
    args.sizes = [int(s) for s in args.sizes.split(",")]
    args.domains = args.domains.split(",")
    args.variants = args.variants.split(",")
    for v in args.variants:
        if v not in variants:
            sys.exit(f"unknown variant {v} (one of {','.join(variants)})")
    return args


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_common_args(ap, os.path.join(REPO, "build", "results_tetopt"), "20000,100000", DOMAINS, DEFAULT_VARIANTS,
                    "default: all but tetopt_global and the planarity_* variants (add them by name)")
    ap.add_argument("--paper", action="store_true", help="write paper/tetopt_tables.md")
    args = parse_common_args(ap, argv, VARIANTS)
    if not args.render_only:
        measure(args)
    render(args)


if __name__ == "__main__":
    main()
