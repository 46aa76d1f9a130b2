#!/bin/sh
# Regenerates the TetGen and Medit meshes of this folder from the .poly PLCs
# (Debian's tetgen 1.5.0). Every facet of each PLC has the one marker 1.
set -e
cd "$(dirname "$0")"
tetgen -pqAa0.01 two_boxes.poly > /dev/null  # two regions (-A)
tetgen -pqa0.02 fichera.poly > /dev/null
tetgen -pqga0.01 cube.poly > /dev/null       # -g: cube.1.mesh (Medit)
# The Medit file as a mesher that writes only boundary triangles would: drop
# TetGen's interior triangles (ref 0) and its Corners and Edges sections, so
# that the one triangle ref 1 over the six sides is all the file classifies.
awk '
  /^Triangles/ { sec = "tri"; print; getline; n = $1; hold = ""; kept = 0
                 for (i = 0; i < n; ++i) { getline; if ($4 != 0) { hold = hold $0 "\n"; ++kept } }
                 print kept; printf "%s", hold; next }
  /^Corners/ || /^Edges/ { skip = 1; next }
  skip && /^[A-Z]/ { skip = 0 }
  !skip { print }
' cube.1.mesh > cube_one_ref.mesh
rm -f cube.1.mesh cube.1.node cube.1.ele cube.1.face ./*.edge
