#!/usr/bin/python3
"""The corpus test: every mesh of tests/corpus/corpus.py, made at test time,
converted by the default command, every invariant checked and the quality
targets measured, recorded and compared with tests/corpus/targets.json.

Per mesh:
  invariants (always asserted): `polydual convert M -o out.vtu --json` exits 0
    (run with --threads 1 and again with --threads 2), the summary lists no
    defect, invalid_after is 0, topology_ok and geometry_ok are true,
    `polydual check out.vtu` exits 0, the two outputs are byte-identical, and
    OpenFOAM's checks (the summary's "openfoam": face pyramids and face tets
    by its own floating-point centres, as checkMesh -allGeometry) fail no face;
  targets (measured): max kappa/3 of the final cells, cells the split added
    over the uncut dual (%), the worst per-material volume error (%) of a
    third conversion with `--boundary keep` (exact there, L5b; the default
    caps' volume error is recorded as volume_error_pct, not a target), seconds
    per 1000 tets of the whole command (its CPU time with --threads 1: the
    work, whatever else the machine runs; the summary's wall seconds are in
    the table too), the cells of `--optimize none` over the uncut dual (the
    split alone makes that dual valid: a ratio); `--optimize none` and
    `--optimize untangle` must also end with no defect and no invalid cell,
    and untangle with no OpenFOAM failure (its repair), its cells the split
    added recorded. targets.json gives the
    bound of each and, per mesh, today's value of the targets it misses: such a
    value may not get worse (beyond the file's slack), a value below it is
    printed as an improvement, and a mesh that now meets the bound says so.
The table goes to WORK/corpus_table.json (read by corpus_table.py). A mesh
whose tool is missing is skipped with a message; exit 77 (ctest's skip) when
every mesh was skipped, 1 when any check failed. With POLYDUAL_REQUIRE_TOOLS=1
in the environment (scripts/test.sh, CI: every tool is installed) a skipped
mesh is a failure, as in the unit tests (tests/require_tool.h).

  run_corpus.py --bin build/polydual --work DIR [--labelled_image_medit BIN]
                [--polyhedral_features_medit BIN] [--only NAME ...]
                [--targets FILE] [--write-targets]
  run_corpus.py --self-test       (the target verdicts on made-up rows)
"""
import argparse
import filecmp
import json
import math
import os
import resource
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus  # noqa: E402

TARGETS = os.path.join(corpus.HERE, "targets.json")
# Below this many tets a command's fixed cost (tens of milliseconds) dominates
# its time per 1000 tets, which is then recorded but not asserted.
MIN_TETS_FOR_TIME = 1000


def cpu_seconds():
    """User + system seconds of this process's finished children."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def convert(binary, mesh, out, threads, extra=()):
    """The default command's summary (with its CPU seconds added as
    "cpu_seconds"), or an error string; `extra`: options added."""
    cmd = [binary, "convert", mesh, "-o", out, "--force", "--json", "--quiet", "--threads", str(threads), *extra]
    cpu0 = cpu_seconds()
    res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    cpu = cpu_seconds() - cpu0
    if res.returncode != 0:
        return None, f"{' '.join(cmd)} exited {res.returncode}: " + " | ".join(res.stderr.strip().splitlines()[-3:])
    try:
        d = json.loads(res.stdout)
    except ValueError as e:
        return None, f"{' '.join(cmd)}: its --json output does not parse ({e})"
    d["cpu_seconds"] = cpu
    return d, None


def finite(x):
    """A measure the summary wrote as null (infinite: a tangled cell) as inf."""
    return float("inf") if x is None else x


def measures(d):
    """The measures the targets bound, from one summary."""
    opt = d["optimize"]
    split = d["split"]
    final = split["optimize"] if split.get("rounds") and "optimize" in split else opt
    uncut = opt["quality_after"]["cells"]
    return {
        "tets": d["tets"], "uncut_cells": uncut, "cells": d["cells"],
        "max_kappa3": finite(d["worst_cells"]["max"]), "mean_kappa3": finite(d["worst_cells"]["mean"]),
        "tangled": final["quality_after"]["tangled"], "split_rounds": len(split.get("rounds", [])),
        "split_added_pct": 100.0 * (d["cells"] - uncut) / uncut,
        "volume_error_pct": 100.0 * volume_error(d),
        "seconds": d["seconds"]["total"], "cpu_seconds": d["cpu_seconds"],
        "seconds_per_ktets": 1000.0 * d["cpu_seconds"] / d["tets"],
    }


def volume_error(d):
    """The worst relative difference of a material's dual and primal volumes."""
    return max((abs(m["volume"] - m["primal_volume"]) / abs(m["primal_volume"]) for m in d["materials"]),
               default=0.0)


def invariants(binary, name, d1, out1, out2):
    """Names and reasons of the invariants one mesh breaks (empty: none)."""
    bad = []
    if d1["defects"]:
        bad.append(f"defects listed: {json.dumps(d1['defects'])[:300]}")
    if d1["invalid_after"] != 0:
        bad.append(f"invalid_after {d1['invalid_after']} (cells {d1.get('invalid_where', [])[:5]})")
    for k in ("topology_ok", "geometry_ok"):
        if d1[k] is not True:
            bad.append(f"{k} is {d1[k]}")
    # OpenFOAM's checkMesh (its own centres, floating point) must find no
    # wrongly oriented face pyramid and no face-tet error.
    of = d1.get("openfoam") or {}
    if of.get("pyramid_faces", 1) != 0 or of.get("face_tet_faces", 1) != 0:
        bad.append(f"OpenFOAM's checks fail: {json.dumps(of)}")
    res = subprocess.run([binary, "check", out1, "--quiet"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    if res.returncode != 0:
        bad.append(f"`polydual check {out1}` exited {res.returncode}: " + " | ".join(res.stderr.splitlines()[-3:]))
    if not filecmp.cmp(out1, out2, shallow=False):
        bad.append("not deterministic: --threads 1 and --threads 2 wrote different bytes")
    return bad


def run_mesh(binary, name, path, work):
    """(row, failures) of one mesh."""
    outs = [os.path.join(work, f"{name}.t{t}.vtu") for t in (1, 2)]
    d1, err1 = convert(binary, path, outs[0], 1)
    d2, err2 = convert(binary, path, outs[1], 2)
    dk, errk = convert(binary, path, os.path.join(work, f"{name}.keep.vtu"), 1, ["--boundary", "keep"])
    dn, errn = convert(binary, path, os.path.join(work, f"{name}.none.vtu"), 1, ["--optimize", "none"])
    du, erru = convert(binary, path, os.path.join(work, f"{name}.untangle.vtu"), 1, ["--optimize", "untangle"])
    errs = [e for e in (err1, err2, errk, errn, erru) if e]
    if errs:
        return None, errs
    try:
        row = measures(d1)
        row["keep_volume_error_pct"] = 100.0 * volume_error(dk)
        row["keep_cells"] = dk["cells"]
        row["none_cells"], row["untangle_cells"] = dn["cells"], du["cells"]
        row["none_cells_ratio"] = dn["cells"] / row["uncut_cells"]
        row["untangle_split_added_pct"] = 100.0 * (du["cells"] - row["uncut_cells"]) / row["uncut_cells"]
    except (KeyError, TypeError, ZeroDivisionError) as e:
        return None, [f"the summary lacks a field the corpus reads: {e!r}"]
    bad = invariants(binary, name, d1, *outs)
    for mode, d in (("--boundary keep", dk), ("--optimize none", dn), ("--optimize untangle", du)):
        if d["defects"] or d["invalid_after"] != 0:
            bad.append(f"{mode}: defects {json.dumps(d['defects'])[:200]}, invalid_after {d['invalid_after']}")
    of = du.get("openfoam") or {}
    if of.get("pyramid_faces", 1) != 0 or of.get("face_tet_faces", 1) != 0:
        bad.append(f"--optimize untangle: OpenFOAM's checks fail: {json.dumps(of)}")
    return row, bad


def target_verdicts(name, row, spec):
    """(failures, notes) of one mesh's targets against targets.json."""
    fails, notes = [], []
    recorded = spec["meshes"].get(name)
    if recorded is None:
        return [], [f"{name}: not in targets.json, its targets are recorded but not asserted"]
    for metric, bound in spec["targets"].items():
        v = row[metric]
        if metric == "seconds_per_ktets" and row["tets"] < MIN_TETS_FOR_TIME:
            continue
        today = recorded.get(metric)
        if today is None:
            if not v <= bound:
                fails.append(f"{metric} {v:.4g} misses the target {bound:g} (met when targets.json was written)")
            continue
        limit = today * (1 + spec["slack"][metric])
        if not v <= limit:  # also catches NaN
            fails.append(f"{metric} {v:.4g} is worse than recorded ({today:.4g}, slack up to {limit:.4g})")
        elif v <= bound:
            notes.append(f"{name}: {metric} {v:.4g} now meets the target {bound:g}: drop it from targets.json")
        elif v < today * (1 - min(spec["slack"][metric], 0.5)):
            notes.append(f"{name}: {metric} {v:.4g} is better than recorded ({today:.4g}): tighten targets.json")
    return fails, notes


def written_targets(spec, rows):
    """targets.json with today's values of every missed target (meshes not
    converted in this run keep their entries)."""
    meshes = dict(spec["meshes"])
    for name, row in rows.items():
        missed = {}
        for metric, bound in spec["targets"].items():
            if metric == "seconds_per_ktets" and row["tets"] < MIN_TETS_FOR_TIME:
                continue
            v = row[metric]
            if not v <= bound:
                missed[metric] = float(f"{v:.4g}") if math.isfinite(v) else 1e308
        meshes[name] = missed
    return {**spec, "meshes": meshes}


def dump_targets(spec, path):
    """Writes SPEC with one line per mesh (readable diffs when it is tightened)."""
    lines = ["{"] + [f" {json.dumps(k)}: {json.dumps(v)}," for k, v in spec.items() if k != "meshes"]
    lines.append(' "meshes": {')
    items = list(spec["meshes"].items())
    lines += [f"  {json.dumps(k)}: {json.dumps(v)}" + ("," if i + 1 < len(items) else "")
              for i, (k, v) in enumerate(items)]
    lines += [" }", "}"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def print_row(name, r):
    print(f"corpus: {name:22s} {r['tets']:6d} tets {r['uncut_cells']:6d} -> {r['cells']:6d} cells "
          f"(+{r['split_added_pct']:.1f} %), max k/3 {r['max_kappa3']:.4g}, mean {r['mean_kappa3']:.3f}, "
          f"vol err caps {r['volume_error_pct']:.3g} % keep {r['keep_volume_error_pct']:.2g} %, "
          f"none {r['none_cells_ratio']:.2f}x, untangle +{r['untangle_split_added_pct']:.1f} %, "
          f"{r['seconds_per_ktets']:.3f} CPU s/1000 tets", flush=True)


def self_test():
    """The verdicts on made-up rows: 0 when each comes out as it must."""
    spec = {"targets": {"max_kappa3": 10, "seconds_per_ktets": 2.0},
            "slack": {"max_kappa3": 0.05, "seconds_per_ktets": 2.0},
            "meshes": {"met": {}, "missed": {"max_kappa3": 100.0}}}
    def row(k, t=5000, tets=5000):
        return {"max_kappa3": k, "seconds_per_ktets": t, "tets": tets}
    cases = [  # (mesh, row, failures expected, note expected)
        ("met", row(9.9, 1.0), 0, False), ("met", row(10.5, 1.0), 1, False),
        ("met", row(9.0, 2.5), 1, False), ("met", row(9.0, 2.5, tets=999), 0, False),
        ("met", row(float("nan"), 1.0), 1, False), ("missed", row(104.0, 1.0), 0, False),
        ("missed", row(106.0, 1.0), 1, False), ("missed", row(50.0, 1.0), 0, True),
        ("missed", row(8.0, 1.0), 0, True), ("unlisted", row(1e9, 1e9), 0, True)]
    bad = 0
    for mesh, r, nfail, note in cases:
        fails, notes = target_verdicts(mesh, r, spec)
        if len(fails) != nfail or bool(notes) != note:
            print(f"corpus self-test: {mesh} {r}: failures {fails}, notes {notes}")
            bad += 1
    kept = written_targets(spec, {"met": row(12.0, 1.0)})["meshes"]
    if kept != {"met": {"max_kappa3": 12.0}, "missed": {"max_kappa3": 100.0}}:
        print(f"corpus self-test: written targets {kept}")
        bad += 1
    print(f"corpus self-test: {len(cases) + 1 - bad} passed, {bad} failed")
    return 1 if bad else 0


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--self-test", action="store_true", help="check the target verdicts on made-up rows")
    ap.add_argument("--bin")
    ap.add_argument("--work")
    ap.add_argument("--labelled_image_medit")
    ap.add_argument("--polyhedral_features_medit")
    ap.add_argument("--only", nargs="*", help="these meshes only")
    ap.add_argument("--targets", default=TARGETS)
    ap.add_argument("--write-targets", action="store_true",
                    help="rewrite the targets file with today's values of every missed target")
    return ap.parse_args()


def main():
    a = parse_args()
    if a.self_test:
        return self_test()
    if not a.bin or not a.work:
        print("run_corpus.py: --bin and --work are needed", file=sys.stderr)
        return 2
    tools = {k: getattr(a, k) for k in ("labelled_image_medit", "polyhedral_features_medit") if getattr(a, k)}
    a.bin = os.path.abspath(a.bin) if os.sep in a.bin else a.bin  # a bare name is looked up on PATH
    spec = json.load(open(a.targets))
    os.makedirs(a.work, exist_ok=True)
    rows, failures, notes, skipped = {}, [], [], []
    for name in a.only or corpus.names():
        t0 = time.monotonic()
        try:
            path = corpus.make(name, a.work, tools)
        except corpus.Skip as e:
            if os.environ.get("POLYDUAL_REQUIRE_TOOLS") == "1":
                failures.append(f"{name}: a tool is missing (POLYDUAL_REQUIRE_TOOLS=1): {e}")
                continue
            print(f"corpus: SKIP {name}: {e}", flush=True)
            skipped.append(name)
            continue
        except corpus.MakeError as e:
            failures.append(f"{name}: could not be made: {e}")
            continue
        row, bad = run_mesh(a.bin, name, path, a.work)
        failures += [f"{name}: {b}" for b in bad]
        if row is None:
            continue
        row["mesh"], row["file"], row["wall_seconds"] = name, path, time.monotonic() - t0
        rows[name] = row
        print_row(name, row)
        f, n = target_verdicts(name, row, spec)
        failures += [f"{name}: {x}" for x in f]
        notes += n
    json.dump({"targets": spec["targets"], "producers": corpus.producer_versions(),
               "meshes": list(rows.values()), "skipped": skipped, "notes": notes, "failures": failures},
              open(os.path.join(a.work, "corpus_table.json"), "w"), indent=1)
    if a.write_targets:
        dump_targets(written_targets(spec, rows), a.targets)
    for n in notes:
        print(f"corpus: NOTE {n}")
    for f in failures:
        print(f"corpus: FAIL {f}")
    print(f"corpus: {len(rows)} meshes converted, {len(skipped)} skipped, {len(failures)} failures; "
          f"table in {os.path.join(a.work, 'corpus_table.json')}")
    if failures:
        return 1
    return 77 if not rows else 0


if __name__ == "__main__":
    sys.exit(main())
