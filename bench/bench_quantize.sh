#!/usr/bin/env bash
# Benchmark of quantize + extract on the published seamless maps of
# ../shared/data/mpz (the vt of each OBJ, with its *_Th_hat cones), beside
# QuadriFlow on the same meshes and targets (SQ_BENCH_PEERS=1; its runs take
# 1 to 15 s each).
#
#   bench/bench_quantize.sh [TARGET ...]      (default: 1000 5000 20000)
#
# Each output goes through shared/tools/check_quad.py (--cones for ours).
# Prints one markdown row per model and target: quads (and the fewest the
# T-mesh allows), validity, mean |angle - 90|, min scaled Jacobian, the
# quad surface's largest distance to the input (relative to the diagonal),
# the times of quantize and extract (wall, from the --json reports), and
# the same figures for QuadriFlow. "dist" is the larger of the referee's
# two one-sided vertex distances (quad vertices to the input, input vertices
# to the quads), relative to the diagonal. SQ_BIN selects the binary.
#
# SQ_BENCH_MAP=param: the maps are `seamquad param`'s for the same cones
# (made once per model, default options), not the published ones; the
# QuadriFlow columns are left out. Quantize's step 0 (the optimization of
# the map before quantization) is the same for every target, so it runs
# once per model, as `seamquad optimize --iterations 600` (the same call
# with the same defaults: sq_optimize_map_free_or_fixed), and quantize then
# runs with --prepare off; its time is added to each row's quantize time.
# SQ_BENCH_CACHE=DIR keeps those maps (MODEL.param.obj, MODEL.prep.obj and
# its --json) across runs.
# SQ_BENCH_QUANTIZE_ARGS: more options for quantize (e.g. "--prepare on");
# SQ_BENCH_MODELS: the models to run (default: all 15).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=$shared/data/mpz
peers=${SQ_BENCH_PEERS:-0}
targets=("$@")
[ ${#targets[@]} = 0 ] && targets=(1000 5000 20000)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# referee MESH QUADS [CONES]: "valid angle sj dist" from check_quad.py
referee() {
  local args=("$1" "$2")
  [ -n "${3:-}" ] && args+=(--cones "$3")
  python3 "$shared/tools/check_quad.py" "${args[@]}" --json "$tmp/ref.json" >/dev/null 2>&1
  local rc=$?
  python3 - "$tmp/ref.json" "$rc" <<'PY'
import json, sys
try:
    j = json.load(open(sys.argv[1]))
except Exception:
    print("unreadable - - -"); sys.exit()
q = j.get("quality", {})
f = j.get("fidelity", {})
ang = q.get("angle_mean_abs_dev_from_90_deg", float("nan"))
sj = q.get("scaled_jacobian_min", float("nan"))
# both ways: quad vertices to the input, input vertices to the quads
dist = max(f.get("quad_vertices_to_input", {}).get("max_rel", float("nan")),
           f.get("input_vertices_to_quad", {}).get("max_rel", float("nan")))
print("%s %.2f %.3f %.4f" % ("PASS" if sys.argv[2] == "0" else "FAIL", ang, sj, dist))
PY
}

echo "| model | target | quads (fewest) | valid | mean abs(angle-90) | min sJ | dist | quantize s | extract s | QuadriFlow quads | valid | mean abs(angle-90) | min sJ | dist | s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for n in "${targets[@]}"; do
  for m in ${SQ_BENCH_MODELS:-block cup eight elk fandisk femur fertility_tri genus3 helmet holes3 homer knot1 rocker_arm sculpt trim-star}; do
    mesh=$data/$m.obj
    cones=$data/${m}_Th_hat
    row="| $m | $n |"
    map=$mesh
    extra=() prep=0
    if [ "${SQ_BENCH_MAP:-published}" = param ]; then
      cache=${SQ_BENCH_CACHE:-$tmp}
      map=$cache/$m.param.obj
      if [ ! -s "$map" ] && ! "$bin" param "$mesh" --cones "$cones" -o "$map" --quiet >/dev/null 2>"$tmp/err"; then
        echo "$row param failed: $(tail -1 "$tmp/err" | cut -c1-80) | | | | | | |"
        continue
      fi
      if [ ! -s "$cache/$m.prep.obj" ] && ! "$bin" optimize "$mesh" --map "$map" --iterations 600 \
          -o "$cache/$m.prep.obj" --json >"$cache/$m.prep.json" 2>"$tmp/err"; then
        echo "$row step 0 failed: $(tail -1 "$tmp/err" | cut -c1-80) | | | | | | |"
        continue
      fi
      map=$cache/$m.prep.obj extra=(--prepare off)
      prep=$(python3 -c "import json; print(json.load(open('$cache/$m.prep.json'))['time_s']['optimize'])")
    fi
    # shellcheck disable=SC2086
    if "$bin" quantize "$mesh" --map "$map" --cones "$cones" --quads "$n" -o "$tmp/igm.obj" --json "${extra[@]}" ${SQ_BENCH_QUANTIZE_ARGS:-} \
        >"$tmp/q.json" 2>"$tmp/err" &&
      "$bin" extract "$mesh" "$tmp/igm.obj" -o "$tmp/quads.obj" --json >"$tmp/x.json" 2>>"$tmp/err"; then
      read -r quads least tq tx < <(python3 -c "
import json
q = json.load(open('$tmp/q.json')); x = json.load(open('$tmp/x.json'))
print(int(q['quads']), int(q['min_quads']), '%.3f' % (q['time_s']['total'] + $prep), '%.3f' % x['time_s']['total'])")
      read -r valid ang sj dist < <(referee "$mesh" "$tmp/quads.obj" "$cones")
      row="$row $quads ($least) | $valid | $ang | $sj | $dist | $tq | $tx |"
    else
      row="$row failed: $(tail -1 "$tmp/err" | cut -c1-80) | | | | | | |"
    fi
    if [ "$peers" = 1 ]; then
      line=$("$shared/peers/run_peer.sh" quadriflow "$mesh" "$n" "$tmp/qf.obj" 2>/dev/null | tail -1)
      if [ -s "$tmp/qf.obj" ]; then
        secs=$(echo "$line" | sed -n 's/.*seconds=\([0-9.]*\).*/\1/p')
        read -r valid ang sj dist < <(referee "$mesh" "$tmp/qf.obj")
        row="$row $(grep -c '^f ' "$tmp/qf.obj") | $valid | $ang | $sj | $dist | $secs |"
      else
        row="$row failed | | | | | |"
      fi
      rm -f "$tmp/qf.obj"
    else
      row="$row - | | | | | |"
    fi
    echo "$row"
  done
done
