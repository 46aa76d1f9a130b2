#!/usr/bin/env bash
# Slow external check (design §9): the .vtu that `polydual convert` writes opens in
# VTK itself, with the reported number of cells, all VTK_POLYHEDRON with faces.
# usage: vtk_read.sh POLYDUAL_BINARY SCRATCH_DIR
set -euo pipefail
bin=$1
out=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$out"
if ! /usr/bin/python3 -c "import vtk" 2>/dev/null; then
  echo "vtk_read: /usr/bin/python3 cannot import vtk (install python3-vtk9)" >&2
  exit 1
fi
"$bin" generate cube --tets 2000 -o "$out/cube.msh"
"$bin" convert "$out/cube.msh" -o "$out/cube.vtu" --json > "$out/cube_convert.json"
/usr/bin/python3 "$here/vtu_check.py" "$out/cube.vtu" "$out/cube_convert.json"
