#!/usr/bin/env bash
# End-to-end tests of `seamquad extract`: the integer-grid maps that
# `seamquad param` writes for mpz/eight, knot1, helmet, holes3 and block (not
# under the sanitizers: it would dominate their run),
# at unit scale (k = 1) and with every vt doubled (k = 2), give quad meshes
# with exactly k^2 times the combinatorial domain's quads (param --json
# "quads"), as many vertices as --json says, which the referee
# (shared/tools/check_quad.py MESH QUADS --cones CONES) judges: faces,
# topology (closed, manifold, oriented, genus), valences (irregular vertices
# = the cones) and the degeneracy counts repeated-vertex, tiny-area and
# zero-length-edge must all pass; folded quads are counted and reported
# (they come from the distortion of param's maps, see docs/extract.md).
# The maps that `seamquad quantize` makes of the seamless UV stored in
# mpz/eight, knot1 and holes3 must pass the referee completely.
# --cones with the map's cones passes, with one cone moved it is refused.
# Bad input: a flipped UV triangle, a non-integer translation, a cone off
# the integer grid, a map without vt, the map of another mesh, an open mesh,
# an unwritable output: exit 1, a message naming the problem, nothing
# written; a wrong command line: exit 2.
# Prints PASS/FAIL per case and a total.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
referee=$shared/tools/check_quad.py
data=$shared/data/mpz
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# scale FILE K OUT [SHIFT]: every vt multiplied by K, plus (SHIFT, SHIFT)
# (exact for K = 2 or 1/2 and SHIFT = 1/4 on param's dyadic UVs)
scale() {
  python3 - "$1" "$2" "$3" "${4:-0}" <<'PY'
import sys
k, c = float(sys.argv[2]), float(sys.argv[4])
with open(sys.argv[1]) as f, open(sys.argv[3], "w") as g:
    for line in f:
        if line.startswith("vt "):
            u, v = line.split()[1:3]
            g.write("vt %r %r\n" % (float(u) * k + c, float(v) * k + c))
        else:
            g.write(line)
PY
}

# nothing NAME: no file NAME and no staging file left in $tmp
nothing() { [ ! -e "$tmp/$1" ] && [ -z "$(ls -A "$tmp" | grep -i 'partial\|\.tmp')" ]; }

# --- the maps of param, k = 1 and 2 -----------------------------------------
# (block, the largest, only without the sanitizers: it dominates their run)
models="eight knot1 helmet holes3 block"
[ "${SQ_SANITIZE:-OFF}" = ON ] && models="eight knot1 helmet holes3"
for name in $models; do
  mesh=$data/$name.obj
  cones=$data/${name}_Th_hat
  seed=1
  if ! "$bin" param "$mesh" --cones "$cones" -o "$tmp/$name.igm1.obj" --seed $seed --json --quiet \
      >"$tmp/$name.param.json" 2>"$tmp/$name.param.err"; then
    bad "$name: param failed: $(tail -1 "$tmp/$name.param.err")"
    continue
  fi
  domain=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["quads"])' "$tmp/$name.param.json")
  scale "$tmp/$name.igm1.obj" 2 "$tmp/$name.igm2.obj"
  for k in 1 2; do
    out=$tmp/$name.q$k
    "$bin" extract "$mesh" "$tmp/$name.igm$k.obj" -o "$out.obj" --json >"$out.json" 2>"$out.err"
    rc=$?
    if [ $rc -ne 0 ]; then
      bad "$name k=$k: exit $rc: $(cat "$out.err")"
      continue
    fi
    python3 "$referee" "$mesh" "$out.obj" --cones "$cones" --json "$out.ref.json" >"$out.ref" 2>&1
    if msg=$(python3 - "$out.json" "$out.ref.json" "$out.obj" "$domain" "$k" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
r = json.load(open(sys.argv[2]))
domain, k = int(sys.argv[4]), int(sys.argv[5])
nv = sum(1 for l in open(sys.argv[3]) if l.startswith("v "))
nf = sum(1 for l in open(sys.argv[3]) if l.startswith("f "))
assert j["ok"] and j["quads"] == domain * k * k == nf, (j["quads"], domain, nf)
assert j["grid_points"]["total"] == nv, (j["grid_points"], nv)
assert j["irregular"] == j["cones"] and j["edges"] == 2 * j["quads"], j
for part in ("faces", "topology", "valence"):
    assert r[part]["passed"], (part, r[part]["failures"])
d = r["degeneracy"]
assert d["repeated_vertex"] == 0 and d["tiny_area"] == 0 and d["zero_length_edge"] == 0, d
assert d["folded"] == 0 and j["degenerate"] == {"short_edge": 0, "tiny": 0, "folded": 0, "turned": 0}, (d, j)
assert r["fidelity"]["quad_vertices_to_input"]["max_rel"] < 1e-9, r["fidelity"]
print("%d quads, %d vertices, %d irregular, genus %d; referee: faces, topology, valences, cones "
      "PASS, %d folded quads; %.3f s" % (nf, nv, j["irregular"], r["topology"]["genus"],
                                          d["folded"], j["time_s"]["total"]))
PY
    ); then
      ok; echo "PASS $name k=$k: $msg"
    else
      bad "$name k=$k: $msg $(tail -1 "$out.ref")"
    fi
  done
done

# --- the whole pipeline on near-isometric maps: `seamquad quantize` turns the
# seamless UV stored in the mpz files into an integer-grid map of about N
# quads; its quad mesh must pass the referee completely (no folded quad) ---
for spec in eight:2000 knot1:2000 holes3:4000; do
  name=${spec%%:*}
  n=${spec#*:}
  mesh=$data/$name.obj
  cones=$data/${name}_Th_hat
  out=$tmp/$name.quantized
  if ! "$bin" quantize "$mesh" --map "$mesh" --quads "$n" --cones "$cones" -o "$out.igm.obj" --quiet \
      >/dev/null 2>"$out.qerr"; then
    bad "$name quantize --quads $n: $(tail -1 "$out.qerr")"
    continue
  fi
  if "$bin" extract "$mesh" "$out.igm.obj" --cones "$cones" -o "$out.obj" --quiet 2>"$out.err" \
      && python3 "$referee" "$mesh" "$out.obj" --cones "$cones" >"$out.ref" 2>&1; then
    ok; echo "PASS $name quantize --quads $n + extract: $(tail -1 "$out.ref")"
  else
    bad "$name quantize --quads $n + extract: $(cat "$out.err") $(tail -1 "$out.ref" 2>/dev/null)"
  fi
done

# --- bad input: exit 1, a message, nothing written --------------------------
eight=$data/eight.obj
igm=$tmp/eight.igm1.obj
# refused CASE EXPECTED-MESSAGE-REGEX EXTRACT-ARGS...
refused() {
  local what=$1 re=$2
  shift 2
  "$bin" extract "$@" -o "$tmp/refused.obj" >"$tmp/refused.out" 2>"$tmp/refused.err"
  local rc=$?
  if [ $rc -eq 1 ] && grep -qi -- "$re" "$tmp/refused.err" && nothing refused.obj; then
    ok; echo "PASS refused $what: $(head -c 200 "$tmp/refused.err")"
  else
    bad "$what: exit $rc (expected 1 and /$re/, nothing written): $(cat "$tmp/refused.err")"
  fi
  rm -f "$tmp/refused.obj"
}
if [ -s "$igm" ]; then
  # a flipped UV triangle: the first face's first two corners swap their vt
  awk 'BEGIN{d=0} /^f /&&!d{split($2,a,"/");split($3,b,"/");$2=a[1]"/"b[2];$3=b[1]"/"a[2];d=1} {print}' \
    "$igm" >"$tmp/flip.obj"
  refused "flipped UV triangle" "face 0" "$eight" "$tmp/flip.obj"
  # every vt moved by (1/4, 1/4): across a seam that turns by 90 degrees,
  # the translation changes by (1/2, 0)
  scale "$igm" 1 "$tmp/shift.obj" 0.25
  refused "non-integer translation" "translation .* is not integer" "$eight" "$tmp/shift.obj"
  # every vt times 1/2: seams still integer, but cones on half-integers
  scale "$igm" 0.5 "$tmp/half.obj"
  refused "cone off the integer grid" "not on an integer point" "$eight" "$tmp/half.obj"
  # no vt at all
  sed -e '/^vt /d' -e 's#/[0-9]*##g' "$igm" >"$tmp/novt.obj"
  refused "missing vt" "vt" "$eight" "$tmp/novt.obj"
  # the map of another mesh
  refused "map of another mesh" "not a map of the input mesh" "$data/knot1.obj" "$igm"
  # a broken mesh file
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/open.obj"
  refused "open mesh" "open.obj" "$tmp/open.obj" "$igm"
  # an unwritable output
  "$bin" extract "$eight" "$igm" -o "$tmp/no/such/dir/q.obj" >/dev/null 2>"$tmp/unwritable.err"
  rc=$?
  if [ $rc -eq 1 ] && grep -q "no/such/dir" "$tmp/unwritable.err"; then
    ok; echo "PASS unwritable output: exit 1"
  else
    bad "unwritable output: exit $rc: $(cat "$tmp/unwritable.err")"
  fi
  # --cones: the map's own cones pass; a cone set with one cone moved to
  # another vertex is refused, naming the vertex
  "$bin" extract "$eight" "$igm" --cones "$data/eight_Th_hat" -o "$tmp/withcones.obj" --json \
    >"$tmp/withcones.json" 2>"$tmp/withcones.err"
  if [ $? -eq 0 ] && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["ok"] and j["irregular"]==8 and j["cones_file"], j' \
      "$tmp/withcones.json"; then
    ok; echo "PASS --cones eight_Th_hat"
  else
    bad "--cones eight_Th_hat: $(cat "$tmp/withcones.err")"
  fi
  python3 - "$data/eight_Th_hat" "$tmp/moved.cones" <<'PY'
import math, sys
cones = [i for i, l in enumerate(open(sys.argv[1])) if l.strip() and abs(float(l) - 2 * math.pi) > 1e-3]
free = min(v for v in range(766) if v not in cones)
with open(sys.argv[2], "w") as f:
    for v in cones[1:] + [free]:
        f.write("%d 5\n" % v)
PY
  refused "cones the map does not have" "does not have these cones" "$eight" "$igm" --cones "$tmp/moved.cones"
  # --json on an error: ok false and the error's stage
  "$bin" extract "$eight" "$tmp/flip.obj" -o "$tmp/refused.obj" --json >"$tmp/err.json" 2>/dev/null
  if python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert not j["ok"] and j["error"]["stage"]=="map", j' \
      "$tmp/err.json" && nothing refused.obj; then
    ok; echo "PASS --json error report"
  else
    bad "--json error report: $(cat "$tmp/err.json")"
  fi
else
  bad "no map of mpz/eight to corrupt"
fi

# --- command line --------------------------------------------------------------
usage() {
  local what=$1 want=$2
  shift 2
  "$bin" extract "$@" >"$tmp/usage.out" 2>"$tmp/usage.err"
  local rc=$?
  if [ $rc -eq "$want" ]; then ok; else bad "$what: exit $rc, expected $want: $(cat "$tmp/usage.err")"; fi
}
usage "no output" 2 "$eight" "$igm"
usage "no map" 2 "$eight" -o "$tmp/u.obj"
usage "unknown option" 2 "$eight" "$igm" -o "$tmp/u.obj" --frobnicate
usage "output not OBJ" 2 "$eight" "$igm" -o "$tmp/u.ply"
usage "output over the map" 2 "$eight" "$igm" -o "$igm"
usage "help" 0 --help
if grep -q "integer-grid map" "$tmp/usage.out" && grep -q "INTEGER translation" "$tmp/usage.out"; then
  ok
else
  bad "--help does not explain integer-grid maps"
fi
[ ! -e "$tmp/u.obj" ] && [ ! -e "$tmp/u.ply" ] && ok || bad "a refused command line wrote a file"

echo "cli_extract: $pass passed, $fail failed"
[ $fail -eq 0 ]
