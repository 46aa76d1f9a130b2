#!/usr/bin/python3
"""Regenerates every figure and table of the paper reproduction from nothing.

    /usr/bin/python3 experiments/run.py [--polydual build/polydual] [--out results]
                                        [--smoke] [--sizes 10000,100000]

STEP 1 generate the four paper domains with `polydual generate` at each size;
STEP 2 (none: the "tetopt" input is made inside STEP 3's convert, below);
STEP 3 convert every (input, optimiser, metric, derivatives) variant with
       `polydual convert --json` and record the JSON summary;
STEP 4 run OpenFOAM's polyDualMesh on the same Gmsh mesh and checkMesh on its
       output and on polydual's own OpenFOAM output;
STEP 5 render figures and tables from the records only (experiments/render.py,
       under xvfb-run).

Every step writes one record OUT/records/<name>.json. A step whose record
already exists for the same command is skipped (use --force to redo), so an
interrupted run resumes. The meshes, VTUs and counts are deterministic; only
the timings vary between runs.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
PY = "/usr/bin/python3"  # Debian's python: VTK, matplotlib, numpy, meshio
DOMAINS = ["cube", "twomat", "fichera", "fracture", "network", "fins"]
OPENFOAM_ENV = {"WM_PROJECT_DIR": "/usr/share/openfoam"}

# Converter variants: name -> (input, optimize, metric, derivatives, scope).
# "raw" is the mesh from `polydual generate` (already passed through Gmsh's
# default optimiser with its default threshold, see tet_optimize.py);
# "tetopt" is that mesh through polydual's own tet pre-optimisation
# (`convert --optimize-tets`: the paper's condition-number moves, then the
# Delaunay flips that give back what the moves broke; paper/tetopt_tables.md:
# fewer invalid dual cells than the raw mesh, the paper's claim, where Gmsh's
# stronger pass and the moves alone gave more).
# scope: "all" sizes; "local" only up to --local-max-tets (the local Newton
# scheme is the slow one); "compare" only up to --compare-max-tets; "figure"
# only at the smallest size (the one the figures show).
VARIANTS = {
    "none":            ("raw", "none", "q1", "fd", "all"),
    "local_q1_fd":     ("raw", "local", "q1", "fd", "local"),    # the paper's scheme
    "local_q1_exact":  ("raw", "local", "q1", "exact", "compare"),
    "local_q2_fd":     ("raw", "local", "q2", "fd", "compare"),
    "global_q1":       ("raw", "global", "q1", "exact", "all"),
    "global_q2":       ("raw", "global", "q2", "exact", "compare"),
    "tetopt_none":     ("tetopt", "none", "q1", "fd", "all"),
    "tetopt_local_q1_fd": ("tetopt", "local", "q1", "fd", "compare"),
    "tetopt_global_q1": ("tetopt", "global", "q1", "exact", "compare"),
    # The figures' panel (b): the dual exactly as Algorithm 1 builds it (no
    # split, which "none" runs by default and which makes every cell valid).
    "dual":            ("raw", "none", "q1", "fd", "figure"),
}
# Flags a variant adds to its convert command.
EXTRA_FLAGS = {"dual": ["--no-split"]}
# The local variants reproduce the paper's scheme: its damped Newton (no
# over-relaxation, no polish) and its tolerance, not polydual's faster default.
PAPER_LOCAL = ["--relaxation", "1", "--polish-sweeps", "0", "--tol", "1e-3"]
SMOKE_VARIANTS = ["none", "global_q1", "local_q1_fd", "tetopt_none", "tetopt_global_q1", "dual"]


class Progress:
    """One line per step with the elapsed wall time since the run started."""

    def __init__(self, total):
        self.t0 = time.monotonic()
        self.total = total
        self.done = 0

    def step(self, what, fn):
        self.done += 1
        start = time.monotonic()
        prefix = f"[{start - self.t0:7.1f}s] {self.done:3d}/{self.total} {what}"
        print(prefix + " ...", flush=True)
        status = fn()
        print(f"[{time.monotonic() - self.t0:7.1f}s] {self.done:3d}/{self.total} {what}: "
              f"{status} ({time.monotonic() - start:.1f}s)", flush=True)


def write_json(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(obj, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def run(cmd, cwd=None, env=None, stdout_path=None):
    """Runs cmd; returns (exit code, stdout text, stderr text, wall seconds)."""
    full_env = dict(os.environ, **(env or {}))
    t = time.monotonic()
    p = subprocess.run(cmd, cwd=cwd, env=full_env, capture_output=True, text=True)
    wall = time.monotonic() - t
    if stdout_path:
        with open(stdout_path, "w") as f:
            f.write(p.stdout)
            f.write(p.stderr)
    return p.returncode, p.stdout, p.stderr, wall


class Harness:
    def __init__(self, args):
        self.a = args
        self.out = os.path.abspath(args.out)
        self.records = os.path.join(self.out, "records")
        self.work = os.path.join(self.out, "work")
        os.makedirs(self.records, exist_ok=True)
        os.makedirs(self.work, exist_ok=True)
        self.polydual = os.path.abspath(args.polydual)

    # -- caching ---------------------------------------------------------------
    def cached(self, name, cmd):
        """The record `name` if it exists for exactly this command."""
        if self.a.force:
            return None
        rec = read_json(os.path.join(self.records, name + ".json"))
        if rec is not None and rec.get("command") == cmd and rec.get("ok", False):
            return rec
        return None

    def save(self, name, rec):
        write_json(os.path.join(self.records, name + ".json"), rec)
        return rec

    def wdir(self, domain, n):
        d = os.path.join(self.work, f"{domain}_{n}")
        os.makedirs(d, exist_ok=True)
        return d

    # -- STEP 1 ----------------------------------------------------------------
    def generate(self, domain, n):
        name = f"{domain}_{n}_generate"
        msh = os.path.join(self.wdir(domain, n), f"{domain}.msh")
        cmd = [self.polydual, "generate", domain, "--tets", str(n), "-o", msh]
        if self.cached(name, cmd) and os.path.exists(msh):
            return "cached"
        rc, out, err, wall = run(cmd)
        self.save(name, {"kind": "generate", "domain": domain, "target_tets": n,
                         "command": cmd, "ok": rc == 0, "wall_seconds": wall,
                         "error": err.strip() if rc else None})
        return "ok" if rc == 0 else "FAILED: " + err.strip()[-200:]

    # -- STEP 3 ----------------------------------------------------------------
    def convert(self, domain, n, variant):
        inp, opt, metric, deriv, _ = VARIANTS[variant]
        name = f"{domain}_{n}_{variant}"
        d = self.wdir(domain, n)
        src = os.path.join(d, f"{domain}.msh")
        vtu = os.path.join(d, f"{variant}.vtu")
        # The paper's capping faces (design §4.10), whatever the command's default.
        cmd = [self.polydual, "convert", src, "-o", vtu, "--json", "--boundary", "caps", "--optimize", opt,
               "--metric", metric, "--derivatives", deriv] + (PAPER_LOCAL if opt == "local" else [])
        cmd += EXTRA_FLAGS.get(variant, [])
        cmd += ["--optimize-tets"] if inp == "tetopt" else ["--no-optimize-tets"]
        if self.a.max_iter:
            cmd += ["--max-iter", str(self.a.max_iter)]
        if self.cached(name, cmd) and os.path.exists(vtu):
            return "cached"
        rec = {"kind": "convert", "domain": domain, "target_tets": n, "variant": variant,
               "input": inp, "optimize": opt, "metric": metric, "derivatives": deriv,
               "command": cmd, "vtu": os.path.relpath(vtu, self.out)}
        if not os.path.exists(src):
            rec.update(ok=False, error=f"input {os.path.basename(src)} missing")
            self.save(name, rec)
            return "skipped: input missing"
        rc, out, err, wall = run(cmd)
        rec["wall_seconds"] = wall
        summary = None
        if rc == 0:
            try:
                summary = json.loads(out)
            except ValueError:
                rc = -1
                err = "convert printed no JSON"
        rec.update(ok=rc == 0, summary=summary, error=err.strip()[-400:] if rc else None)
        self.save(name, rec)
        if rc:
            return "FAILED: " + rec["error"][-160:]
        s = summary
        return f"{s['cells']} cells, invalid {s['invalid_before']} -> {s['invalid_after']}"

    # -- STEP 4 ----------------------------------------------------------------
    def foam_polydual(self, domain, n, variant):
        """polydual's own OpenFOAM output, through the same checkMesh."""
        inp, opt, metric, deriv, _ = VARIANTS[variant]
        name = f"{domain}_{n}_peer_polydual_{variant}"
        d = self.wdir(domain, n)
        src = os.path.join(d, f"{domain}.msh")
        case = os.path.join(d, f"foam_polydual_{variant}")
        cmd = ["/usr/bin/time", "-v", self.polydual, "convert", src, "-o", case,
               "--format", "foam", "--json", "--optimize", opt, "--metric", metric,
               "--derivatives", deriv] + (PAPER_LOCAL if opt == "local" else [])
        if self.a.max_iter:
            cmd += ["--max-iter", str(self.a.max_iter)]
        if self.cached(name, cmd):
            return "cached"
        shutil.rmtree(case, ignore_errors=True)
        rc, out, err, wall = run(cmd)
        rec = {"kind": "peer", "tool": "polydual", "variant": variant, "domain": domain,
               "target_tets": n, "command": cmd, "ok": rc == 0, "wall_seconds": wall,
               "peak_rss_kb": peak_rss_kb(err)}
        if rc == 0:
            s = json.loads(out)
            rec["polydual_cells"] = s["cells"]
            rec["invalid_after"] = s["invalid_after"]
            rec.update(check_mesh(case, os.path.join(d, f"checkMesh_polydual_{variant}.log")))
        else:
            rec["error"] = err.strip()[-400:]
        self.save(name, rec)
        return summary_line(rec)

    def foam_peer(self, domain, n):
        """OpenFOAM polyDualMesh on the same Gmsh mesh (gmshToFoam first)."""
        name = f"{domain}_{n}_peer_polyDualMesh"
        d = self.wdir(domain, n)
        src = os.path.join(d, f"{domain}.msh")
        case = os.path.join(d, "foam_polyDualMesh")
        cmd = ["polyDualMesh", str(self.a.feature_angle), "-overwrite"]
        if self.cached(name, cmd + [src]):
            return "cached"
        shutil.rmtree(case, ignore_errors=True)
        os.makedirs(case)
        rec = {"kind": "peer", "tool": "polyDualMesh", "domain": domain, "target_tets": n,
               "command": cmd + [src], "feature_angle": self.a.feature_angle}
        # gmshToFoam reads msh 2.2 and takes patches/zones from physical tags;
        # our meshes carry no physical groups, so make physical := elementary.
        msh22 = os.path.join(d, f"{domain}_22.msh")
        rc, _, err, _ = run(["gmsh", src, "-save", "-format", "msh22", "-o", msh22])
        if rc == 0:
            physical_from_elementary(msh22)
        shutil.copytree(os.path.join(REPO, "experiments", "foam_system"),
                        os.path.join(case, "system"))
        rc2, _, err2, wall_g = run(["gmshToFoam", msh22], cwd=case, env=OPENFOAM_ENV,
                                   stdout_path=os.path.join(d, "gmshToFoam.log"))
        if rc or rc2:
            rec.update(ok=False, error=(err + err2).strip()[-400:])
            self.save(name, rec)
            return "FAILED: gmsh/gmshToFoam"
        rec["gmshToFoam_seconds"] = wall_g
        rec["tet_mesh"] = check_mesh(case, os.path.join(d, "checkMesh_tets.log"),
                                     quick=True)
        rc, out, err, wall = run(["/usr/bin/time", "-v"] + cmd, cwd=case, env=OPENFOAM_ENV,
                                 stdout_path=os.path.join(d, "polyDualMesh.log"))
        rec.update(ok=rc == 0 and "FOAM FATAL" not in out + err, wall_seconds=wall,
                   peak_rss_kb=peak_rss_kb(err))
        if rec["ok"]:
            rec.update(check_mesh(case, os.path.join(d, "checkMesh_polyDualMesh.log")))
        else:
            rec["error"] = (out + err).strip()[-400:]
        self.save(name, rec)
        return summary_line(rec)

    # -- STEP 5 ----------------------------------------------------------------
    def render(self):
        cmd = [PY, os.path.join(HERE, "render.py"), "--out", self.out]
        if self.a.paper:
            cmd += ["--paper", os.path.abspath(self.a.paper)]
        if shutil.which("xvfb-run"):
            cmd = ["xvfb-run", "-a", "-s", "-screen 0 1600x1200x24"] + cmd
        rc, out, err, wall = run(cmd)
        with open(os.path.join(self.out, "render.log"), "w") as f:
            f.write(out + err)
        if rc:
            raise SystemExit(f"render.py failed:\n{(out + err)[-2000:]}")
        return out.strip().splitlines()[-1] if out.strip() else "ok"


def in_scope(a, variant, n, peer=False):
    """Whether `variant` runs at size n (peer: as a polydual OpenFOAM case, where
    only the unoptimised dual runs at every size)."""
    scope = VARIANTS[variant][4]
    if scope == "local":
        return n <= a.local_max_tets
    if scope == "figure":
        return not peer and n == min(a.sizes)
    if scope == "compare" or (peer and variant != "none"):
        return n <= a.compare_max_tets
    return True


def sha256(path):
    import hashlib
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def peak_rss_kb(time_v_stderr):
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", time_v_stderr)
    return int(m.group(1)) if m else None


def physical_from_elementary(msh22):
    """In a msh 2.2 ASCII file, sets every element's physical tag to its
    elementary (model entity) tag, so gmshToFoam makes one patch per external
    model face, one cellZone per region and faceZones for internal faces."""
    with open(msh22) as f:
        lines = f.read().split("\n")
    start = lines.index("$Elements")
    count = int(lines[start + 1])
    for i in range(start + 2, start + 2 + count):
        p = lines[i].split()
        if len(p) > 4 and int(p[2]) >= 2:
            p[3] = p[4]
            lines[i] = " ".join(p)
    with open(msh22, "w") as f:
        f.write("\n".join(lines))


def check_mesh(case, log_path, quick=False):
    """Runs checkMesh; returns cells, faces, zones, *** lines and failed checks."""
    cmd = ["checkMesh", "-case", case]
    if not quick:
        cmd += ["-allGeometry", "-allTopology"]
    rc, out, err, wall = run(cmd, env=OPENFOAM_ENV, stdout_path=log_path)
    log = out + err
    def num(pattern):
        m = re.search(pattern, log, re.M)
        return int(m.group(1)) if m else None
    failed = num(r"Failed (\d+) mesh checks")
    stars = [l.strip() for l in log.splitlines() if "***" in l]
    return {"checkMesh_exit": rc, "checkMesh_seconds": wall,
            "cells": num(r"^\s+cells:\s+(\d+)"), "faces": num(r"^\s+faces:\s+(\d+)"),
            "points": num(r"^\s+points:\s+(\d+)"),
            "cell_zones": num(r"^\s+cell zones:\s+(\d+)"),
            "face_zones": num(r"^\s+face zones:\s+(\d+)"),
            "patches": len(re.findall(r"^\s+\S+\s+\d+\s+\d+\s+ok \(|^\s+\S+\s+\d+\s+\d+\s+\S",
                                      log.partition("Checking patch topology")[2]
                                         .partition("Checking")[0], re.M)) or None,
            "star_lines": stars, "failed_checks": failed if failed is not None else 0,
            "mesh_ok": "Mesh OK." in log, "fatal": "FOAM FATAL" in log}


def summary_line(rec):
    if not rec.get("ok"):
        return "FAILED: " + str(rec.get("error", ""))[-160:]
    return (f"{rec.get('cells')} cells, checkMesh failed {rec.get('failed_checks')} "
            f"({len(rec.get('star_lines', []))} *** lines), {rec['wall_seconds']:.2f}s, "
            f"{(rec.get('peak_rss_kb') or 0) / 1024:.0f} MB")


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--polydual", default=os.path.join(REPO, "build", "polydual"))
    ap.add_argument("--out", default=os.path.join(REPO, "build", "results"),
                    help="results directory (records, meshes, tables, figures; default build/results)")
    ap.add_argument("--smoke", action="store_true",
                    help="~2k tets, fast variants only, no paper/ update (for CI)")
    ap.add_argument("--sizes", help="comma-separated target tet counts "
                    "(default 10000,100000; smoke 2000)")
    ap.add_argument("--domains", default=",".join(DOMAINS))
    ap.add_argument("--variants", help="comma-separated subset of " + ",".join(VARIANTS))
    ap.add_argument("--local-max-tets", type=int, default=100000,
                    help="run the paper's local Newton variant only up to this size")
    ap.add_argument("--compare-max-tets", type=int, default=20000,
                    help="run the comparison variants (exact derivatives, Q2, global Q2, "
                    "optimisers on the tet-optimised input, polydual foam after "
                    "optimisation) only up to this size")
    ap.add_argument("--max-iter", type=int, default=0,
                    help="optimiser iteration cap passed to convert (0: polydual default)")
    ap.add_argument("--feature-angle", type=int, default=30,
                    help="polyDualMesh feature angle (degrees)")
    ap.add_argument("--no-peer", action="store_true", help="skip the OpenFOAM comparison")
    ap.add_argument("--peer-variants", default="none,global_q1",
                    help="polydual variants written as OpenFOAM cases for checkMesh")
    ap.add_argument("--no-render", action="store_true")
    ap.add_argument("--paper", help="also copy figures/tables into this paper/ folder "
                    "(default: REPO/paper unless --smoke)")
    ap.add_argument("--force", action="store_true", help="redo steps with a record")
    a = ap.parse_args(argv)
    if a.sizes is None:
        a.sizes = "2000" if a.smoke else "10000,100000"
    a.sizes = [int(s) for s in a.sizes.split(",")]
    a.domains = a.domains.split(",")
    a.peer_variants = [v for v in a.peer_variants.split(",") if v]
    for v in a.peer_variants:
        if VARIANTS.get(v, ("tetopt",))[0] != "raw":
            ap.error(f"--peer-variants: {v} is not a variant of the raw input")
    if a.variants:
        a.variants = a.variants.split(",")
    else:
        a.variants = SMOKE_VARIANTS if a.smoke else list(VARIANTS)
    if a.smoke and not a.max_iter:
        a.max_iter = 3
    if a.paper is None and not a.smoke:
        a.paper = os.path.join(REPO, "paper")
    for v in a.variants:
        if v not in VARIANTS:
            ap.error(f"unknown variant {v}")
    return a


def main(argv=None):
    a = parse_args(argv)
    if not os.access(a.polydual, os.X_OK):
        raise SystemExit(f"polydual binary {a.polydual} not found (build it, or --polydual)")
    h = Harness(a)
    write_json(os.path.join(h.out, "run.json"),
               {"sizes": a.sizes, "domains": a.domains, "variants": a.variants,
                "smoke": a.smoke, "max_iter": a.max_iter,
                "local_max_tets": a.local_max_tets, "feature_angle": a.feature_angle,
                "polydual": a.polydual, "polydual_sha256": sha256(a.polydual)})
    steps = []
    for n in a.sizes:
        for d in a.domains:
            steps.append((f"generate {d} {n}", lambda d=d, n=n: h.generate(d, n)))
            for v in a.variants:
                if not in_scope(a, v, n):
                    continue
                steps.append((f"convert {d} {n} {v}", lambda d=d, n=n, v=v: h.convert(d, n, v)))
            if not a.no_peer:
                steps.append((f"OpenFOAM polyDualMesh {d} {n}",
                              lambda d=d, n=n: h.foam_peer(d, n)))
                for v in [v for v in a.peer_variants if in_scope(a, v, n, peer=True)]:
                    steps.append((f"polydual foam + checkMesh {d} {n} {v}",
                                  lambda d=d, n=n, v=v: h.foam_polydual(d, n, v)))
    if not a.no_render:
        steps.append(("render figures and tables", h.render))
    p = Progress(len(steps))
    for what, fn in steps:
        p.step(what, fn)
    print(f"results in {h.out}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
