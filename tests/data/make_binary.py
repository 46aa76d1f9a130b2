#!/usr/bin/python3
"""Writes the binary test files of tests/data (run once, outputs committed):
cube5_bin.msh (Gmsh 4.1 binary), cube5_v2_bin.msh (Gmsh 2.2 binary),
cube5_bin.vtu (VTU, base64 with one UInt64-header stream) and
cube5_bin32.vtu (UInt32 header encoded separately, as some VTK versions do).
The mesh is the same 5-tet unit cube as the ASCII files: four corner tets
(region 10, volume entity 1) around a centre tet (region 20, volume entity 2);
cube faces are model faces 1..6, the centre tet's faces the interface 7, cube
edges model edges 1..12, face diagonals 13..18, cube corners model vertices."""
import base64
import itertools
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def cube():
    pts = [(float(v & 1), float((v >> 1) & 1), float((v >> 2) & 1)) for v in range(8)]

    def orient(t):
        a, b, c, d = (pts[i] for i in t)
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        w = [d[k] - a[k] for k in range(3)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]))

    tets = []
    for t in [(0, 1, 2, 4), (3, 1, 2, 7), (5, 1, 4, 7), (6, 2, 4, 7), (1, 2, 4, 7)]:
        t = list(t)
        if orient(t) < 0:
            t[2], t[3] = t[3], t[2]
        assert orient(t) > 0
        tets.append(t)
    regions = [10, 10, 10, 10, 20]
    # Boundary faces: tagged by the cube face plane (x=0:1, x=1:2, y=0:3, ...).
    count = {}
    for t in tets:
        for f in itertools.combinations(sorted(t), 3):
            count[f] = count.get(f, 0) + 1
    tris = []
    for f, n in sorted(count.items()):
        if n == 1:
            for axis in range(3):
                vals = {pts[i][axis] for i in f}
                if len(vals) == 1:
                    tris.append((f, 1 + 2 * axis + int(vals.pop())))
    for f in itertools.combinations(sorted(tets[4]), 3):
        tris.append((f, 7))
    edges = []
    for a, b in itertools.combinations(range(8), 2):
        if bin(a ^ b).count("1") == 1:
            edges.append(((a, b), len(edges) + 1))
    for a, b in itertools.combinations(sorted(tets[4]), 2):
        edges.append(((a, b), 13 + len(edges) - 12))
    corners = [(v, v + 1) for v in range(8)]
    return pts, tets, regions, tris, edges, corners


def msh4_binary(path):
    pts, tets, regions, tris, edges, corners = cube()
    i, q, d = (lambda v: struct.pack("<i", v)), (lambda v: struct.pack("<Q", v)), (lambda v: struct.pack("<d", v))
    b = b"$MeshFormat\n4.1 1 8\n" + i(1) + b"\n$EndMeshFormat\n$Entities\n"
    b += q(8) + q(18) + q(7) + q(2)
    for v, tag in corners:
        b += i(tag) + b"".join(d(c) for c in pts[v]) + q(0)
    box = d(0) * 3 + d(1) * 3
    for _, tag in edges:
        b += i(tag) + box + q(0) + q(0)
    for tag in range(1, 8):
        b += i(tag) + box + q(0) + q(0)
    b += i(1) + box + q(1) + i(10) + q(0)
    b += i(2) + box + q(1) + i(20) + q(0)
    b += b"\n$EndEntities\n$Nodes\n"
    # Sparse node tags 10, 20, ..., 80 in two blocks.
    b += q(2) + q(8) + q(10) + q(80)
    for block in (range(0, 4), range(4, 8)):
        b += i(3) + i(1) + i(0) + q(len(block))
        b += b"".join(q(10 * (v + 1)) for v in block)
        b += b"".join(d(c) for v in block for c in pts[v])
    b += b"\n$EndNodes\n$Elements\n"
    blocks = [(0, tag, 15, [[v]]) for v, tag in corners]
    blocks += [(1, tag, 1, [list(e)]) for e, tag in edges]
    for tag in range(1, 8):
        blocks.append((2, tag, 2, [list(f) for f, t in tris if t == tag]))
    blocks.append((3, 1, 4, tets[:4]))
    blocks.append((3, 2, 4, tets[4:]))
    n = sum(len(bl[3]) for bl in blocks)
    b += q(len(blocks)) + q(n) + q(1) + q(n)
    eid = 0
    for dim, tag, typ, elems in blocks:
        b += i(dim) + i(tag) + i(typ) + q(len(elems))
        for e in elems:
            eid += 1
            b += q(eid) + b"".join(q(10 * (v + 1)) for v in e)
    b += b"\n$EndElements\n"
    open(path, "wb").write(b)


def msh2_binary(path):
    pts, tets, regions, tris, _, _ = cube()
    i, d = (lambda v: struct.pack("<i", v)), (lambda v: struct.pack("<d", v))
    b = b"$MeshFormat\n2.2 1 8\n" + i(1) + b"\n$EndMeshFormat\n"
    b += b'$PhysicalNames\n2\n3 10 "corners"\n3 20 "centre"\n$EndPhysicalNames\n'
    b += b"$Nodes\n8\n" + b"".join(i(v + 1) + b"".join(d(c) for c in pts[v]) for v in range(8))
    b += b"\n$EndNodes\n$Elements\n" + str(len(tets) + len(tris)).encode() + b"\n"
    # Triangles: physical 0, elementary = face tag; tets: physical = region.
    b += i(2) + i(len(tris)) + i(2)
    for k, (f, tag) in enumerate(tris):
        b += i(k + 1) + i(0) + i(tag) + b"".join(i(v + 1) for v in f)
    b += i(4) + i(len(tets)) + i(2)
    for k, t in enumerate(tets):
        b += i(len(tris) + k + 1) + i(regions[k]) + i(1 + k // 4) + b"".join(i(v + 1) for v in t)
    b += b"\n$EndElements\n"
    open(path, "wb").write(b)


def vtu_binary(path, header):
    pts, tets, regions, _, _, _ = cube()
    hfmt = "<Q" if header == "UInt64" else "<I"

    def array(fmt, values, separate):
        data = b"".join(struct.pack(fmt, v) for v in values)
        head = struct.pack(hfmt, len(data))
        if separate:
            return (base64.b64encode(head) + base64.b64encode(data)).decode()
        return base64.b64encode(head + data).decode()

    sep = header == "UInt32"
    conn = [v for t in tets for v in t]
    s = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
         f'header_type="{header}">\n<UnstructuredGrid>\n<Piece NumberOfPoints="8" NumberOfCells="5">\n'
         '<Points>\n<DataArray type="Float64" Name="Points" NumberOfComponents="3" format="binary">\n'
         f'{array("<d", [c for p in pts for c in p], sep)}\n</DataArray>\n</Points>\n<Cells>\n'
         f'<DataArray type="Int64" Name="connectivity" format="binary">\n{array("<q", conn, sep)}\n</DataArray>\n'
         f'<DataArray type="Int64" Name="offsets" format="binary">\n{array("<q", [4, 8, 12, 16, 20], sep)}\n</DataArray>\n'
         f'<DataArray type="UInt8" Name="types" format="binary">\n{array("<B", [10] * 5, sep)}\n</DataArray>\n'
         '</Cells>\n<CellData>\n'
         f'<DataArray type="Int32" Name="CellEntityIds" format="binary">\n{array("<i", regions, sep)}\n</DataArray>\n'
         '</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n')
    open(path, "w").write(s)


if __name__ == "__main__":
    msh4_binary(os.path.join(HERE, "cube5_bin.msh"))
    msh2_binary(os.path.join(HERE, "cube5_v2_bin.msh"))
    vtu_binary(os.path.join(HERE, "cube5_bin.vtu"), "UInt64")
    vtu_binary(os.path.join(HERE, "cube5_bin32.vtu"), "UInt32")
