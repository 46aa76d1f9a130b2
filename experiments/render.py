#!/usr/bin/python3
"""Renders the figures and tables of the paper reproduction from the records
that experiments/run.py wrote; never from hand-edited data.

    xvfb-run -a /usr/bin/python3 experiments/render.py --out results [--paper paper]

Reads  OUT/records/*.json and the meshes/VTUs they name (OUT/work/...).
Writes OUT/figures/<domain>_{a_tets,b_initial_cut,c_optimised_cut,d_optimised}.png,
       OUT/figures/fig_<domain>.png (the four panels, like the paper's Figs. 7-10),
       OUT/tables/*.md.
With --paper DIR it copies figures and tables to DIR/figures, DIR/tables and
replaces every block <!-- BEGIN table:NAME --> ... <!-- END table:NAME --> in
DIR/README.md by OUT/tables/NAME.md.
"""
import argparse
import glob
import json
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DOMAINS = ["cube", "twomat", "fichera", "fracture", "network", "fins"]
PAPER_FIG = {"cube": "paper Fig. 7", "twomat": "paper Fig. 8", "fichera": "paper Fig. 9",
             "fracture": "paper Fig. 10", "network": "not in the paper", "fins": "not in the paper"}
# Preferred optimised variant for the figures: the paper's scheme if it ran.
FIGURE_VARIANTS = ["local_q1_fd", "global_q1"]
TETOPT_FIGURE_VARIANTS = ["tetopt_local_q1_fd", "tetopt_global_q1"]
VARIANT_ORDER = ["none", "local_q1_fd", "local_q1_exact", "local_q2_fd", "global_q1",
                 "global_q2", "tetopt_none", "tetopt_local_q1_fd", "tetopt_global_q1"]


def load_records(out):
    recs = []
    for p in sorted(glob.glob(os.path.join(out, "records", "*.json"))):
        with open(p) as f:
            r = json.load(f)
        r["_name"] = os.path.splitext(os.path.basename(p))[0]
        recs.append(r)
    return recs


def find(recs, **kw):
    return [r for r in recs if all(r.get(k) == v for k, v in kw.items())]


def one(recs, **kw):
    r = find(recs, **kw)
    return r[0] if r else None


def dom_key(d):
    return DOMAINS.index(d) if d in DOMAINS else 99


def fmt(x, nd=3):
    if x is None:
        return "–"
    if isinstance(x, float):
        if x != 0 and (abs(x) >= 1e4 or abs(x) < 10 ** -nd):
            return f"{x:.{nd}g}"
        return f"{x:.{nd}f}"
    return str(x)


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(fmt(c) for c in row) + " |" for row in rows]
    return "\n".join(out) + "\n"


def deriv_label(r):
    return "analytic" if r["optimize"] == "global" else ("–" if r["optimize"] == "none"
                                                         else r["derivatives"])


def converts(recs):
    """The convert records of the tables ("dual", the unsplit dual, is the
    figures' panel (b) only)."""
    rs = [r for r in recs if r.get("kind") == "convert" and r["variant"] != "dual"]
    return sorted(rs, key=lambda r: (r["target_tets"], dom_key(r["domain"]),
                                     VARIANT_ORDER.index(r["variant"])
                                     if r["variant"] in VARIANT_ORDER else 99))


# ----------------------------------------------------------------------------- tables
def table_meshes(recs):
    """Per domain and size: counts and invalid cells before/after each optimiser."""
    rows = []
    for r in converts(recs):
        if r["variant"] != "none" or not r.get("ok"):
            continue
        s = r["summary"]
        d, n = r["domain"], r["target_tets"]
        after = []
        for v in ("local_q1_fd", "global_q1"):
            o = one(recs, kind="convert", domain=d, target_tets=n, variant=v)
            after.append(o["summary"]["invalid_after"] if o and o.get("ok") else None)
        rows.append([d, n, s["tets"], s["vertices"], s["cells"], s["faces"], s["points"],
                     s["dual"]["clamped_tets"], s["invalid_before"], after[0], after[1],
                     s["slit_cells"]])
    hdr = ["domain", "target tets", "tets", "tet vertices", "dual cells", "dual faces",
           "dual points", "clamped centres", "invalid initial", "invalid after local Q1",
           "invalid after global Q1", "slit cells"]
    return md_table(hdr, rows)


def table_optimisers(recs):
    """Every optimiser variant: invalid and quality (kappa/3 of its metric) before/after."""
    rows = []
    for r in converts(recs):
        if r["optimize"] == "none":
            continue
        if not r.get("ok"):
            rows.append([r["domain"], r["target_tets"], r["input"], r["optimize"], r["metric"],
                         deriv_label(r)] + ["failed"] + [None] * 9)
            continue
        o = r["summary"]["optimize"]
        qb, qa = o["quality_before"], o["quality_after"]
        rows.append([r["domain"], r["target_tets"], r["input"], r["optimize"], r["metric"].upper(),
                     deriv_label(r), o["invalid_before"], o["invalid_after"],
                     qb["min"], qb["mean"], qb["max"], qa["min"], qa["mean"], qa["max"],
                     len(o["iterations"]) - 1, o["seconds"]])
    hdr = ["domain", "target tets", "input", "optimiser", "metric", "derivatives",
           "invalid before", "invalid after", "quality before min", "mean", "max",
           "quality after min", "mean", "max", "iterations", "optimise s"]
    return md_table(hdr, rows)


def table_timing(recs):
    """Seconds per stage (from the "seconds" record of convert)."""
    stages = ["read", "classify", "dual", "star_test", "optimize", "write", "total"]
    rows = []
    for r in converts(recs):
        if not r.get("ok"):
            continue
        s = r["summary"]["seconds"]
        o = r["summary"].get("optimize") or {}
        rows.append([r["domain"], r["target_tets"], r["variant"], r["summary"]["tets"]]
                    + [s.get(k) for k in stages]
                    + [o.get("vertex_updates_per_second"),
                       1e6 * (s.get("classify", 0) + s.get("dual", 0)) / r["summary"]["tets"]])
    hdr = ["domain", "target tets", "variant", "tets"] + [f"{k} s" for k in stages] + \
          ["vertex updates/s", "classify+dual µs/tet"]
    return md_table(hdr, rows)


def table_derivatives(recs):
    """fd vs exact derivatives, and Q1 vs Q2, for the local scheme."""
    rows = []
    for r in converts(recs):
        if r["optimize"] != "local" or r["input"] != "raw" or not r.get("ok"):
            continue
        o = r["summary"]["optimize"]
        times = [it["seconds"] for it in o["iterations"] if it["invalid"] == 0]
        rows.append([r["domain"], r["target_tets"], r["metric"].upper(), r["derivatives"],
                     o["invalid_before"], o["invalid_after"], o["quality_after"]["mean"],
                     o["iterations"][-1]["objective"], len(o["iterations"]) - 1,
                     times[0] if times else None, o["seconds"],
                     o["vertex_updates_per_second"]])
    hdr = ["domain", "target tets", "metric", "derivatives", "invalid before", "invalid after",
           "mean quality after", "final objective", "iterations", "s to 0 invalid",
           "optimise s", "vertex updates/s"]
    return md_table(hdr, rows)


def table_tetopt(recs):
    """The same domains with and without the extra Gmsh optimisation of the tets."""
    rows = []
    keys = sorted({(r["target_tets"], r["domain"]) for r in recs if r.get("kind") == "convert"},
                  key=lambda k: (k[0], dom_key(k[1])))
    for n, d in keys:
        t = one(recs, kind="tetopt", domain=d, target_tets=n)
        for inp, nv, ov in (("raw", "none", ["local_q1_fd", "global_q1"]),
                            ("tetopt", "tetopt_none", ["tetopt_local_q1_fd", "tetopt_global_q1"])):
            r = one(recs, kind="convert", domain=d, target_tets=n, variant=nv)
            if r is None:
                continue
            if not r.get("ok"):
                err = (r.get("error") or (t or {}).get("error") or "failed").splitlines()[-1]
                err = re.sub(r"\S*/", "", err.split("error:")[-1]).strip()
                rows.append([d, n, inp, None, None, None, None, None,
                             "convert failed: " + err.replace("|", "/")[:90]])
                continue
            s = r["summary"]
            after = [None, None]
            for i, v in enumerate(ov):
                o = one(recs, kind="convert", domain=d, target_tets=n, variant=v)
                if o and o.get("ok"):
                    after[i] = o["summary"]["invalid_after"]
            rows.append([d, n, inp, s["tets"], s["cells"], s["dual"]["well_centred_tets"],
                         s["invalid_before"], after[0] if after[0] is not None else "–",
                         f"global Q1: {fmt(after[1])}"])
    hdr = ["domain", "target tets", "input", "tets", "dual cells", "well-centred tets",
           "invalid initial", "invalid after local Q1", "notes"]
    return md_table(hdr, rows)


def table_peer(recs):
    """OpenFOAM polyDualMesh vs polydual on the same Gmsh mesh, same checkMesh."""
    rows = []
    peers = [r for r in recs if r.get("kind") == "peer"]
    peers.sort(key=lambda r: (r["target_tets"], dom_key(r["domain"]),
                              r["tool"] != "polyDualMesh", r.get("variant", "")))
    for r in peers:
        tool = r["tool"] if r["tool"] == "polyDualMesh" else f"polydual ({r['variant']})"
        if not r.get("ok"):
            rows.append([r["domain"], r["target_tets"], tool, "failed"] + [None] * 8)
            continue
        stars = r.get("star_lines") or []
        inv = r.get("invalid_after") if r["tool"] == "polydual" else None
        rows.append([r["domain"], r["target_tets"], tool, r.get("cells"), r.get("faces"),
                     r.get("cell_zones"), r.get("face_zones"), r["wall_seconds"],
                     (r.get("peak_rss_kb") or 0) / 1024.0, r.get("failed_checks"), len(stars),
                     "; ".join(short_star(l) for l in stars) or "Mesh OK",
                     inv])
    hdr = ["domain", "target tets", "tool", "cells", "faces", "cellZones", "faceZones",
           "wall s", "peak RSS MB", "checkMesh failed checks", "*** lines",
           "failures", "polydual invalid (star test)"]
    return md_table(hdr, rows)


def short_star(line):
    """'***Concave cells (using face planes) found, number of cells: 199' ->
    'Concave cells 199'."""
    line = re.sub(r"\s+", " ", line.replace("***", "")).strip()
    label = re.split(r"[:(,]| found| \d", line, maxsplit=1)[0]
    label = re.sub(r"^Error in |^Number of ", "", label).strip(" .")
    nums = re.findall(r"\b\d+\b", line)
    count = nums[-1] if "number of" in line.lower() or "Number of" in line else (
        nums[0] if nums else "")
    return f"{label} {count}".strip().replace("|", "/")


TABLES = {"meshes": table_meshes, "optimisers": table_optimisers, "timing": table_timing,
          "derivatives": table_derivatives, "tetopt": table_tetopt, "peer": table_peer}


# ---------------------------------------------------------------------------- figures
def vtk_modules():
    import vtk  # noqa: F401  (Debian python3-vtk9)
    return vtk


def read_vtu(path):
    vtk = vtk_modules()
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def read_tets(msh):
    """The tets of a Gmsh file as a vtkUnstructuredGrid with cell data 'region'."""
    import meshio
    import numpy as np
    vtk = vtk_modules()
    from vtk.util import numpy_support
    m = meshio.read(msh)
    tets, regions = [], []
    for i, block in enumerate(m.cells):
        if block.type != "tetra":
            continue
        tets.append(block.data)
        ent = m.cell_data.get("gmsh:geometrical", [None] * len(m.cells))[i]
        regions.append(ent if ent is not None else np.full(len(block.data), i))
    tets = np.vstack(tets).astype(np.int64)
    regions = np.concatenate(regions).astype(np.int32)
    g = vtk.vtkUnstructuredGrid()
    pts = vtk.vtkPoints()
    pts.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(m.points, dtype=float), deep=1))
    g.SetPoints(pts)
    conn = np.hstack([np.full((len(tets), 1), 4, dtype=np.int64), tets]).ravel()
    ca = vtk.vtkCellArray()
    ca.SetCells(len(tets), numpy_support.numpy_to_vtkIdTypeArray(conn, deep=1))
    g.SetCells(vtk.VTK_TETRA, ca)
    arr = numpy_support.numpy_to_vtk(regions, deep=1)
    arr.SetName("region")
    g.GetCellData().AddArray(arr)
    # Triangles of internal model faces (interfaces, fractures): not on the
    # boundary of the tet mesh, so the surface view would hide them.
    from collections import Counter
    faces = Counter()
    for t in tets:
        for f in ((t[0], t[1], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[3]), (t[1], t[2], t[3])):
            faces[tuple(sorted(f))] += 1
    inner = [b.data for b in m.cells if b.type == "triangle"]
    inner = [tri for blk in inner for tri in blk if faces.get(tuple(sorted(tri)), 0) == 2]
    tg = None
    if inner:
        tri = np.array(inner, dtype=np.int64)
        tg = vtk.vtkUnstructuredGrid()
        tg.SetPoints(pts)
        conn = np.hstack([np.full((len(tri), 1), 3, dtype=np.int64), tri]).ravel()
        ca2 = vtk.vtkCellArray()
        ca2.SetCells(len(tri), numpy_support.numpy_to_vtkIdTypeArray(conn, deep=1))
        tg.SetCells(vtk.VTK_TRIANGLE, ca2)
    return g, tg


def cut(grid, axis=1, value=0.5):
    """Whole cells whose centre lies below value on axis (the paper's cut views)."""
    vtk = vtk_modules()
    from vtk.util import numpy_support
    cc = vtk.vtkCellCenters()
    cc.SetInputData(grid)
    cc.Update()
    c = numpy_support.vtk_to_numpy(cc.GetOutput().GetPoints().GetData())
    ids = vtk.vtkIdList()
    for i in (c[:, axis] < value).nonzero()[0]:
        ids.InsertNextId(int(i))
    ex = vtk.vtkExtractCells()
    ex.SetInputData(grid)
    ex.SetCellList(ids)
    ex.Update()
    return ex.GetOutput()


def count_invalid(grid):
    from vtk.util import numpy_support
    a = grid.GetCellData().GetArray("valid")
    if a is None:
        return None, grid.GetNumberOfCells()
    v = numpy_support.vtk_to_numpy(a)
    return int((v == 0).sum()), len(v)


def render(grid, png, color_by, title, bounds, invalid_overlay=True, size=(900, 760),
           inner=None, highlight=None):
    """Surface with edges. color_by: 'valid' (green/red) or 'region' (materials).
    highlight: a cell array name; its nonzero cells are drawn opaque (orange)
    over the faded mesh, so cells inside the cut are seen too."""
    vtk = vtk_modules()
    ren = vtk.vtkRenderer()
    ren.SetBackground(1, 1, 1)
    geo = vtk.vtkGeometryFilter()
    geo.SetInputData(grid)
    geo.Update()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(geo.GetOutputPort())
    lut = vtk.vtkLookupTable()
    if color_by == "valid":
        lut.SetNumberOfTableValues(2)
        lut.SetTableValue(0, 0.90, 0.10, 0.10, 1)   # invalid: red
        lut.SetTableValue(1, 0.45, 0.80, 0.45, 1)   # valid: green
        lut.Build()
        mapper.SetScalarRange(0, 1)
    else:
        colors = [(0.55, 0.70, 0.90), (0.95, 0.75, 0.45), (0.70, 0.85, 0.60), (0.85, 0.6, 0.8)]
        lut.SetNumberOfTableValues(len(colors))
        for i, c in enumerate(colors):
            lut.SetTableValue(i, *c, 1)
        lut.Build()
        arr = grid.GetCellData().GetArray(color_by)
        lo, hi = arr.GetRange() if arr else (0, 1)
        mapper.SetScalarRange(lo, max(hi, lo + 1))
        lut.SetNumberOfTableValues(max(1, int(hi - lo) + 1))
        for i in range(int(hi - lo) + 1):
            lut.SetTableValue(i, *colors[i % len(colors)], 1)
    mapper.SetLookupTable(lut)
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray(color_by)
    mapper.ScalarVisibilityOn()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    p = actor.GetProperty()
    p.EdgeVisibilityOn()
    p.SetEdgeColor(0.15, 0.15, 0.15)
    p.SetLineWidth(0.8)
    p.SetAmbient(0.35)
    p.SetDiffuse(0.7)
    ren.AddActor(actor)
    if inner is not None:
        # Internal model faces drawn opaque through a faded tet surface.
        gi = vtk.vtkGeometryFilter()
        gi.SetInputData(inner)
        mi = vtk.vtkPolyDataMapper()
        mi.SetInputConnection(gi.GetOutputPort())
        mi.ScalarVisibilityOff()
        ai = vtk.vtkActor()
        ai.SetMapper(mi)
        ai.GetProperty().SetColor(0.95, 0.55, 0.15)
        ai.GetProperty().EdgeVisibilityOn()
        ai.GetProperty().SetEdgeColor(0.3, 0.15, 0)
        ren.AddActor(ai)
        p.SetOpacity(0.25)
    overlay = None
    if color_by == "valid" and invalid_overlay:
        overlay = ("valid", lambda v: v == 0, (0.9, 0.1, 0.1), (0.3, 0, 0))
    if highlight is not None:
        overlay = (highlight, lambda v: v != 0, (0.95, 0.55, 0.15), (0.3, 0.15, 0))
    if overlay is not None:
        # Invalid (or highlighted) cells hidden inside the cut are drawn again as
        # an opaque overlay on top of a faded mesh, so none is missed.
        from vtk.util import numpy_support
        name, pick, colour, edge = overlay
        a = grid.GetCellData().GetArray(name)
        if a is not None:
            bad = pick(numpy_support.vtk_to_numpy(a)).nonzero()[0]
            if len(bad):
                ids = vtk.vtkIdList()
                for i in bad:
                    ids.InsertNextId(int(i))
                ex = vtk.vtkExtractCells()
                ex.SetInputData(grid)
                ex.SetCellList(ids)
                ex.Update()
                g2 = vtk.vtkGeometryFilter()
                g2.SetInputData(ex.GetOutput())
                m2 = vtk.vtkPolyDataMapper()
                m2.SetInputConnection(g2.GetOutputPort())
                m2.ScalarVisibilityOff()
                a2 = vtk.vtkActor()
                a2.SetMapper(m2)
                a2.GetProperty().SetColor(*colour)
                a2.GetProperty().EdgeVisibilityOn()
                a2.GetProperty().SetEdgeColor(*edge)
                ren.AddActor(a2)
                p.SetOpacity(0.35)
    txt = vtk.vtkTextActor()
    txt.SetInput(title)
    txt.GetTextProperty().SetFontSize(20)
    txt.GetTextProperty().SetColor(0, 0, 0)
    txt.SetDisplayPosition(12, size[1] - 34)
    ren.AddActor2D(txt)
    # Camera: oblique view from +x, -y... looking at the cut plane y = const from
    # the +y side and slightly above, z up.
    (x0, x1, y0, y1, z0, z1) = bounds
    cx, cy, cz = (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2
    diag = ((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) ** 0.5
    cam = ren.GetActiveCamera()
    cam.SetFocalPoint(cx, cy, cz)
    cam.SetPosition(cx + 0.9 * diag, cy + 1.9 * diag, cz + 1.1 * diag)
    cam.SetViewUp(0, 0, 1)
    ren.ResetCamera(x0, x1, y0, y1, z0, z1)
    cam.Zoom(1.02)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.AddRenderer(ren)
    win.SetSize(*size)
    win.Render()
    w2i = vtk.vtkWindowToImageFilter()
    w2i.SetInput(win)
    w2i.Update()
    wr = vtk.vtkPNGWriter()
    wr.SetFileName(png)
    wr.SetInputConnection(w2i.GetOutputPort())
    wr.Write()
    win.Finalize()


def compose(pngs, titles, out_png, suptitle):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.image as mpimg
    fig, axes = plt.subplots(1, len(pngs), figsize=(4.2 * len(pngs), 4.0), dpi=130, squeeze=False)
    axes = axes[0]
    for ax, p, t in zip(axes, pngs, titles):
        ax.imshow(mpimg.imread(p))
        ax.set_title(t, fontsize=10)
        ax.axis("off")
    fig.suptitle(suptitle, fontsize=12)
    fig.tight_layout()
    fig.savefig(out_png, metadata={"Software": None})
    plt.close(fig)


def figures(out, recs, size=None):
    """Per domain, for the smallest size: (a) tets, (b) initial cut, (c) optimised
    cut, (d) full optimised mesh; plus the same for the tet-optimised input."""
    figdir = os.path.join(out, "figures")
    os.makedirs(figdir, exist_ok=True)
    made = []
    sizes = sorted({r["target_tets"] for r in recs if r.get("kind") == "convert"})
    if not sizes:
        return made
    n = size or sizes[0]
    for d in DOMAINS:
        # Panel (b): the dual as Algorithm 1 builds it ("dual": --no-split);
        # older runs without that record fall back to "none" (split).
        none = next((r for v in ("dual", "none")
                     for r in [one(recs, kind="convert", domain=d, target_tets=n, variant=v)]
                     if r and r.get("ok")), None)
        if not none:
            continue
        opt = next((r for v in FIGURE_VARIANTS
                    for r in [one(recs, kind="convert", domain=d, target_tets=n, variant=v)]
                    if r and r.get("ok")), None)
        msh = os.path.join(out, "work", f"{d}_{n}", f"{d}.msh")
        tets, inner = read_tets(msh)
        init = read_vtu(os.path.join(out, none["vtu"]))
        bounds = init.GetBounds()
        ycut = (bounds[2] + bounds[3]) / 2
        panels, titles = [], []
        p = os.path.join(figdir, f"{d}_a_tets.png")
        render(tets, p, "region", f"(a) {d}: {tets.GetNumberOfCells()} tets"
               + (", internal model faces in orange" if inner else ""), bounds, inner=inner)
        panels.append(p); titles.append("(a) input tet mesh")
        ic = cut(init, 1, ycut)
        bad, tot = count_invalid(init)
        p = os.path.join(figdir, f"{d}_b_initial_cut.png")
        render(ic, p, "valid", f"(b) initial dual, cut y < {ycut:g} (whole mesh: {bad} of {tot} invalid)", bounds)
        panels.append(p); titles.append("(b) initial dual (cut)")
        if opt:
            og = read_vtu(os.path.join(out, opt["vtu"]))
            bad2, tot2 = count_invalid(og)
            label = opt["variant"].replace("_", " ")
            p = os.path.join(figdir, f"{d}_c_optimised_cut.png")
            render(cut(og, 1, ycut), p, "valid",
                   f"(c) {label}, cut y < {ycut:g} (whole mesh: {bad2} of {tot2} invalid)", bounds)
            panels.append(p); titles.append(f"(c) after {label} (cut)")
            p = os.path.join(figdir, f"{d}_d_optimised.png")
            render(og, p, "valid", f"(d) {label}: {tot2} cells, {bad2} invalid", bounds)
            panels.append(p); titles.append("(d) full optimised mesh")
        f = os.path.join(figdir, f"fig_{d}.png")
        compose(panels, titles, f,
                f"{d} ({PAPER_FIG[d]}), {tets.GetNumberOfCells()} tets, "
                f"{tot} dual cells; green = star-shaped, red = invalid (exact test)")
        made += panels + [f]
        print(f"figure {f}", flush=True)
    return made


# ------------------------------------------------------------------------------ paper
def fill_markers(readme, tables_dir):
    with open(readme) as f:
        text = f.read()
    def repl(m):
        name = m.group(1)
        path = os.path.join(tables_dir, name + ".md")
        if not os.path.exists(path):
            return m.group(0)
        with open(path) as f:
            body = f.read()
        return f"<!-- BEGIN table:{name} -->\n{body}<!-- END table:{name} -->"
    new = re.sub(r"<!-- BEGIN table:(\w+) -->.*?<!-- END table:\1 -->", repl, text, flags=re.S)
    if new != text:
        with open(readme, "w") as f:
            f.write(new)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "build", "results"),
                    help="the results directory run.py wrote (default build/results)")
    ap.add_argument("--paper", help="copy figures and tables here and fill README markers")
    ap.add_argument("--no-figures", action="store_true")
    ap.add_argument("--figure-size", type=int, help="target tets of the figures "
                    "(default: the smallest size run)")
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    recs = load_records(out)
    tdir = os.path.join(out, "tables")
    os.makedirs(tdir, exist_ok=True)
    for name, fn in TABLES.items():
        with open(os.path.join(tdir, name + ".md"), "w") as f:
            f.write(f"<!-- generated by experiments/render.py from {len(recs)} records -->\n")
            f.write(fn(recs))
    figs = [] if a.no_figures else figures(out, recs, a.figure_size)
    if a.paper:
        for sub, files in (("tables", glob.glob(os.path.join(tdir, "*.md"))), ("figures", figs)):
            dst = os.path.join(a.paper, sub)
            os.makedirs(dst, exist_ok=True)
            for f in files:
                shutil.copy2(f, dst)
        readme = os.path.join(a.paper, "README.md")
        if os.path.exists(readme):
            fill_markers(readme, tdir)
    print(f"rendered {len(TABLES)} tables and {len(figs)} figures into {out}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
