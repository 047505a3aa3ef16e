#!/usr/bin/env python3
"""Three quads per triangle: the Catmull-Clark split of a triangle mesh
(stdlib only).

usage: quad_split.py IN OUT

IN is a triangle mesh (OBJ or OFF, by extension); OUT is written as an OBJ
quad mesh. Every triangle (a, b, c) gets its centroid g and every edge its
midpoint (shared by the two triangles of the edge); the triangle becomes the
three quads (corner, midpoint of the next edge, g, midpoint of the previous
edge), as in stages/tests/test_smooth.c. The input vertices keep their
indices; midpoints and centroids follow. Used by tests/cli_smooth.sh and
bench/bench_smooth.sh.
"""
import sys


def read_mesh(path):
    V, F = [], []
    if path.endswith('.off'):
        t = [w for l in open(path) for w in l.split('#')[0].split()]
        i = 1 if t[0] == 'OFF' else 0
        nv, nf = int(t[i]), int(t[i + 1])
        i += 3
        V = [[float(x) for x in t[i + 3 * k:i + 3 * k + 3]] for k in range(nv)]
        i += 3 * nv
        for _ in range(nf):
            k = int(t[i])
            F.append([int(x) for x in t[i + 1:i + 1 + k]])
            i += 1 + k
    else:
        for l in open(path):
            w = l.split()
            if w and w[0] == 'v':
                V.append([float(x) for x in w[1:4]])
            elif w and w[0] == 'f':
                F.append([int(x.split('/')[0]) - 1 for x in w[1:]])
    return V, F


def quad_split(V, F, name):
    out, edge, Q = [list(v) for v in V], {}, []

    def mid(a, b):
        k = (min(a, b), max(a, b))
        if k not in edge:
            edge[k] = len(out)
            out.append([(V[a][j] + V[b][j]) / 2 for j in range(3)])
        return edge[k]

    for n, f in enumerate(F):
        if len(f) != 3:
            sys.exit('%s: face %d has %d vertices: not a triangle mesh' % (name, n, len(f)))
        g = len(out)
        out.append([sum(V[v][j] for v in f) / 3 for j in range(3)])
        for j in range(3):
            a, b, p = f[j], f[(j + 1) % 3], f[(j + 2) % 3]
            Q.append((a, mid(a, b), g, mid(p, a)))
    return out, Q


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    V, F = read_mesh(argv[1])
    out, Q = quad_split(V, F, argv[1])
    with open(argv[2], 'w') as o:
        o.writelines('v %.17g %.17g %.17g\n' % tuple(v) for v in out)
        o.writelines('f %d %d %d %d\n' % tuple(x + 1 for x in q) for q in Q)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
