#!/usr/bin/env bash
# Benchmark of `seamquad optimize` (free translations) on seamless maps of
# ../shared/data/mpz: the published map stored in each OBJ (its vt), and
# with SQ_BENCH_PARAM=1 also `seamquad param`'s map of the same cones,
# through `optimize` (the whole map) and through `param --optimize on`
# (rounds of the optimizer, each followed by param's simplification;
# faces before -> after). SQ_BENCH_PARAM=rounds: the published map and
# the rounds only.
#
#   bench/bench_optimize.sh [MODEL ...]     (default: the 16 mpz models)
#
# Prints one markdown row per map: faces, the referee's figures before and
# after (shared/tools/check_param.py: mean and max sigma1/sigma2, mean
# symmetric Dirichlet, after its global scale), Newton iterations, why it
# stopped, and the optimize command's own time (--json). SQ_BIN selects the
# binary; SQ_ITERATIONS caps the iterations (default: the command's, 100).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=$shared/data/mpz
models=("$@")
[ ${#models[@]} = 0 ] && models=(block cup eight elk fandisk femur fertility_tri genus3 helmet holes3 homer
  knot1 rocker_arm sculpt trim-star twirl)
iters=()
[ -n "${SQ_ITERATIONS:-}" ] && iters=(--iterations "$SQ_ITERATIONS")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

figures() { # MESH CONES MAP -> "conf_mean conf_max sd_mean" or "FAIL - -"
  if python3 "$shared/tools/check_param.py" "$1" "$2" "$3" --json "$tmp/ref.json" >/dev/null 2>&1; then
    python3 -c "import json; d = json.load(open('$tmp/ref.json'))['f_stats']; print('%.3g %.3g %.3g' % (d['conformal_mean'], d['conformal_max'], d['sym_dirichlet_mean']))"
  else
    echo "FAIL - -"
  fi
}

row() { # NAME KIND MESH CONES MAP
  local name=$1 kind=$2 mesh=$3 cones=$4 map=$5
  local faces before after
  faces=$(grep -c '^f ' "$map")
  before=$(figures "$mesh" "$cones" "$map")
  if "$bin" optimize "$mesh" --map "$map" --cones "$cones" -o "$tmp/out.obj" "${iters[@]}" --json \
      >"$tmp/o.json" 2>"$tmp/err"; then
    after=$(figures "$mesh" "$cones" "$tmp/out.obj")
    read -r it why secs < <(python3 -c "import json; j = json.load(open('$tmp/o.json')); print(j['iterations'], j['stopped'].split(' (')[0].replace(' ', '_'), '%.2f' % j['time_s']['optimize'])")
    echo "| $name | $kind | $faces | ${before// / | } | ${after// / | } | $it | ${why//_/ } | $secs |"
  else
    echo "| $name | $kind | $faces | ${before// / | } | error: $(tail -1 "$tmp/err" | cut -c1-80) | | | | | |"
  fi
}

rounds_row() { # NAME MESH CONES: param --optimize on
  local name=$1 mesh=$2 cones=$3 before after
  if "$bin" param "$mesh" --cones "$cones" -o "$tmp/rounds.obj" --optimize on "${iters[@]}" --json \
      >"$tmp/r.json" 2>"$tmp/err"; then
    after=$(figures "$mesh" "$cones" "$tmp/rounds.obj")
    read -r fb fa cb it why secs < <(python3 -c "import json; o = json.load(open('$tmp/r.json'))['optimize']; print(o['faces_before'], o['faces_after'], '%.3g' % o['conformal_before'], o['iterations'], o['stopped'].split(' (')[0].replace(' ', '_'), '%.2f' % o['seconds'])")
    echo "| $name | param --optimize on | $fb -> $fa | $cb | | | ${after// / | } | $it | ${why//_/ } | $secs |"
  else
    echo "| $name | param --optimize on | error: $(tail -1 "$tmp/err" | cut -c1-80) | | | | | | | | | |"
  fi
}

echo "| model | map | faces | conf. mean | conf. max | SD mean | opt. conf. mean | opt. conf. max | opt. SD mean | iterations | stopped | s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for m in "${models[@]}"; do
  mesh=$data/$m.obj
  cones=$data/${m}_Th_hat
  row "$m" published "$mesh" "$cones" "$mesh"
  if [ "${SQ_BENCH_PARAM:-0}" = 1 ]; then
    if "$bin" param "$mesh" --cones "$cones" -o "$tmp/param.obj" --quiet >/dev/null 2>"$tmp/err"; then
      row "$m" param "$mesh" "$cones" "$tmp/param.obj"
    else
      echo "| $m | param | param failed: $(tail -1 "$tmp/err" | cut -c1-80) | | | | | | | | | |"
    fi
  fi
  if [ "${SQ_BENCH_PARAM:-0}" = 1 ] || [ "${SQ_BENCH_PARAM:-0}" = rounds ]; then
    rounds_row "$m" "$mesh" "$cones"
  fi
done
