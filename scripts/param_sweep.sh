#!/usr/bin/env bash
# Random-cone sweep of `seamquad param` (issue 4): every closed mesh of
# ../shared/data that comes without cones (genus 0 to 7; not the quad
# meshes of quads/), random admissible
# cone sets (scripts/random_cones.py: random vertices, valences 3/5 with some
# 2/6, total excess 4*chi, never valence 1 or the torus {3,5}), several seeds
# per mesh; each output is judged by the referee
# (../shared/tools/check_param.py MESH CONES OUT.obj --integer). With
# --optimize each map is param's optimized and simplified in rounds
# (`param --optimize on`; the referee without --integer: the translations
# are real), its mean conformal ratio before -> after. With --quads N each
# map then goes through `seamquad quantize --quads N` and
# `seamquad extract`, and the quad mesh is judged by the referee too
# (../shared/tools/check_quad.py MESH QUADS --cones CONES). Prints a
# markdown table and a summary; exit 0 only if every run passes.
#
# usage: scripts/param_sweep.sh [--seeds N] [--max-faces F] [--optimize] [--quads N] [--keep DIR]
#   --seeds N      cone sets per mesh (default 3; seeds 1..N, also the cut
#                  graph's --seed)
#   --max-faces F  skip meshes with more faces (default: no limit)
#   --optimize     param --optimize on
#   --quads N      also quantize each map to about N quads and extract them
#   --keep DIR     keep cone files, outputs and referee reports in DIR
# env: SQ_BIN (default build/bin/seamquad, built by scripts/build if missing),
#      SQ_SHARED_DIR (default ../shared)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SQ_SHARED_DIR:-$root/../shared}
bin=${SQ_BIN:-$root/build/bin/seamquad}
seeds=3
max_faces=0
quads=0
keep=
optimize=off
while [ $# -gt 0 ]; do
  case "$1" in
    --seeds) seeds=$2; shift 2 ;;
    --max-faces) max_faces=$2; shift 2 ;;
    --quads) quads=$2; shift 2 ;;
    --optimize) optimize=on; shift ;;
    --keep) keep=$2; shift 2 ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "param_sweep: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$bin" ] || "$root/scripts/build" || exit 3
if [ -n "$keep" ]; then mkdir -p "$keep" && work=$keep; else work=$(mktemp -d); trap 'rm -rf "$work"' EXIT; fi

pass=0
fail=0
integer=--integer
[ $optimize = on ] && integer=
echo "| mesh | genus | faces | seed | cones | faces out | conformal mean | time (s) | result | quads | quads result |"
echo "|---|---:|---:|---:|---|---:|---|---:|---|---:|---|"
while IFS=$'\t' read -r file _ _ _ _ _ nf closed genus cones _; do
  [ "$file" = file ] && continue
  [ "$closed" = yes ] && [ "$cones" = - ] || continue
  case "$file" in quads/*) continue ;; esac # quad meshes (inputs of smooth)
  [ "$max_faces" -gt 0 ] && [ "$nf" -gt "$max_faces" ] && continue
  mesh=$shared/data/$file
  name=$(basename "$file" | sed 's/\.[^.]*$//')
  for seed in $(seq 1 "$seeds"); do
    base=$work/${name}_s$seed
    vals=$(python3 "$root/scripts/random_cones.py" "$mesh" "${base}_Th_hat" --seed "$seed") || {
      fail=$((fail + 1)); echo "| $file | $genus | $nf | $seed | - | - | - | FAIL: cone generator | - | - |"; continue; }
    hist=$(echo "$vals" | tr ',' '\n' | sort -n | uniq -c | awk '{printf "%s%s:%s", sep, $2, $1; sep=" "}')
    [ -n "$hist" ] || hist="none"
    t0=$(date +%s.%N)
    "$bin" param "$mesh" --cones "${base}_Th_hat" -o "$base.obj" --seed "$seed" --optimize $optimize --json --quiet \
      >"$base.json" 2>"$base.err"
    rc=$?
    t=$(printf '%.2f' "$(echo "$(date +%s.%N) - $t0" | bc)")
    if [ $rc -ne 0 ]; then
      fail=$((fail + 1))
      echo "| $file | $genus | $nf | $seed | $hist | - | - | $t | FAIL: exit $rc: $(tail -1 "$base.err" | cut -c1-120 | tr '|' '/') | - | - |"
      continue
    fi
    read -r fout conf < <(python3 -c '
import json, sys
j = json.load(open(sys.argv[1])); o = j.get("optimize")
if o: print(o["faces_after"], "%.3g_->_%.3g" % (o["conformal_before"], o["conformal_after"]))
else: print(j["faces_out"], "%.3g" % j["distortion"]["conformal_mean"])' "$base.json" 2>/dev/null || echo "? ?")
    conf=${conf//_/ }
    if python3 "$shared/tools/check_param.py" "$mesh" "${base}_Th_hat" "$base.obj" $integer >"$base.ref" 2>&1; then
      qcol="| - | - |"
      ok=1
      if [ "$quads" -gt 0 ]; then
        if ! "$bin" quantize "$mesh" --map "$base.obj" --cones "${base}_Th_hat" --quads "$quads" \
            -o "$base.igm.obj" --quiet 2>"$base.qerr" ||
          ! "$bin" extract "$mesh" "$base.igm.obj" -o "$base.quads.obj" --cones "${base}_Th_hat" \
            --quiet 2>>"$base.qerr"; then
          ok=0
          qcol="| - | FAIL: $(tail -1 "$base.qerr" | cut -c1-100 | tr '|' '/') |"
        elif python3 "$shared/tools/check_quad.py" "$mesh" "$base.quads.obj" --cones "${base}_Th_hat" \
            >"$base.qref" 2>&1; then
          qcol="| $(grep -c '^f ' "$base.quads.obj") | PASS |"
        else
          ok=0
          qcol="| $(grep -c '^f ' "$base.quads.obj") | FAIL: $(tail -1 "$base.qref" | cut -c1-100 | tr '|' '/') |"
        fi
        [ -n "$keep" ] || rm -f "$base.igm.obj" "$base.quads.obj"
      fi
      if [ $ok = 1 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
      echo "| $file | $genus | $nf | $seed | $hist | $fout | $conf | $t | PASS $qcol"
    else
      fail=$((fail + 1))
      echo "| $file | $genus | $nf | $seed | $hist | $fout | $conf | $t | FAIL: referee: $(tail -1 "$base.ref" | cut -c1-120 | tr '|' '/') | - | - |"
    fi
    [ -n "$keep" ] || rm -f "$base.obj"
  done
done <"$shared/data/MANIFEST.tsv"
echo
echo "param_sweep: $pass passed, $fail failed ($seeds seeds per mesh, --optimize $optimize)"
[ $fail -eq 0 ]
