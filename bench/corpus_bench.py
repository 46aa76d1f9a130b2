#!/usr/bin/python3
"""Work bounded by size: seconds per thousand tets of every stage of the
default `polydual convert`, over a corpus of meshes that other tools wrote.

The corpus is made in WORK from Debian's tools (nothing is downloaded):
  - Gmsh OpenCASCADE models of tests/data/geo (fractures, fins, holes and an
    inclusion, a sphere, a coarse sphere) at Gmsh's default size and finer;
  - the demo's built-in domains (`polydual generate`);
  - TetGen (when the tetgen command is installed) on the PLCs of
    tests/data/tetgen, with its quality bound (-q) and without it (slivers).
With --corpus tests the meshes of the tests' corpus are taken instead, with
--corpus all both (tests/corpus/corpus.py, the one list of that corpus: Gmsh, TetGen, CGAL Mesh_3 and Netgen meshes of the
models there; the Mesh_3 generators from build/tests/meshgen unless given).
Each mesh is converted once, `--threads 1 --json`; the table gives, per mesh,
its tets, cells, and seconds per 1000 tets of each stage of the summary's
`seconds.stages`, then per stage the maximum over the corpus and the mesh that
reached it. A stage whose time grows with anything but the mesh shows as a
row far above the others.

  bench/corpus_bench.py [--bin build/polydual] [--work bench-data/corpus] [--quick]
                        [--corpus bench|tests|all]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GEO = os.path.join(ROOT, "tests", "data", "geo")
PLC = os.path.join(ROOT, "tests", "data", "tetgen")


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def gmsh_meshes(work, quick):
    """(name, path) of Gmsh meshes of the committed .geo models."""
    out = []
    if not shutil.which("gmsh"):
        print("corpus: gmsh not installed, its models skipped", file=sys.stderr)
        return out
    scales = [1.0] if quick else [1.0, 0.5]
    for geo in ["fractures3", "piston_fins", "holes_inclusion", "sphere", "sphere_coarse", "twovol", "hole"]:
        for s in scales:
            if geo == "sphere_coarse" and s != 1.0:
                continue
            extra = ["-clscale", "2"] if geo == "sphere_coarse" else ["-clscale", str(s)]
            name = f"gmsh_{geo}_{s:g}"
            path = os.path.join(work, name + ".msh")
            if not os.path.exists(path):
                run(["gmsh", "-3", os.path.join(GEO, geo + ".geo"), *extra, "-format", "msh4", "-o", path])
            out.append((name, path))
    return out


def domain_meshes(work, binary, quick):
    out = []
    for dom in ["cube", "twomat", "fichera", "fracture", "network", "fins"]:
        for tets in ([20000] if quick else [20000, 100000]):
            name = f"{dom}_{tets // 1000}k"
            path = os.path.join(work, name + ".msh")
            if not os.path.exists(path):
                run([binary, "generate", dom, "--tets", str(tets), "-o", path, "--quiet"])
            out.append((name, path))
    return out


def tetgen_meshes(work):
    out = []
    if not shutil.which("tetgen"):
        print("corpus: tetgen not installed (Debian package tetgen), its meshes skipped", file=sys.stderr)
        return out
    for plc in ["fichera", "two_boxes", "cube"]:
        # With the quality bound and a volume bound; without either (slivers).
        for tag, flags in [("q", "-pqAa0.002"), ("noq", "-pAa0.0005")]:
            name = f"tetgen_{plc}_{tag}"
            d = os.path.join(work, name)
            if not os.path.exists(os.path.join(d, plc + ".1.ele")):
                os.makedirs(d, exist_ok=True)
                shutil.copy(os.path.join(PLC, plc + ".poly"), d)
                run(["tetgen", flags, plc + ".poly"], cwd=d)
            out.append((name, os.path.join(d, plc + ".1.node")))
    return out


def tests_corpus_meshes(work, generators):
    """(name, path) of the tests' corpus (tests/corpus/corpus.py), one list for both."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "corpus"))
    import corpus
    out = []
    for name in corpus.names():
        try:
            out.append((name, corpus.make(name, os.path.join(work, "tests"), generators)))
        except (corpus.Skip, corpus.MakeError) as e:
            print(f"corpus: {name} skipped: {e}", file=sys.stderr)
    return out


def convert(binary, name, path, work):
    res = subprocess.run([binary, "convert", path, "-o", os.path.join(work, name + ".vtu"), "--force", "--json",
                          "--quiet", "--threads", "1"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if res.returncode != 0:
        return None, res.stderr.strip().splitlines()[-1:] or ["exit %d" % res.returncode]
    return json.loads(res.stdout), None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "polydual"))
    ap.add_argument("--work", default=os.path.join(ROOT, "bench-data", "corpus"))
    ap.add_argument("--quick", action="store_true", help="one size per model (about a minute)")
    ap.add_argument("--corpus", choices=["bench", "tests", "all"], default="bench",
                    help="this script's meshes, the tests' corpus (tests/corpus), or both")
    gen_dir = os.path.join(ROOT, "build", "tests", "meshgen")
    for gen in ("labelled_image_medit", "polyhedral_features_medit"):
        ap.add_argument("--" + gen, default=os.path.join(gen_dir, gen), help="the CGAL Mesh_3 generator's binary")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    corpus = []
    if a.corpus in ("bench", "all"):
        corpus += gmsh_meshes(a.work, a.quick) + domain_meshes(a.work, a.bin, a.quick) + tetgen_meshes(a.work)
    if a.corpus in ("tests", "all"):
        gens = {g: getattr(a, g) for g in ("labelled_image_medit", "polyhedral_features_medit")}
        corpus += tests_corpus_meshes(a.work, gens)
    rows, stages, failed = [], [], []
    for name, path in corpus:
        d, err = convert(a.bin, name, path, a.work)
        if d is None:
            failed.append((name, err))
            continue
        st = d["seconds"]["stages"]
        for s in st:
            if s not in stages:
                stages.append(s)
        rows.append((name, d["tets"], d["cells"], st, d["seconds"]["total"], d["invalid_after"]))
    print("| mesh | tets | cells | total s | " + " | ".join(stages) + " | invalid |")
    print("|---|---|---|---|" + "---|" * len(stages) + "---|")
    for name, tets, cells, st, total, inv in rows:
        per = [f"{1000 * st.get(s, 0) / tets:.4f}" for s in stages]
        print(f"| {name} | {tets} | {cells} | {total:.2f} | " + " | ".join(per) + f" | {inv} |")
    # Below 1000 tets a stage's fixed cost (milliseconds) dominates its rate.
    big = [r for r in rows if r[1] >= 1000] or rows
    print("\nseconds per 1000 tets, maximum over the meshes of 1000 tets or more (and the mesh):")
    for s in stages:
        worst = max(big, key=lambda r: r[3].get(s, 0) / r[1])
        print(f"  {s:12s} {1000 * worst[3].get(s, 0) / worst[1]:.4f}  ({worst[0]})")
    worst = max(big, key=lambda r: r[4] / r[1])
    print(f"  {'total':12s} {1000 * worst[4] / worst[1]:.4f}  ({worst[0]})")
    slowest = max(rows, key=lambda r: r[4])
    print(f"slowest mesh: {slowest[0]} ({slowest[1]} tets, {slowest[4]:.2f} s)")
    for name, err in failed:
        print(f"refused: {name}: {' '.join(err)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
