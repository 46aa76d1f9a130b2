"""Judges one OpenFOAM checkMesh log (run with -allTopology) for checkmesh.sh.

usage: checkmesh_summary.py DOMAIN LOG EXIT_CODE

Passes when checkMesh ran (exit 0, no FOAM FATAL), its topology section (the
text before "Checking geometry...") has no "***" failure, and the zones the
domain must have are present: a material_<tag> cellZone for every domain, two
of them and an interface_<tag> faceZone for twomat, a fracture_<tag> faceZone
for fracture, network and fins. Baffles (slit faces) are allowed. Geometry failures are reported, not judged: the dual before
optimisation may legitimately fail geometric quality checks.
Prints one summary line; exits 1 on failure.
"""
import re
import sys


def main(domain, log_path, exit_code):
    with open(log_path, errors="replace") as f:
        log = f.read()
    problems = []
    if exit_code != 0:
        problems.append(f"checkMesh exit code {exit_code}")
    if "FOAM FATAL" in log:
        problems.append("FOAM FATAL ERROR: " + log[log.index("FOAM FATAL"):].splitlines()[1].strip())
    if "Checking topology..." not in log or "Checking geometry..." not in log:
        problems.append("checkMesh did not reach the topology and geometry checks")
    head, _, geometry = log.partition("Checking geometry...")
    topology = head.partition("Checking topology...")[2]
    geo_failures = [l.strip() for l in geometry.splitlines() if "***" in l]
    # Not every topology failure is starred (v1912 prints "Faces with invalid
    # vertex labels found" plainly), so in the basic block every check line must
    # say OK ("<<" lines are notes), and the final failure count must not exceed
    # the starred geometry failures.
    basic = topology.partition("Checking patch topology")[0]
    topo_failures = [l.strip() for l in topology.splitlines() if "***" in l]
    topo_failures += [l.strip() for l in basic.splitlines()
                      if l.strip() and "***" not in l and "OK" not in l
                      and not l.strip().startswith(("<<", "*"))  # notes and warnings
                      and "multiple regions" not in l
                      # slit faces are written as baffles (a face and its reverse
                      # on one cell); checkMesh counts them without failing
                      and "identical duplicate faces (baffle faces)" not in l]
    failed = re.search(r"Failed (\d+) mesh checks", log)
    if failed and int(failed.group(1)) > len(geo_failures) and not topo_failures:
        topo_failures.append(f"checkMesh failed {failed.group(1)} checks, "
                             f"only {len(geo_failures)} of them geometric")
    problems += topo_failures

    cell_zones = re.findall(r"^\s+(material_-?\d+)\s+\d+", head, re.M)
    face_zones = re.findall(r"^\s+((?:interface|fracture)_-?\d+)\s+\d+", head, re.M)
    if not cell_zones:
        problems.append("no material_<tag> cellZone")
    if domain == "twomat":
        if len(cell_zones) < 2:
            problems.append(f"twomat has {len(cell_zones)} material cellZones, expected 2")
        if not any(z.startswith("interface_") for z in face_zones):
            problems.append("twomat has no interface_<tag> faceZone")
    if domain in ("fracture", "network", "fins") and not any(z.startswith("fracture_") for z in face_zones):
        problems.append(f"{domain} has no fracture_<tag> faceZone")

    cells = re.search(r"^\s+cells:\s+(\d+)", log, re.M)
    verdict = "FAIL" if problems else "ok"
    print(f"checkmesh {domain}: {verdict}; cells {cells.group(1) if cells else '?'}; "
          f"topology {'FAILED' if topo_failures else 'OK'}; "
          f"geometry {len(geo_failures)} failed check(s)"
          f"{' (' + '; '.join(geo_failures) + ')' if geo_failures else ''}; "
          f"cellZones {' '.join(cell_zones) or '-'}; faceZones {' '.join(face_zones) or '-'}"
          f"{'; problems: ' + ' | '.join(problems) if problems else ''}")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2], int(sys.argv[3])))
