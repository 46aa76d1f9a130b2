"""Checks a polyhedral .vtu with VTK itself (python3-vtk9, run by /usr/bin/python3).

usage: vtu_check.py MESH.vtu CONVERT.json

Asserts that VTK reads the file, that the cell count equals the "cells" value
that `polydual convert --json` reported, and that every cell is a
VTK_POLYHEDRON (42) with faces whose directed edges cancel (each edge appears
as often in one direction as in the other: closed and consistently oriented).
"""
import collections
import json
import sys

import vtk


def find_key(value, key):
    """The value of `key` nearest the top of a JSON document (breadth first)."""
    queue = collections.deque([value])
    while queue:
        v = queue.popleft()
        if isinstance(v, dict):
            if key in v:
                return v[key]
            queue.extend(v.values())
        elif isinstance(v, list):
            queue.extend(v)
    return None


def main(vtu_path, json_path):
    with open(json_path) as f:
        text = f.read()
    # The command may print a line or two before its JSON object.
    report = json.loads(text[text.index("{"):])
    expected = find_key(report, "cells")
    if not isinstance(expected, int):
        sys.exit(f"{json_path}: no integer 'cells' in the convert --json output")

    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(vtu_path)
    reader.Update()
    grid = reader.GetOutput()
    n = grid.GetNumberOfCells()
    if n != expected:
        sys.exit(f"{vtu_path}: VTK reads {n} cells, convert reported {expected}")
    if n == 0:
        sys.exit(f"{vtu_path}: no cells")

    bad = []
    for c in range(n):
        if grid.GetCellType(c) != vtk.VTK_POLYHEDRON:
            bad.append(f"cell {c}: type {grid.GetCellType(c)}, not VTK_POLYHEDRON")
            continue
        cell = grid.GetCell(c)
        if cell.GetNumberOfFaces() < 4:
            bad.append(f"cell {c}: {cell.GetNumberOfFaces()} faces")
            continue
        balance = collections.Counter()
        for k in range(cell.GetNumberOfFaces()):
            ids = cell.GetFace(k).GetPointIds()
            loop = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
            for a, b in zip(loop, loop[1:] + loop[:1]):
                balance[(a, b)] += 1
                balance[(b, a)] -= 1
        if any(balance.values()):
            bad.append(f"cell {c}: faces not closed/consistently oriented")
    if bad:
        sys.exit(f"{vtu_path}: {len(bad)} bad cells, first: " + "; ".join(bad[:5]))
    print(f"vtk_read: {vtu_path}: {n} VTK_POLYHEDRON cells with faces, as reported")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
