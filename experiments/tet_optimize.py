"""Optimise the tets of a classified Gmsh mesh in place of the paper's
"condition number optimization" of the input (section 4), keeping the full
classification (msh 4.1, every entity saved).

The gmsh 4.8.4 command line skips discrete (loaded) volumes in OptimizeMesh,
and Debian ships no gmsh.py, so this calls the C API of libgmsh with ctypes
and passes force=1, which applies the optimiser to discrete entities too.

usage: tet_optimize.py IN.msh OUT.msh [--method Netgen] [--niter 1]
"""
import argparse
import ctypes
import ctypes.util
import sys

def _lib():
    for name in ("libgmsh.so.4.8", "libgmsh.so", ctypes.util.find_library("gmsh")):
        if not name:
            continue
        try:
            return ctypes.CDLL(name)
        except OSError:
            pass
    raise OSError("libgmsh not found (Debian package libgmsh4.8)")

def optimize(src, dst, methods=("", "Relocate3D"), niter=1, threshold=0.6):
    g = _lib()
    ierr = ctypes.c_int(0)
    def check(what):
        if ierr.value != 0:
            raise RuntimeError(f"gmsh {what} failed (ierr={ierr.value})")
    g.gmshInitialize(0, None, 0, ctypes.byref(ierr)); check("initialize")
    try:
        for name, value in (("General.Terminal", 0), ("General.NumThreads", 1),
                            ("Mesh.RandomSeed", 1), ("Mesh.SaveAll", 1),
                            ("Mesh.MshFileVersion", 4.1), ("Mesh.Binary", 0),
                            ("Mesh.OptimizeThreshold", threshold)):
            g.gmshOptionSetNumber(name.encode(), ctypes.c_double(value), ctypes.byref(ierr))
            check("option " + name)
        g.gmshOpen(src.encode(), ctypes.byref(ierr)); check("open " + src)
        for method in methods:
            g.gmshModelMeshOptimize(method.encode(), 1, niter, None, ctypes.c_size_t(0),
                                    ctypes.byref(ierr)); check("optimize " + (method or "Gmsh"))
        g.gmshWrite(dst.encode(), ctypes.byref(ierr)); check("write " + dst)
    finally:
        g.gmshFinalize(ctypes.byref(ierr))

def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("src"); ap.add_argument("dst")
    ap.add_argument("--methods", default="Gmsh,Relocate3D",
                    help="comma-separated gmsh optimisers, Gmsh = the default one")
    ap.add_argument("--niter", type=int, default=1)
    ap.add_argument("--threshold", type=float, default=0.6,
                    help="Mesh.OptimizeThreshold: tets below this quality are optimised")
    a = ap.parse_args(argv)
    methods = ["" if m == "Gmsh" else m for m in a.methods.split(",")]
    optimize(a.src, a.dst, methods, a.niter, a.threshold)
    return 0

if __name__ == "__main__":
    sys.exit(main())
