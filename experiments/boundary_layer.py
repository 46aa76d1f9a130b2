#!/usr/bin/env python3
"""Boundary layers that stay layers (design §14): the dual of a mixed mesh with
hexahedral wall layers against OpenFOAM's polyDualMesh on the same mesh.

The model: a channel around a cylinder, a 2D Gmsh mesh with a quadrangle
boundary layer on the cylinder's wall (BoundaryLayer field: first layer
`--first` thick, ratio 1.3) extruded in z with `Layers; Recombine`: hexahedra
in the wall layers, prisms elsewhere. For each mesh:
  - polydual convert --format foam (the default) and gmshToFoam + polyDualMesh
    30 (writeFormat binary) on the same Gmsh 2.2 file;
  - checkMesh -allGeometry -allTopology on both and on the primal itself
    (gmshToFoam's case): failed checks, max non-orthogonality, max skewness;
  - the dual's wall layers: the radial height of the dual cells that touch the
    wall against the primal's first layer (the dual's wall cell should be half
    of it), from polydual's VTU;
  - OpenFOAM's laplacianFoam on the harmonic u = x^2 - y^2 + z with u imposed
    on every boundary face (experiments/boundary_laplace.py): the L2 error on
    both duals.
Writes OUT/boundary_layer.json, paper/tables/boundary_layer.md and
paper/figures/fig_boundary_layer.png (a slice through the first z layer near
the wall: the primal's quads and triangles and polydual's dual faces).

usage: /usr/bin/python3 experiments/boundary_layer.py POLYDUAL OUT [--first H]
Needs Gmsh and Debian's openfoam.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import boundary_laplace  # noqa: E402  (the Laplace solve of a case)

ENV = dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam")
R_WALL = 0.5
GEO = """SetFactory("OpenCASCADE");
Rectangle(1) = {{-2, -1.5, 0, 6, 3}};
Disk(2) = {{0, 0, 0, {r}, {r}}};
BooleanDifference(3) = {{ Surface{{1}}; Delete; }}{{ Surface{{2}}; Delete; }};
MeshSize{{ PointsOf{{ Surface{{3}}; }} }} = 0.2;
c[] = Boundary{{ Surface{{3}}; }};
MeshSize{{ PointsOf{{ Curve{{c[4]}}; }} }} = {wall};
Field[1] = BoundaryLayer;
Field[1].CurvesList = {{c[4]}};
Field[1].Size = {first};
Field[1].Ratio = 1.3;
Field[1].Thickness = {thick};
Field[1].Quads = 1;
BoundaryLayer Field = 1;
out[] = Extrude {{0, 0, {dz}}} {{ Surface{{3}}; Layers{{{nz}}}; Recombine; }};
Physical Volume("fluid") = {{out[1]}};
"""


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, env=ENV, **kw)


def make_mesh(out, first):
    geo = os.path.join(out, "cylinder_layers.geo")
    with open(geo, "w") as f:
        f.write(GEO.format(r=R_WALL, wall=0.06, first=first, thick=first * 8, dz=0.4, nz=4))
    msh = os.path.join(out, "cylinder_layers.msh")
    p = run(["gmsh", "-3", geo, "-format", "msh22", "-o", msh])
    if p.returncode != 0:
        sys.exit("gmsh failed: " + p.stdout[-2000:] + p.stderr[-2000:])
    return msh


def checkmesh(case):
    text = run(["checkMesh", "-allGeometry", "-allTopology", "-case", case]).stdout
    with open(os.path.join(case, "checkMesh.log"), "w") as f:
        f.write(text)
    m = re.search(r"Failed (\d+) mesh checks", text)
    nonorth = re.search(r"Mesh non-orthogonality Max: ([0-9.eE+-]+) average: ([0-9.eE+-]+)", text)
    skew = re.search(r"Max skewness = ([0-9.eE+-]+)", text)
    cells = re.search(r"^\s+cells:\s+(\d+)", text, re.M)
    return {"failed_checks": 0 if "Mesh OK." in text else (int(m.group(1)) if m else None),
            "cells": int(cells.group(1)) if cells else None,
            "max_non_orthogonality": float(nonorth.group(1)) if nonorth else None,
            "mean_non_orthogonality": float(nonorth.group(2)) if nonorth else None,
            "max_skewness": float(skew.group(1)) if skew else None}


def foam_case(case, system_from):
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    shutil.copytree(os.path.join(system_from, "system"), os.path.join(case, "system"))
    cd = os.path.join(case, "system", "controlDict")
    with open(cd) as f:
        text = re.sub(r"(?m)^writeFormat .*$", "writeFormat     binary;", f.read())
    with open(cd, "w") as f:
        f.write(text)


def vtu_arrays(path):
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray[^>]*Name="([^"]+)"[^>]*>(.*?)</DataArray>', text, re.S):
        out.setdefault(m.group(1), m.group(2).split())
    return out


def dual_cells(vtu):
    """Per cell: its face loops (point ids) and the points, from an ASCII VTU."""
    a = vtu_arrays(vtu)
    p = [float(x) for x in a["Points"]]
    pts = [(p[3 * i], p[3 * i + 1], p[3 * i + 2]) for i in range(len(p) // 3)]
    faces = [int(x) for x in a["faces"]]
    ends = [int(x) for x in a["faceoffsets"]]
    cells, start = [], 0
    for end in ends:
        i, loops = start + 1, []
        for _ in range(faces[start]):
            n = faces[i]
            loops.append(faces[i + 1:i + 1 + n])
            i += 1 + n
        cells.append(loops)
        start = end
    return pts, cells


def radius(q):
    return math.hypot(q[0], q[1])


def primal_layers(msh):
    """Radii of the primal's vertices on the plane z = 0 near the wall, sorted:
    the wall's radius (the first) and the first layer's outer radius (the
    smallest radius clearly beyond the wall's)."""
    text = open(msh).read()
    nodes = text.split("$Nodes")[1].split("$EndNodes")[0].split("\n")[2:]
    radii = sorted({round(radius((float(l.split()[1]), float(l.split()[2]))), 9)
                    for l in nodes if l.strip() and abs(float(l.split()[3])) < 1e-12
                    and radius((float(l.split()[1]), float(l.split()[2]))) < R_WALL * 1.5})
    wall = radii[0]
    beyond = [r for r in radii if r > wall + 1e-6]
    return wall, beyond[0] - wall


def wall_layers(vtu, first):
    """Radial heights of the dual cells in the wall layer and the next one."""
    pts, cells = dual_cells(vtu)
    rows = []
    for loops in cells:
        ids = {i for loop in loops for i in loop}
        rs = [radius(pts[i]) for i in ids]
        if min(rs) < R_WALL + first:  # touches the wall or the first layer
            rows.append((min(rs), max(rs) - min(rs)))
    wall = [h for r0, h in rows if r0 < R_WALL - 1e-9 or abs(r0 - R_WALL) < 1e-6]
    next_layer = [h for r0, h in rows if R_WALL + 1e-6 < r0 < R_WALL + first]
    med = lambda v: sorted(v)[len(v) // 2] if v else None  # noqa: E731
    return {"wall_cells": len(wall), "wall_height_median": med(wall), "wall_height_max": max(wall) if wall else None,
            "next_layer_cells": len(next_layer), "next_layer_height_median": med(next_layer)}


def figure(vtu, msh, path, first):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    pts, cells = dual_cells(vtu)
    z_mid = 0.05  # the first z layer's mid-height (dz 0.4 / 4 layers / 2)
    window = 0.9
    polys = set()
    for loops in cells:
        for loop in loops:
            if all(abs(pts[i][2] - z_mid) < 1e-9 for i in loop) and all(radius(pts[i]) < window for i in loop):
                polys.add(tuple(loop))
    text = open(msh).read()
    nodes = {}
    for l in text.split("$Nodes")[1].split("$EndNodes")[0].split("\n")[2:]:
        if l.strip():
            f = l.split()
            nodes[int(f[0])] = (float(f[1]), float(f[2]), float(f[3]))
    primal = []
    for l in text.split("$Elements")[1].split("$EndElements")[0].split("\n")[2:]:
        f = l.split()
        if len(f) < 4 or f[1] not in ("5", "6"):  # hexahedra, prisms: their bottom face
            continue
        v = [nodes[int(x)] for x in f[3 + int(f[2]):]]
        v = v[:len(v) // 2]
        if all(abs(q[2]) < 1e-12 for q in v) and all(radius(q) < window for q in v):
            primal.append([(q[0], q[1]) for q in v])
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.add_collection(PolyCollection(primal, facecolors="none", edgecolors="0.6", linewidths=0.5))
    ax.add_collection(PolyCollection([[(pts[i][0], pts[i][1]) for i in p] for p in polys],
                                     facecolors="none", edgecolors="C3", linewidths=0.7))
    t = [i * math.pi / 180 for i in range(0, 361, 2)]
    ax.plot([R_WALL * math.cos(a) for a in t], [R_WALL * math.sin(a) for a in t], "k-", lw=0.8)
    ax.set_xlim(0.15, 0.15 + 0.55)
    ax.set_ylim(0.15, 0.15 + 0.55)
    ax.set_aspect("equal")
    ax.set_title("wall layers: the primal's hexahedra and prisms at z = 0 (grey),\n"
                 "polydual's dual faces at z = 0.05, the first layer's mid-height (red)")
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("polydual")
    ap.add_argument("out")
    ap.add_argument("--first", type=float, default=0.01, help="the first wall layer's thickness")
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    msh = make_mesh(out, a.first)
    rec = {"mesh": os.path.basename(msh), "first_layer": a.first}
    info = run([a.polydual, "info", msh]).stdout.strip()
    rec["info"] = info.splitlines()[0].replace(msh, os.path.basename(msh)) if info else ""
    pd = os.path.join(out, "polydual")
    shutil.rmtree(pd, ignore_errors=True)
    p = run([a.polydual, "convert", msh, "-o", pd, "--format", "foam", "--json", "--quiet"])
    if p.returncode != 0:
        sys.exit("polydual convert failed: " + p.stderr[-2000:])
    summary = json.loads(p.stdout)
    rec["polydual"] = {"cells": summary["cells"], "invalid_cells": summary["invalid_cells"],
                       "seconds": summary["seconds"]["total"]}
    vtu = os.path.join(out, "polydual.vtu")
    run([a.polydual, "convert", msh, "-o", vtu, "--vtu-encoding", "ascii", "--quiet"])
    primal = os.path.join(out, "primal")
    foam_case(primal, pd)
    run(["gmshToFoam", msh, "-case", primal])
    pdm = os.path.join(out, "polyDualMesh")
    foam_case(pdm, pd)
    run(["gmshToFoam", msh, "-case", pdm])
    q = run(["polyDualMesh", "30", "-case", pdm, "-overwrite"])
    if q.returncode != 0:
        sys.exit("polyDualMesh failed: " + q.stdout[-2000:])
    for name, case in (("primal", primal), ("polydual", pd), ("polyDualMesh", pdm)):
        rec.setdefault(name, {})["checkMesh"] = checkmesh(case)
    for name, case in (("polydual", pd), ("polyDualMesh", pdm)):
        try:
            l2, cells = boundary_laplace.solve(case)
            rec[name]["laplace_l2"] = l2
        except (subprocess.CalledProcessError, KeyError, AttributeError, FileNotFoundError) as e:
            rec[name]["laplace_l2"] = None
            rec[name]["laplace_error"] = f"{type(e).__name__}: {str(e)[:120]}"
    wall_r, h1 = primal_layers(msh)
    rec["primal_wall_radius"], rec["primal_first_layer"] = wall_r, h1
    rec["layers"] = wall_layers(vtu, h1)
    with open(os.path.join(out, "boundary_layer.json"), "w") as f:
        json.dump(rec, f, indent=1, sort_keys=True)
    write_outputs(rec, vtu, msh, a.first)


def write_outputs(rec, vtu, msh, first):
    fig = os.path.join(REPO, "paper", "figures", "fig_boundary_layer.png")
    figure(vtu, msh, fig, first)
    lay = rec["layers"]
    rows = ["| | cells | checkMesh failed | max non-orth. | mean non-orth. | max skewness | laplacianFoam L2 error |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for name in ("primal", "polydual", "polyDualMesh"):
        c = rec[name]["checkMesh"]
        l2 = rec[name].get("laplace_l2")
        rows.append(f"| {name} | {c['cells']} | {c['failed_checks']} | {c['max_non_orthogonality']:.1f} | "
                    f"{c['mean_non_orthogonality']:.2f} | {c['max_skewness']:.2f} | {'' if l2 is None else f'{l2:.3e}'} |")
    text = "\n".join([
        "# Boundary layers (generated by experiments/boundary_layer.py; do not edit)", "",
        f"Mesh: {rec['info']} (`{rec['mesh']}`: a channel around a cylinder, Gmsh BoundaryLayer quads "
        f"extruded with Layers and Recombine).", "",
        *rows, "",
        f"Wall layers of polydual's dual: the primal's first layer is {rec['primal_first_layer']:.4g} thick; "
        f"the {lay['wall_cells']} dual cells at the wall are {lay['wall_height_median']:.4g} high (median; max "
        f"{lay['wall_height_max']:.4g}), the {lay['next_layer_cells']} of the next layer "
        f"{lay['next_layer_height_median']:.4g}.", "",
        "![wall layers](../figures/fig_boundary_layer.png)", ""])
    path = os.path.join(REPO, "paper", "tables", "boundary_layer.md")
    with open(path, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
