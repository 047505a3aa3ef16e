#!/usr/bin/env bash
# Benchmark of `seamquad remesh` (a triangle mesh in, a quad mesh out) beside
# QuadriFlow and Instant Meshes (../shared/peers/run_peer.sh, one thread
# each) on the same meshes and targets.
#
#   bench/bench_remesh.sh [MESH[:CONES] ...]
#
# MESH is relative to ../shared/data; CONES (a file beside it) is given to
# seamquad, else seamquad takes its cones from the cross field. Default: the
# 15 accepted mpz models with their *_Th_hat cones. Environment:
#   SQ_BENCH_TARGETS  quad targets (default "5000")
#   SQ_BENCH_PEERS    1: run the peers too (default 1)
#   SQ_BENCH_ITER     seamquad's optimizer iterations (default: remesh's)
#   SQ_BENCH_ARGS     more arguments for seamquad remesh (e.g. "--param never")
#   SQ_BENCH_MAP      1: seamquad starts from the seamless map stored in MESH
#                     (its vt: the published maps of mpz/*.obj) with
#                     `--map MESH`, instead of param's (default 0)
#   SQ_BIN            the seamquad binary
#
# Every output goes through shared/tools/check_quad.py (--cones for ours when
# a cone file is given). One markdown row per tool, mesh and target: quads,
# valid (PASS/FAIL of the referee: closed, manifold, genus, pure quads,
# nothing folded, no self-intersection, and for ours the irregular vertices
# = the cones), the
# irregular vertex count, mean |angle - 90|, min angle, min scaled
# Jacobian, the largest distance both ways relative to the diagonal, wall
# time and peak memory (GNU time).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
peers=${SQ_BENCH_PEERS:-1}
targets=${SQ_BENCH_TARGETS:-5000}
iter=${SQ_BENCH_ITER:-}
read -r -a extra <<<"${SQ_BENCH_ARGS:-}"
models=("$@")
if [ ${#models[@]} = 0 ]; then
  # smallest param maps first (the larger take minutes each)
  for m in eight knot1 helmet sculpt holes3 cup block genus3 fandisk fertility_tri femur rocker_arm trim-star homer elk; do
    models+=("mpz/$m.obj:${m}_Th_hat")
  done
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# referee MESH QUADS [CONES]: "valid irregular angle minangle sj dist"
referee() {
  local args=("$1" "$2")
  [ -n "${3:-}" ] && args+=(--cones "$3")
  python3 "$shared/tools/check_quad.py" "${args[@]}" --self-intersections --json "$tmp/ref.json" >/dev/null 2>&1
  local rc=$?
  python3 - "$tmp/ref.json" "$rc" <<'PY'
import json, sys
try:
    j = json.load(open(sys.argv[1]))
except Exception:
    print("unreadable - - - - -"); sys.exit()
q, f = j.get("quality", {}), j.get("fidelity", {})
irr = j.get("valence", {}).get("irregular_vertices", "-")
dist = max(f.get("quad_vertices_to_input", {}).get("max_rel", float("nan")),
           f.get("input_vertices_to_quad", {}).get("max_rel", float("nan")))
print("%s %s %.2f %.2f %.3f %.4f" % ("PASS" if sys.argv[2] == "0" else "FAIL", irr,
      q.get("angle_mean_abs_dev_from_90_deg", float("nan")), q.get("angle_min_deg", float("nan")),
      q.get("scaled_jacobian_min", float("nan")), dist))
PY
}

# timed OUT_PREFIX CMD...: runs CMD under GNU time; "seconds peak_mb"
timed() {
  local pre=$1
  shift
  /usr/bin/time -f "%e %M" -o "$pre.time" "$@" >"$pre.out" 2>"$pre.err"
  local rc=$?
  read -r secs kb < <(tail -1 "$pre.time" 2>/dev/null) || true
  case "$secs$kb" in *[!0-9.]*|"") secs=- kb=0 ;; esac
  echo "$rc $secs $((kb / 1024))"
}

echo "| mesh | cones | target | tool | quads | valid | irregular | mean abs(angle-90) | min angle | min sJ | dist | s | MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for spec in "${models[@]}"; do
  rel=${spec%%:*}
  mesh=$shared/data/$rel
  cones=
  [ "$spec" != "$rel" ] && cones=$(dirname "$mesh")/${spec#*:}
  name=$(basename "$rel")
  for n in $targets; do
    args=(remesh "$mesh" --quads "$n" -o "$tmp/sq.obj" --quiet)
    [ -n "$cones" ] && args+=(--cones "$cones")
    [ -n "$iter" ] && args+=(--iterations "$iter")
    args+=("${extra[@]}")
    [ "${SQ_BENCH_MAP:-0}" = 1 ] && args+=(--map "$mesh")
    read -r rc secs mb < <(timed "$tmp/sq" "$bin" "${args[@]}")
    ctag=$([ -n "$cones" ] && basename "$cones" || echo field)
    [ "${SQ_BENCH_MAP:-0}" = 1 ] && ctag="$ctag, its vt"
    if [ "$rc" = 0 ]; then
      read -r valid irr ang amin sj dist < <(referee "$mesh" "$tmp/sq.obj" "$cones")
      echo "| $name | $ctag | $n | seamquad | $(grep -c '^f ' "$tmp/sq.obj") | $valid | $irr | $ang | $amin | $sj | $dist | $secs | $mb |"
    else
      echo "| $name | $ctag | $n | seamquad | failed: $(tail -1 "$tmp/sq.err" | cut -c1-90) | | | | | | | $secs | $mb |"
    fi
    rm -f "$tmp/sq.obj"
    [ "$peers" = 1 ] || continue
    for peer in quadriflow instant-meshes; do
      line=$("$shared/peers/run_peer.sh" "$peer" "$mesh" "$n" "$tmp/peer.obj" 2>/dev/null | tail -1)
      secs=$(echo "$line" | sed -n 's/.*seconds=\([0-9.]*\).*/\1/p')
      mb=$(echo "$line" | sed -n 's/.*peak_mb=\([0-9.NA]*\).*/\1/p')
      if [ -s "$tmp/peer.obj" ]; then
        read -r valid irr ang amin sj dist < <(referee "$mesh" "$tmp/peer.obj")
        echo "| $name | - | $n | $peer | $(grep -c '^f ' "$tmp/peer.obj") | $valid | $irr | $ang | $amin | $sj | $dist | $secs | $mb |"
      else
        echo "| $name | - | $n | $peer | failed | | | | | | | $secs | $mb |"
      fi
      rm -f "$tmp/peer.obj"
    done
  done
done
