# Meshes a box with a cylindrical hole through it with Netgen (Debian's
# python3-netgen) and exports it as Netgen's "Gmsh2 Format" (msh 2.0, every
# tet negatively oriented by Gmsh's convention).
# Usage: /usr/bin/python3 make_gmsh2.py OUT.msh [maxh, default 0.45]
import sys

from netgen.csg import CSGeometry, Cylinder, OrthoBrick, Pnt

out = sys.argv[1]
maxh = float(sys.argv[2]) if len(sys.argv) > 2 else 0.45
geo = CSGeometry()
box = OrthoBrick(Pnt(0, 0, 0), Pnt(2, 1, 1))
hole = Cylinder(Pnt(1, 0.5, -1), Pnt(1, 0.5, 2), 0.25)
geo.Add(box - hole)
mesh = geo.GenerateMesh(maxh=maxh)
mesh.Export(out, "Gmsh2 Format")
