#!/usr/bin/env python3
"""Random admissible cone set for a closed triangle mesh (stdlib only).

usage: random_cones.py MESH OUT_Th_hat [--seed N] [--pairs N]

Picks random distinct vertices and valences whose total excess satisfies
Gauss-Bonnet, sum over cones of (4 - k) = 4 * chi: |4 chi| cones of valence 3
(chi > 0) or 5 (chi < 0), some of them merged two by two into valence 2 or 6,
plus a few cancelling 3/5 pairs. Never valence 1, never the torus with
exactly one 3 and one 5 (no quad mesh exists). Writes a Th_hat file (one
angle k*pi/2 per vertex, in vertex order), the format of
../shared/tools/check_param.py, and prints the valences on stdout.
"""
import argparse
import math
import random
import sys


def read_mesh(path):
    nv, faces = 0, []
    with open(path, encoding="utf-8", errors="replace") as fh:
        lines = fh.read().splitlines()
    if path.lower().endswith(".off"):
        body = [l.split("#", 1)[0].split() for l in lines]
        body = [b for b in body if b]
        head = body[0]
        counts = head[1:] if len(head) > 1 else body[1]
        start = 1 if len(head) > 1 else 2
        nv, nf = int(counts[0]), int(counts[1])
        for b in body[start + nv:start + nv + nf]:
            faces.append([int(x) for x in b[1:1 + int(b[0])]])
    else:
        for l in lines:
            t = l.split()
            if not t:
                continue
            if t[0] == "v":
                nv += 1
            elif t[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in t[1:]])
    edges = set()
    for f in faces:
        for i in range(len(f)):
            a, b = f[i], f[(i + 1) % len(f)]
            edges.add((min(a, b), max(a, b)))
    return nv, nv - len(edges) + len(faces)


def random_valences(chi, rng, pairs):
    genus = (2 - chi) // 2
    target = 4 * chi  # sum of (4 - k)
    while True:
        vals = []
        for _ in range(pairs if pairs is not None else rng.randint(0, 4)):
            vals += [3, 5]
        k = 3 if target > 0 else 5
        run = abs(target)
        while run > 0:
            if run >= 2 and rng.random() < 0.2:
                vals.append(2 if k == 3 else 6)  # two cones merged
                run -= 2
            else:
                vals.append(k)
                run -= 1
        assert sum(4 - v for v in vals) == target
        if genus == 1 and sorted(vals) == [3, 5]:
            pairs = (pairs or 0) + 1  # the torus exception: add a pair
            continue
        return vals


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--pairs", type=int, default=None, help="cancelling 3/5 pairs (default: random 0..4)")
    a = ap.parse_args()
    nv, chi = read_mesh(a.mesh)
    rng = random.Random(a.seed)
    vals = random_valences(chi, rng, a.pairs)
    if len(vals) > nv:
        sys.exit("random_cones: %d cones for %d vertices" % (len(vals), nv))
    angle = [2 * math.pi] * nv
    for v, k in zip(rng.sample(range(nv), len(vals)), vals):
        angle[v] = k * math.pi / 2
    with open(a.out, "w") as fh:
        fh.write("".join("%.17g\n" % x for x in angle))
    print(",".join(str(k) for k in sorted(vals)))


if __name__ == "__main__":
    main()
