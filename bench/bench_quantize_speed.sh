#!/usr/bin/env bash
# Speed of quantize + extract on inputs of about 50,000 faces at 5K quads
# (issue: "under 1 s for a 50K-face input"). The inputs are published mpz
# maps split 1-to-4 by bench/subdivide_map.py (same surface, same map, same
# cones): genus3 (13,312 -> 53,248 faces) and holes3 (11,776 -> 47,104).
#
#   bench/bench_quantize_speed.sh [REPS]      (default 3)
#
# For each input, quantize with steps 0 and 5 (the optimizations before and
# after quantization, the default) and without them (--prepare off
# --optimize off: the fast path), then extract; the best of REPS runs of each command's
# own --json total (wall seconds), the quads, and the referee's verdict and
# mean |angle - 90| (check_quad.py --cones on the last run). SQ_BIN selects
# the binary.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
reps=${1:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

best() { python3 -c "import sys; print('%.3f' % min(float(x) for x in sys.argv[1:]))" "$@"; }
total() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['time_s']['total'])" "$1"; }

echo "| input | faces | steps 0 and 5 | quads | valid | mean abs(angle-90) | quantize s | extract s | total s |"
echo "|---|---|---|---|---|---|---|---|---|"
for m in genus3 holes3; do
  python3 "$root/bench/subdivide_map.py" "$shared/data/mpz/$m.obj" "$tmp/$m.obj" || exit 1
  # the same cones: the new vertices are flat (2 pi)
  nv=$(grep -c '^v ' "$tmp/$m.obj")
  python3 -c "
import sys
th = open(sys.argv[1]).read().split()
th += ['6.283185307179586'] * (int(sys.argv[2]) - len(th))
open(sys.argv[3], 'w').write('\n'.join(th) + '\n')" "$shared/data/mpz/${m}_Th_hat" "$nv" "$tmp/$m.cones"
  faces=$(grep -c '^f ' "$tmp/$m.obj")
  for opt in on off; do
    tq=() tx=()
    for ((r = 0; r < reps; r++)); do
      "$bin" quantize "$tmp/$m.obj" --map "$tmp/$m.obj" --cones "$tmp/$m.cones" --quads 5000 \
        --prepare $opt --optimize $opt -o "$tmp/igm.obj" --json >"$tmp/q.json" || exit 1
      "$bin" extract "$tmp/$m.obj" "$tmp/igm.obj" -o "$tmp/quads.obj" --json >"$tmp/x.json" || exit 1
      tq+=("$(total "$tmp/q.json")") tx+=("$(total "$tmp/x.json")")
    done
    quads=$(grep -c '^f ' "$tmp/quads.obj")
    verdict=FAIL
    python3 "$shared/tools/check_quad.py" "$tmp/$m.obj" "$tmp/quads.obj" --cones "$tmp/$m.cones" \
      --json "$tmp/ref.json" >/dev/null 2>&1 && verdict=PASS
    ang=$(python3 -c "import json; print('%.2f' % json.load(open('$tmp/ref.json'))['quality']['angle_mean_abs_dev_from_90_deg'])")
    bq=$(best "${tq[@]}") bx=$(best "${tx[@]}")
    echo "| $m x4 | $faces | $opt | $quads | $verdict | $ang | $bq | $bx | $(python3 -c "print('%.3f' % ($bq + $bx))") |"
  done
done
