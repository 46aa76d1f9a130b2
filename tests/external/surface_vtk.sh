#!/usr/bin/env bash
# Slow external check (design §15): the surface dual of a Gmsh fracture network
# (OpenCASCADE BooleanFragments of two crossing squares and a disk ending inside
# one) opens in VTK itself in every encoding, with the reported numbers of
# polygons and points, all VTK_POLYGON, every polygon valid.
# usage: surface_vtk.sh POLYDUAL_BINARY SCRATCH_DIR
set -euo pipefail
bin=$1
out=$2
mkdir -p "$out"
if ! /usr/bin/python3 -c "import vtk" 2>/dev/null; then
  echo "surface_vtk: /usr/bin/python3 cannot import vtk (install python3-vtk9)" >&2
  exit 1
fi
command -v gmsh > /dev/null || { echo "surface_vtk: gmsh not found (package gmsh)" >&2; exit 1; }
cat > "$out/network.geo" <<'GEO'
SetFactory("OpenCASCADE");
Rectangle(1) = {-1, -1, 0, 2, 2};
Rectangle(2) = {-1, -1, 0, 2, 2};
Rotate {{1, 0, 0}, {0, 0, 0}, Pi/2} { Surface{2}; }
Disk(3) = {0.3, 0.5, 0, 0.4, 0.4};
Rotate {{0, 1, 0}, {0.3, 0.5, 0}, Pi/2} { Surface{3}; }
BooleanFragments{ Surface{1, 2, 3}; Delete; }{}
Mesh.MeshSizeMax = 0.05;
GEO
gmsh -2 -format msh41 "$out/network.geo" -o "$out/network.msh" > "$out/gmsh.log" 2>&1
for enc in raw base64 ascii; do
  "$bin" convert "$out/network.msh" -o "$out/network_$enc.vtu" --vtu-encoding "$enc" --zlib 0 --json --quiet \
    > "$out/network_$enc.json"
  /usr/bin/python3 - "$out/network_$enc.vtu" "$out/network_$enc.json" <<'PY'
import json, sys, vtk
path, summary = sys.argv[1], json.load(open(sys.argv[2]))
r = vtk.vtkXMLUnstructuredGridReader()
r.SetFileName(path)
r.Update()
g = r.GetOutput()
assert g.GetNumberOfCells() == summary["dual"]["polygons"], (g.GetNumberOfCells(), summary["dual"])
assert g.GetNumberOfPoints() == summary["dual"]["points"], (g.GetNumberOfPoints(), summary["dual"])
assert all(g.GetCellType(i) == 7 for i in range(g.GetNumberOfCells())), "not all VTK_POLYGON"
assert summary["invalid"] == 0 and g.GetCellData().GetArray("valid").GetRange() == (1.0, 1.0)
print(f"surface_vtk: {path}: {g.GetNumberOfCells()} polygons, {g.GetNumberOfPoints()} points, all valid")
PY
done
