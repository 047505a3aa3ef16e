#!/usr/bin/env bash
# Benchmark of `seamquad smooth` (docs/smooth.md) on the test inputs: two
# QuadriFlow meshes (elephant: 3 folded quads; 3holes) and the Catmull-Clark
# splits (every triangle -> three quads) of helmet, double-torus and 3holes.
# Per input: wall time, outer/Ceres iterations, peak RSS (/usr/bin/time -v),
# and the referee's (check_quad.py --json) quality before and after: mean
# |corner angle - 90|, min scaled Jacobian, mean edge ratio, max vertex
# distance to the surface / diagonal. Prints a markdown table. Usage:
#   bench/bench_smooth.sh [SEAMQUAD_BINARY] [ITERATIONS]
#   (defaults build/bin/seamquad, 10)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/bin/seamquad}
it=${2:-10}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=$shared/data
referee=$shared/tools/check_quad.py
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

split() { # MESH OUT.obj: corner, two edge midpoints, centroid per triangle
  python3 - "$1" "$2" <<'PY'
import sys
path = sys.argv[1]
V, F = [], []
if path.endswith('.off'):
    t = [w for l in open(path) for w in l.split('#')[0].split()]
    i = 1 if t[0] == 'OFF' else 0
    nv, nf = int(t[i]), int(t[i + 1]); i += 3
    V = [[float(x) for x in t[i + 3 * k:i + 3 * k + 3]] for k in range(nv)]; i += 3 * nv
    for _ in range(nf):
        k = int(t[i]); F.append([int(x) for x in t[i + 1:i + 1 + k]]); i += 1 + k
else:
    for l in open(path):
        w = l.split()
        if w and w[0] == 'v': V.append([float(x) for x in w[1:4]])
        elif w and w[0] == 'f': F.append([int(x.split('/')[0]) - 1 for x in w[1:]])
out, edge, Q = [list(v) for v in V], {}, []
def mid(a, b):
    k = (min(a, b), max(a, b))
    if k not in edge:
        edge[k] = len(out); out.append([(V[a][j] + V[b][j]) / 2 for j in range(3)])
    return edge[k]
for f in F:
    g = len(out); out.append([sum(V[v][j] for v in f) / 3 for j in range(3)])
    for j in range(3):
        a, b, p = f[j], f[(j + 1) % 3], f[(j + 2) % 3]
        Q.append((a, mid(a, b), g, mid(p, a)))
with open(sys.argv[2], 'w') as o:
    o.writelines('v %.17g %.17g %.17g\n' % tuple(v) for v in out)
    o.writelines('f %d %d %d %d\n' % tuple(x + 1 for x in q) for q in Q)
PY
}

echo "| input | quads | iterations (Ceres) | time s | peak RSS MiB | mean abs(a-90) deg | min sJ | edge ratio mean | max dist/diag |"
echo "|---|---|---|---|---|---|---|---|---|"
run() { # NAME QUADS SURFACE
  local name=$1 quads=$2 surf=$3
  /usr/bin/time -v "$bin" smooth "$quads" --surface "$surf" -o "$tmp/$name.obj" --iterations "$it" --json -q \
    >"$tmp/$name.json" 2>"$tmp/$name.time" || { echo "| $name | failed: $(tail -1 "$tmp/$name.time") |"; return; }
  python3 "$referee" "$surf" "$quads" --json "$tmp/$name.b.json" >/dev/null 2>&1 || true
  python3 "$referee" "$surf" "$tmp/$name.obj" --json "$tmp/$name.a.json" >/dev/null 2>&1 || true
  python3 - "$name" "$tmp/$name.json" "$tmp/$name.time" "$tmp/$name.b.json" "$tmp/$name.a.json" <<'PY'
import json, re, sys
name, s, t = sys.argv[1], json.load(open(sys.argv[2])), open(sys.argv[3]).read()
b, a = json.load(open(sys.argv[4])), json.load(open(sys.argv[5]))
rss = int(re.search(r'Maximum resident set size \(kbytes\): (\d+)', t).group(1)) / 1024
wall = re.search(r'Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)', t).group(1)
sec = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall.split(':'))))
qb, qa = b['quality'], a['quality']
d = lambda j: j['fidelity']['quad_vertices_to_input']['max_rel']
print('| %s | %d | %d (%d) | %.1f | %.0f | %.3f -> %.3f | %.4f -> %.4f | %.4f -> %.4f | %.1e -> %.1e%s |' % (
    name, a['topology']['F'] if 'F' in a['topology'] else s['after']['quads'] if 'quads' in s['after'] else 0,
    s['iterations'], s['solver_iterations'], sec, rss,
    qb['angle_mean_abs_dev_from_90_deg'], qa['angle_mean_abs_dev_from_90_deg'],
    qb['scaled_jacobian_min'], qa['scaled_jacobian_min'], qb['edge_ratio_mean'], qa['edge_ratio_mean'],
    d(b), d(a), '' if a['passed'] else ' REFEREE FAILS'))
PY
}
run elephant_qf "$data/quads/elephant_quadriflow5k.obj" "$data/cid/elephant.obj"
run 3holes_qf "$data/quads/3holes_quadriflow5k.obj" "$data/libigl/3holes.off"
split "$data/mpz/helmet.obj" "$tmp/helmet_in.obj"
run helmet_split "$tmp/helmet_in.obj" "$data/mpz/helmet.obj"
split "$data/gpjs/double-torus.obj" "$tmp/dt_in.obj"
run double_torus_split "$tmp/dt_in.obj" "$data/gpjs/double-torus.obj"
split "$data/libigl/3holes.off" "$tmp/3holes_in.obj"
run 3holes_split "$tmp/3holes_in.obj" "$data/libigl/3holes.off"
