#!/usr/bin/env python3
"""Splits every triangle of a mesh with a seamless map (OBJ: v, vt, f v/vt)
into four at its edge midpoints, in 3D and in the map, and writes the result.

The surface is the same piecewise-linear surface, the map the same map (the
midpoint of a seam edge on either side is the image of the same surface
point under the same transition), the cones the same vertices (each new
vertex is flat: its UV angles sum to 2 pi). bench/bench_quantize_speed.sh
uses it to make inputs of about 50,000 faces from the published maps.

    bench/subdivide_map.py IN.obj OUT.obj
"""
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    verts, uvs, faces = [], [], []
    with open(sys.argv[1]) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                verts.append(t[1:4])
            elif t[0] == "vt":
                uvs.append(t[1:3])
            elif t[0] == "f":
                if len(t) != 4:
                    sys.exit("%s: only triangles are split" % sys.argv[1])
                c = [x.split("/") for x in t[1:]]
                faces.append([(int(a[0]) - 1, int(a[1]) - 1) for a in c])
    # exact midpoints are not needed: the inputs are made exact by quantize
    v = [[float(x) for x in p] for p in verts]
    t = [[float(x) for x in p] for p in uvs]
    vmid, tmid = {}, {}

    def mid(table, pts, i, j):
        key = (min(i, j), max(i, j))
        if key not in table:
            table[key] = len(pts)
            pts.append([(a + b) / 2 for a, b in zip(pts[i], pts[j])])
        return table[key]

    out = []
    for f in faces:
        m = [(mid(vmid, v, f[k][0], f[(k + 1) % 3][0]), mid(tmid, t, f[k][1], f[(k + 1) % 3][1]))
             for k in range(3)]
        out.append([f[0], m[0], m[2]])
        out.append([f[1], m[1], m[0]])
        out.append([f[2], m[2], m[1]])
        out.append([m[0], m[1], m[2]])
    with open(sys.argv[2], "w") as g:
        for p in v:
            g.write("v %.17g %.17g %.17g\n" % tuple(p))
        for p in t:
            g.write("vt %.17g %.17g\n" % tuple(p))
        for f in out:
            g.write("f %d/%d %d/%d %d/%d\n" % tuple(x + 1 for c in f for x in c))


if __name__ == "__main__":
    main()
