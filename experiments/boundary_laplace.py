#!/usr/bin/env python3
"""The error of OpenFOAM's laplacianFoam on polydual's meshes, keep against caps
(design §4.10): for each mesh and boundary mode, `polydual convert --format foam
--boundary MODE`, the harmonic u = x^2 - y^2 + z imposed as fixedValue at every
boundary face centre (OpenFOAM's own, from `postProcess -func writeCellCentres`),
one implicit Euler step of 1e9 s (the steady state), and the L2 error
sqrt(sum V (T - u(C))^2 / sum V) over the cells. Needs Debian's openfoam.

usage: boundary_laplace.py POLYDUAL OUTDIR MESH... [-- EXTRA CONVERT OPTIONS]
"""
import math
import os
import re
import shutil
import subprocess
import sys

ENV = dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam")
HEADER = """FoamFile {{ version 2.0; format ascii; class {cls}; location "{loc}"; object {obj}; }}
"""
FILES = {
    "system/controlDict": ("dictionary", "system", "controlDict", """application laplacianFoam;
startFrom startTime; startTime 0; stopAt endTime; endTime 1e9; deltaT 1e9;
writeControl timeStep; writeInterval 1; writeFormat ascii; writePrecision 17; timePrecision 6;
"""),
    "system/fvSchemes": ("dictionary", "system", "fvSchemes", """ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
"""),
    "system/fvSolution": ("dictionary", "system", "fvSolution", """solvers { T { solver PCG; preconditioner DIC; tolerance 1e-14; relTol 0; maxIter 5000; } }
SIMPLE { nNonOrthogonalCorrectors 4; }
"""),
    "constant/transportProperties": ("dictionary", "constant", "transportProperties", "DT DT [0 2 -1 0 0 0 0] 1;\n"),
}


def exact(x, y, z):
    return x * x - y * y + z


def write(case, rel, cls, loc, obj, body):
    path = os.path.join(case, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, loc=loc, obj=obj) + body)


def read_list(text, start):
    """The entries of the OpenFOAM list whose count begins at text[start:]."""
    m = re.compile(r"\s*(\d+)\s*\(").match(text, start)
    n = int(m.group(1))
    body = text[m.end():]
    if n == 0:
        return []
    entries = re.findall(r"\(([^()]*)\)", body) if body.lstrip().startswith("(") else body.split(")")[0].split()
    return entries[:n]


def field_blocks(path):
    """internalField and each patch's value of a volume field file, as lists of strings."""
    text = open(path).read()
    out = {}
    m = re.search(r"internalField\s+nonuniform\s+List<\w+>", text)
    out["internal"] = read_list(text, m.end())
    for pm in re.finditer(r"\n\s*(\w+)\s*\n\s*\{[^{}]*?value\s+nonuniform\s+List<\w+>", text):
        out[pm.group(1)] = read_list(text, pm.end())
    return out


def patches(case):
    text = open(os.path.join(case, "constant/polyMesh/boundary")).read()
    return re.findall(r"\n\s*(\w+)\s*\n\s*\{\s*type\s+\w+;\s*nFaces\s+(\d+);", text)


def solve(case):
    for rel, (cls, loc, obj, body) in FILES.items():
        write(case, rel, cls, loc, obj, body)
    os.makedirs(os.path.join(case, "0"), exist_ok=True)
    subprocess.run(["postProcess", "-case", case, "-func", "writeCellCentres", "-time", "0"], env=ENV,
                   capture_output=True, check=True)
    subprocess.run(["postProcess", "-case", case, "-func", "writeCellVolumes", "-time", "0"], env=ENV,
                   capture_output=True, check=True)
    C = field_blocks(os.path.join(case, "0/C"))
    bf = []
    for name, n in patches(case):
        if int(n) == 0:
            bf.append(f"    {name} {{ type fixedValue; value uniform 0; }}\n")
            continue
        vals = [exact(*map(float, c.split())) for c in C[name]]
        bf.append(f"    {name} {{ type fixedValue; value nonuniform List<scalar> {len(vals)}("
                  + " ".join(repr(v) for v in vals) + "); }\n")
    write(case, "0/T", "volScalarField", "0", "T",
          "dimensions [0 0 0 1 0 0 0];\ninternalField uniform 0;\nboundaryField\n{\n" + "".join(bf) + "}\n")
    subprocess.run(["laplacianFoam", "-case", case], env=ENV, capture_output=True, check=True)
    T = [float(t) for t in field_blocks(os.path.join(case, "1e+09/T"))["internal"]]
    V = [float(v) for v in field_blocks(os.path.join(case, "0/V"))["internal"]]
    cc = [tuple(map(float, c.split())) for c in C["internal"]]
    err = sum(v * (t - exact(*c)) ** 2 for t, v, c in zip(T, V, cc))
    return math.sqrt(err / sum(V)), len(T)


def main():
    args = sys.argv[1:]
    extra = []
    if "--" in args:
        k = args.index("--")
        args, extra = args[:k], args[k + 1:]
    if len(args) < 3 or args[0] in ("-h", "--help"):
        sys.exit(__doc__)
    polydual, outdir, meshes = args[0], args[1], args[2:]
    os.makedirs(outdir, exist_ok=True)
    print("| mesh | boundary | cells | L2 error of T |")
    print("|---|---|---|---|")
    for mesh in meshes:
        name = os.path.basename(mesh).split(".")[0]
        for mode in ("caps", "keep"):
            case = os.path.join(outdir, f"{name}_{mode}")
            shutil.rmtree(case, ignore_errors=True)
            p = subprocess.run([polydual, "convert", mesh, "-o", case, "--format", "foam", "--boundary", mode] + extra,
                               capture_output=True, text=True)
            if p.returncode != 0:
                print(f"| {name} | {mode} | convert exit {p.returncode} | |", flush=True)
                continue
            try:
                l2, cells = solve(case)
                print(f"| {name} | {mode} | {cells} | {l2:.3e} |", flush=True)
            except (subprocess.CalledProcessError, KeyError, AttributeError, FileNotFoundError) as e:
                print(f"| {name} | {mode} | OpenFOAM failed: {type(e).__name__} {str(e)[:60]} | |", flush=True)


if __name__ == "__main__":
    main()
