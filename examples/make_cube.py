#!/usr/bin/env python3
"""Writes examples/cube.obj (the surface of [-1,1]^3, each face an n x n grid
of squares split into triangles, outward orientation) and examples/cube.cones
(its eight corners as valence-3 cones, in seamquad's cone-list format)."""
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 6
index = {}
verts = []


def vid(p):
    key = tuple(round(c * n) for c in p)
    if key not in index:
        index[key] = len(verts)
        verts.append(p)
    return index[key]


faces = []
for axis in range(3):
    for sign in (-1, 1):
        u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
        if sign < 0:
            u_axis, v_axis = v_axis, u_axis
        for i in range(n):
            for j in range(n):
                def at(a, b):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = float(sign)
                    p[u_axis] = -1 + 2 * a / n
                    p[v_axis] = -1 + 2 * b / n
                    return vid(tuple(p))
                a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
                faces.append((a, b, c))
                faces.append((a, c, d))

with open("cube.obj", "w") as f:
    f.write("# seamquad example: cube surface, %d x %d squares per side\n" % (n, n))
    for p in verts:
        f.write("v %g %g %g\n" % p)
    for t in faces:
        f.write("f %d %d %d\n" % tuple(i + 1 for i in t))

with open("cube.cones", "w") as f:
    f.write("# seamquad cone list: VERTEX VALENCE (0-based vertex index)\n")
    f.write("# the eight corners of the cube: angle 3*pi/2, valence 3\n")
    for key, i in sorted(index.items(), key=lambda kv: kv[1]):
        if all(abs(k) == n for k in key):
            f.write("%d 3\n" % i)
