"""Checks that VTK itself reads every format write_vtu_poly writes, and reads
the same mesh from each (python3-vtk9, run by /usr/bin/python3; called by
tests/io/io_vtu_vtk_test.cpp).

usage: vtu_formats_check.py REFERENCE.vtu OTHER.vtu...

For every file: vtkXMLUnstructuredGridReader reads it without error, every cell
is a VTK_POLYHEDRON whose faces' directed edges cancel (closed, consistently
oriented), and points, face lists and every cell/point/field array equal those
of REFERENCE (normally the ascii file) exactly.
"""
import collections
import sys

import vtk
from vtk.util.numpy_support import vtk_to_numpy


def load(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    errors = vtk.vtkStringOutputWindow()
    vtk.vtkOutputWindow.SetInstance(errors)
    reader.Update()
    if reader.GetErrorCode() != 0 or "ERROR" in errors.GetOutput():
        sys.exit(f"{path}: VTK reports an error: {errors.GetOutput()[:500]}")
    grid = reader.GetOutput()
    cells = []
    for c in range(grid.GetNumberOfCells()):
        if grid.GetCellType(c) != vtk.VTK_POLYHEDRON:
            sys.exit(f"{path}: cell {c} has type {grid.GetCellType(c)}, not VTK_POLYHEDRON")
        cell = grid.GetCell(c)
        faces, balance = [], collections.Counter()
        for k in range(cell.GetNumberOfFaces()):
            ids = cell.GetFace(k).GetPointIds()
            loop = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
            faces.append(loop)
            for a, b in zip(loop, loop[1:] + loop[:1]):
                balance[(a, b)] += 1
                balance[(b, a)] -= 1
        if any(balance.values()):
            sys.exit(f"{path}: cell {c}: faces not closed/consistently oriented")
        cells.append(faces)
    arrays = {}
    for kind, data in (("cell", grid.GetCellData()), ("point", grid.GetPointData()), ("field", grid.GetFieldData())):
        for i in range(data.GetNumberOfArrays()):
            arrays[(kind, data.GetArrayName(i))] = vtk_to_numpy(data.GetArray(i)).tolist()
    points = vtk_to_numpy(grid.GetPoints().GetData()).tolist() if grid.GetPoints() else []
    return points, cells, arrays


def main(paths):
    ref_path, others = paths[0], paths[1:]
    ref = load(ref_path)
    if not ref[1]:
        sys.exit(f"{ref_path}: no cells")
    for path in others:
        got = load(path)
        for what, a, b in zip(("points", "cells", "arrays"), ref, got):
            if a != b:
                sys.exit(f"{path}: {what} differ from {ref_path}")
    print(f"vtu_formats_check: VTK reads {len(paths)} files, {len(ref[1])} polyhedra each, all equal")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
