"""The corpus of real meshes: one list, made at test time from Debian's tools.

Every mesh is written by a program that users bring, from models written here
(tests/corpus/models/*.geo, netgen_models.py) and never by polydual itself:
  gmsh_*      Gmsh OpenCASCADE booleans at Gmsh's default size (no size
              option: what a new user gets) and at half of it (-clscale 0.5);
  tetgen_*    TetGen on Gmsh's STL of CAD-like surfaces with sharp edges, with
              its quality bound (_q: -pq1.4) and without it (_n: -pY, slivers;
              on the thick torus and cone-on-a-box, no interior vertex);
  cgal_image_*    CGAL Mesh_3 on a three-material labelled image
                  (experiments/meshgen/labelled_image_medit);
  cgal_features_* CGAL Mesh_3 on Gmsh's STL of a model, sharp features detected
                  and protected (experiments/meshgen/polyhedral_features_medit);
  netgen_*    Netgen (python3-netgen) CSG models exported as "Gmsh2 Format".
The runner (run_corpus.py) and the benchmark (bench/corpus_bench.py) both take
the list from here. A mesh whose tool is missing raises Skip with the reason.
Meshes are cached in the work directory and remade when their recipe (the
commands and the model file's contents) changes.
"""
import hashlib
import json
import os
import shutil
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = os.path.join(HERE, "models")
PYTHON = "/usr/bin/python3"  # Debian's, where python3-netgen lives


class Skip(Exception):
    """The mesh cannot be made here (a tool is missing); the message says which."""


class MakeError(Exception):
    """A tool ran and failed: the message names the command and its last output."""


def _gmsh(model, scale):
    return {"tool": "gmsh", "model": model, "scale": scale}


def _tetgen(model, flags):
    return {"tool": "tetgen", "model": model, "flags": flags}


# (name, recipe), meshes of 1k-40k tets.
MESHES = [
    *[(f"gmsh_{m}", _gmsh(m, None)) for m in ("inclusions", "holes", "fillets", "sheet", "multimat")],
    *[(f"gmsh_{m}_fine", _gmsh(m, 0.5)) for m in ("inclusions", "holes", "fillets", "sheet", "multimat")],
    ("tetgen_star_q", _tetgen("star", "-pq1.4")),
    ("tetgen_star_n", _tetgen("star", "-pY")),
    ("tetgen_fillets_q", _tetgen("fillets", "-pq1.4")),
    ("tetgen_fillets_n", _tetgen("fillets", "-pY")),
    ("tetgen_torus_n", _tetgen("torus", "-pY")),
    ("tetgen_conebox_n", _tetgen("conebox", "-pY")),
    ("cgal_image_balls", {"tool": "labelled_image_medit", "args": ["shape=balls"]}),
    ("cgal_image_blocks", {"tool": "labelled_image_medit", "args": ["shape=blocks"]}),
    ("cgal_features_holes", {"tool": "polyhedral_features_medit", "model": "holes", "args": []}),
    ("cgal_features_star", {"tool": "polyhedral_features_medit", "model": "star",
                            "args": ["edge_size=0.06", "facet_size=0.1", "cell_size=0.1"]}),
    ("netgen_ballblock", {"tool": "netgen", "model": "ballblock", "maxh": 0.08}),
    ("netgen_bracket", {"tool": "netgen", "model": "bracket", "maxh": 0.08}),
]

# Gmsh's surface size for the STL that TetGen and CGAL mesh (a fraction of
# Gmsh's default size: the default surfaces are too coarse for a volume mesh).
STL_SCALE = 0.3


def names():
    return [n for n, _ in MESHES]


def producer_versions():
    """Debian versions of the producers' packages ("missing" when not installed)."""
    out = {}
    for pkg in ("gmsh", "tetgen", "libcgal-dev", "python3-netgen"):
        res = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", pkg], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, text=True)
        out[pkg] = res.stdout.strip() if res.returncode == 0 and res.stdout.strip() else "missing"
    return out


def _run(cmd, cwd, log):
    with open(log, "w") as f:
        res = subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT)
    if res.returncode != 0:
        tail = open(log).read().strip().splitlines()[-5:]
        raise MakeError(f"{' '.join(cmd)} exited {res.returncode}:\n  " + "\n  ".join(tail))


def _need(tool, package):
    path = shutil.which(tool)
    if not path:
        raise Skip(f"the {tool} command is not installed (Debian package {package})")
    return path


def _stl(model, work):
    """Gmsh's STL of a model's surface at STL_SCALE of its default size."""
    gmsh = _need("gmsh", "gmsh")
    path = os.path.join(work, f"{model}.stl")
    _run([gmsh, "-2", os.path.join(MODELS, model + ".geo"), "-clscale", str(STL_SCALE), "-format", "stl",
          "-o", path], work, path + ".log")
    return path


def _make_gmsh(name, r, work, tools):
    gmsh = _need("gmsh", "gmsh")
    out = os.path.join(work, name + ".msh")
    scale = ["-clscale", str(r["scale"])] if r["scale"] else []
    _run([gmsh, "-3", os.path.join(MODELS, r["model"] + ".geo"), *scale, "-format", "msh4", "-o", out],
         work, out + ".log")
    return out


def _make_tetgen(name, r, work, tools):
    tetgen = _need("tetgen", "tetgen")
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    stl = _stl(r["model"], work)
    shutil.copy(stl, os.path.join(d, r["model"] + ".stl"))
    _run([tetgen, "-Q", r["flags"], r["model"] + ".stl"], d, os.path.join(d, "tetgen.log"))
    return os.path.join(d, r["model"] + ".1.ele")


def _make_cgal(name, r, work, tools):
    gen = tools.get(r["tool"])
    if not gen or not os.path.exists(gen):
        raise Skip(f"{r['tool']} was not built (CGAL's Mesh_3 not found, or not passed as --{r['tool']})")
    gen = os.path.abspath(gen)  # it runs in WORK
    out = os.path.join(work, name + ".mesh")
    surface = [_stl(r["model"], work)] if "model" in r else []
    _run([gen, *surface, out, *r["args"]], work, out + ".log")
    return out


def _make_netgen(name, r, work, tools):
    probe = subprocess.run([PYTHON, "-c", "import netgen.csg"], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
    if probe.returncode != 0:
        raise Skip("Netgen's Python module is not installed (Debian package python3-netgen)")
    out = os.path.join(work, name + ".msh")
    _run([PYTHON, os.path.join(HERE, "netgen_models.py"), r["model"], out, str(r["maxh"])], work, out + ".log")
    return out


MAKERS = {"gmsh": _make_gmsh, "tetgen": _make_tetgen, "labelled_image_medit": _make_cgal,
          "polyhedral_features_medit": _make_cgal, "netgen": _make_netgen}


def _stamp(recipe, tools):
    """What the mesh depends on: its recipe, its model file, the generator."""
    h = hashlib.sha256(json.dumps(recipe, sort_keys=True).encode())
    for f in [os.path.join(MODELS, recipe.get("model", "") + ".geo"), os.path.join(HERE, "netgen_models.py"),
              tools.get(recipe["tool"], "")]:
        if f and os.path.isfile(f):
            h.update(open(f, "rb").read() if f.endswith((".geo", ".py")) else str(os.path.getmtime(f)).encode())
    h.update(str(STL_SCALE).encode())
    return h.hexdigest()


def make(name, work, tools):
    """Path of mesh NAME in WORK, made (or reused when its recipe is unchanged).
    TOOLS maps generator names to built binaries. Raises Skip or MakeError."""
    recipe = dict(MESHES)[name]
    os.makedirs(work, exist_ok=True)
    stamp_file = os.path.join(work, name + ".recipe")
    stamp = _stamp(recipe, tools)
    cached = os.path.join(work, name + ".path")
    if os.path.exists(stamp_file) and open(stamp_file).read() == stamp and os.path.exists(cached):
        path = open(cached).read()
        if os.path.exists(path):
            return path
    path = MAKERS[recipe["tool"]](name, recipe, work, tools)
    open(cached, "w").write(path)
    open(stamp_file, "w").write(stamp)
    return path
