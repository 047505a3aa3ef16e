#!/usr/bin/env bash
# Smoothing with and without fidelity pins (docs/smooth.md, "Fidelity"):
# the published map of each mpz model through `seamquad optimize`,
# `quantize --quads N --optimize off` and `extract`, then `smooth` with
# `--pin-threshold 0` and with the default; both outputs through
# check_quad.py --cones. Prints a markdown table: mean |angle - 90|, min
# scaled Jacobian and the widest input-vertex-to-quads gap (the referee's
# input_vertices_to_quad max, relative to the diagonal), and the smoothing
# time. Usage:
#   bench/bench_pins.sh [N] [MODEL...]     (defaults: 5000, the 15 mpz models)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=$shared/data/mpz
referee=$shared/tools/check_quad.py
n=${1:-5000}
shift || true
models=${*:-block cup eight elk fandisk femur fertility_tri genus3 helmet holes3 homer knot1 rocker_arm sculpt trim-star}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "| model | quads | pins | valid | mean abs(angle-90) | min sJ | gap | smooth s |"
echo "|---|---|---|---|---|---|---|---|"
for m in $models; do
  mesh=$data/$m.obj cones=$data/${m}_Th_hat
  "$bin" optimize "$mesh" --cones "$cones" --map "$mesh" -o "$tmp/opt.obj" -q >/dev/null 2>&1 &&
    "$bin" quantize "$mesh" --map "$tmp/opt.obj" --cones "$cones" --quads "$n" --optimize off \
      -o "$tmp/igm.obj" -q >/dev/null 2>&1 &&
    "$bin" extract "$mesh" "$tmp/igm.obj" -o "$tmp/q.obj" -q >/dev/null 2>&1 ||
    { echo "| $m | failed before smoothing |"; continue; }
  for t in 0 default; do
    opt=()
    [ "$t" = 0 ] && opt=(--pin-threshold 0)
    "$bin" smooth "$tmp/q.obj" --surface "$mesh" -o "$tmp/s.obj" "${opt[@]}" --json -q >"$tmp/s.json" 2>&1 ||
      { echo "| $m | | $t | smooth failed |"; continue; }
    python3 "$referee" "$mesh" "$tmp/s.obj" --cones "$cones" --json "$tmp/c.json" >/dev/null 2>&1 || true
    python3 - "$m" "$t" "$tmp/s.json" "$tmp/c.json" <<'PY'
import json, sys
m, t, s, c = sys.argv[1], sys.argv[2], json.load(open(sys.argv[3])), json.load(open(sys.argv[4]))
q = c['quality']
gap = c['fidelity']['input_vertices_to_quad']['max_rel']
pins = "off" if t == "0" else "%d" % s.get('pinned', 0)
print("| %s | %d | %s | %s | %.2f | %.3f | %.4f | %.2f |" % (m, s['quads'], pins, "PASS" if c['passed'] else "FAIL",
      q['angle_mean_abs_dev_from_90_deg'], q['scaled_jacobian_min'], gap, s['smooth_s']))
PY
  done
done
