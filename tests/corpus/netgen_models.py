#!/usr/bin/python3
"""Netgen (Debian's python3-netgen) meshes of two CSG models, written in
Netgen's "Gmsh2 Format" export (msh 2.0 header, every tet negatively oriented
by Gmsh's convention: the file a Netgen user hands to other tools).

  netgen_models.py MODEL OUT.msh [MAXH]

Models:
  ballblock  a block with a cylindrical through-hole and a spherical inclusion
             (two materials, a curved interface);
  bracket    an L-shaped block with a slanted cut and a round hole through its
             upright (sharp convex and concave edges, one curved face).
Prints the number of tets. Netgen's own progress goes to stdout as well.
"""
import sys


def ballblock(csg):
    box = csg.OrthoBrick(csg.Pnt(0, 0, 0), csg.Pnt(1, 1, 0.6))
    hole = csg.Cylinder(csg.Pnt(0.3, 0.5, -1), csg.Pnt(0.3, 0.5, 2), 0.15)
    ball = csg.Sphere(csg.Pnt(0.7, 0.5, 0.3), 0.18)
    geo = csg.CSGeometry()
    geo.Add(box - hole - ball)
    geo.Add(ball)
    return geo


def bracket(csg):
    base = csg.OrthoBrick(csg.Pnt(0, 0, 0), csg.Pnt(1.2, 0.8, 0.25))
    upright = csg.OrthoBrick(csg.Pnt(0, 0, 0), csg.Pnt(0.3, 0.8, 1.0))
    # Keep the side of the plane through (1.2, 0, 0.1) with outer normal (1, 0, 1).
    slant = csg.Plane(csg.Pnt(1.2, 0, 0.1), csg.Vec(1, 0, 1))
    hole = csg.Cylinder(csg.Pnt(-1, 0.4, 0.65), csg.Pnt(2, 0.4, 0.65), 0.15)
    geo = csg.CSGeometry()
    geo.Add(((base * slant) + upright) - hole)
    return geo


MODELS = {"ballblock": ballblock, "bracket": bracket}


def main(argv):
    if len(argv) < 3 or argv[1] not in MODELS:
        print(__doc__, file=sys.stderr)
        return 2
    import netgen.csg as csg  # Debian's python3-netgen; imported late so --help works without it
    maxh = float(argv[3]) if len(argv) > 3 else 0.1
    mesh = MODELS[argv[1]](csg).GenerateMesh(maxh=maxh)
    mesh.Export(argv[2], "Gmsh2 Format")
    print(f"{len(mesh.Elements3D())} tets")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
