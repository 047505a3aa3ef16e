#!/usr/bin/env python3
"""Writes the small broken inputs of tests/data/broken/ (each violates one
rule; see EXPECTED.tsv) and the valid tests/data/torus.obj. Re-run after a
change; the outputs are committed."""
import math
import os

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.join(here, "broken")

TETRA_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def write_obj(name, verts, faces, comment):
    with open(os.path.join(out, name), "w") as f:
        f.write("# %s\n" % comment)
        for v in verts:
            f.write("v %s\n" % " ".join(repr(float(c)) if isinstance(c, float) else str(c) for c in v))
        for t in faces:
            f.write("f %s\n" % " ".join(str(i + 1) for i in t))


def shifted(faces, k):
    return [tuple(i + k for i in t) for t in faces]


def moved(verts, dx):
    return [(x + dx, y, z) for (x, y, z) in verts]


write_obj("flipped_face.obj", TETRA_V, TETRA_F[:3] + [(1, 3, 2)],
          "tetrahedron whose last face is flipped")
write_obj("two_components.obj", TETRA_V + moved(TETRA_V, 5), TETRA_F + shifted(TETRA_F, 4),
          "two disjoint tetrahedra")
# Bow-tie: second tetrahedron shares vertex 0 with the first.
bt_v = TETRA_V + [(-1, 0, 0), (0, -1, 0), (0, 0, -1)]
# the mirrored tetrahedron needs reversed faces to stay consistently oriented
bt_f = TETRA_F + [tuple({0: 0, 1: 4, 2: 5, 3: 6}[i] for i in reversed(t)) for t in TETRA_F]
write_obj("bowtie.obj", bt_v, bt_f, "two tetrahedra touching at vertex 0 (bow-tie)")
# Non-manifold edge: two tetrahedra sharing edge (0, 1).
nm_v = TETRA_V + [(0.5, -1, 0.3), (0.5, -0.5, -1)]
nm_f = TETRA_F + [tuple({0: 0, 1: 1, 2: 4, 3: 5}[i] for i in reversed(t)) for t in TETRA_F]
write_obj("nonmanifold_edge.obj", nm_v, nm_f, "two tetrahedra sharing edge (0, 1)")
# Exactly degenerate face: vertex 4 is the exact midpoint of edge (0, 1).
dg_v = [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2), (1, 0, 0)]
dg_f = [(0, 2, 4), (4, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3), (0, 4, 1)]
write_obj("degenerate_face.obj", dg_v, dg_f, "closed mesh with one zero-area face (0, 4, 1)")
write_obj("open.obj", TETRA_V, TETRA_F[:3], "tetrahedron without its last face")
write_obj("repeated_vertex.obj", TETRA_V, TETRA_F[:3] + [(1, 2, 2)],
          "a face that uses vertex 2 twice")
write_obj("unreferenced_vertex.obj", TETRA_V + [(3, 3, 3)], TETRA_F,
          "tetrahedron plus a vertex no face uses")
cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
cube_f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
write_obj("polygon.obj", cube_v, cube_f, "a cube made of quads: not a triangle mesh")


def torus(n, m, R=2.0, r=0.7):
    verts, faces = [], []
    for i in range(n):
        for j in range(m):
            u, v = 2 * math.pi * i / n, 2 * math.pi * j / m
            verts.append((round((R + r * math.cos(v)) * math.cos(u), 6),
                          round((R + r * math.cos(v)) * math.sin(u), 6),
                          round(r * math.sin(v), 6)))
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            faces.append((a, b, c))
            faces.append((a, c, d))
    return verts, faces


tv, tf = torus(12, 8)
with open(os.path.join(here, "torus.obj"), "w") as f:
    f.write("# seamquad test mesh: torus, 12 x 8 grid (genus 1)\n")
    for v in tv:
        f.write("v %g %g %g\n" % v)
    for t in tf:
        f.write("f %d %d %d\n" % tuple(i + 1 for i in t))

with open(os.path.join(out, "torus_3_5.cones"), "w") as f:
    f.write("# torus with one valence-3 and one valence-5 cone: no quad mesh exists\n0 3\n40 5\n")
with open(os.path.join(out, "torus_gauss_bonnet.cones"), "w") as f:
    f.write("# torus with a single valence-3 cone: violates Gauss-Bonnet\n7 3\n")
with open(os.path.join(out, "valence1.cones"), "w") as f:
    f.write("# cube: a valence-1 cone at 13 and five valence-3 corners (Gauss-Bonnet holds)\n")
    f.write("13 1\n0 3\n42 3\n48 3\n49 3\n62 3\n")
# Th_hat files for examples/cube.obj (n = 6: 6*36 + 2 = 218 vertices).
corners = {0, 13, 42, 48, 49, 62, 91, 97}
NV = 218
with open(os.path.join(out, "cube_wrong_count_Th_hat"), "w") as f:
    for v in range(NV - 1):
        f.write("%.17g\n" % (1.5 * math.pi if v in corners else 2 * math.pi))
with open(os.path.join(out, "cube_off_grid_Th_hat"), "w") as f:
    for v in range(NV):
        a = 1.5 * math.pi if v in corners else 2 * math.pi
        if v == 5:
            a = 6.2
        f.write("%.17g\n" % a)
with open(os.path.join(here, "cube_Th_hat"), "w") as f:
    for v in range(NV):
        f.write("%.17g\n" % (1.5 * math.pi if v in corners else 2 * math.pi))
