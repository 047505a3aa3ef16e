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
  python3 "$root/scripts/quad_split.py" "$1" "$2"
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
