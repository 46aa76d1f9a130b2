#!/usr/bin/env python3
"""Save a TetGen .node/.ele pair as a Gmsh msh 2.2 file (tets only, region
attribute as physical and elementary tag) so that gmshToFoam can read it.
Used by bench/peer_files.sh; untimed preprocessing.
    ele_to_msh22.py MESH.ele OUT.msh"""
import sys


def records(path):
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0].split()
            if line:
                yield line


def main(ele, out):
    node_rows = records(ele[:-4] + '.node')
    n, _dim, nattr, nmark = map(int, next(node_rows))
    nodes = [next(node_rows)[:4] for _ in range(n)]
    ele_rows = records(ele)
    m, _per, attrs = map(int, next(ele_rows))
    with open(out, 'w') as f:
        f.write('$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n' % n)
        shift = 1 - int(nodes[0][0])  # TetGen numbers from 0 or 1; msh from 1
        for row in nodes:
            f.write('%d %s\n' % (int(row[0]) + shift, ' '.join(row[1:])))
        f.write('$EndNodes\n$Elements\n%d\n' % m)
        for k in range(m):
            row = next(ele_rows)
            region = int(float(row[5])) if attrs else 1
            ids = ' '.join(str(int(v) + shift) for v in row[1:5])
            f.write('%d 4 2 %d %d %s\n' % (k + 1, region, region, ids))
        f.write('$EndElements\n')
    del nattr, nmark


if __name__ == '__main__':
    main(*sys.argv[1:3])
