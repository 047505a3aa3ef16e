#!/usr/bin/env bash
# End-to-end tests of `seamquad domain`: every cone file in ../shared/data
# gives a domain whose closed mesh passes the referee
# (shared/tools/check_quad.py --topology-only, with the mesh's genus and the
# cone valences), except mpz/twirl whose valence-1 cone gets the clear error;
# outputs are complete and documented; bad input writes nothing.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
referee=$shared/tools/check_quad.py
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# valences of a Th_hat file as a comma list (cones only)
valences_of() {
  python3 -c '
import math, sys
ks = [round(float(l) / (math.pi / 2)) for l in open(sys.argv[1]) if l.strip()]
print(",".join(str(k) for k in ks if k != 4))' "$1"
}

while IFS=$'\t' read -r file _ _ _ _ _ _ closed genus cones _; do
  [ "$file" = file ] && continue
  [ "$closed" = yes ] && [ "$cones" != - ] || continue
  mesh=$shared/data/$file
  cfile=$(dirname "$mesh")/$cones
  name=$(basename "$file" .obj)
  out=$tmp/$name
  "$bin" domain "$mesh" --cones "$cfile" -o "$out" --json >"$out.json" 2>"$out.err"
  rc=$?
  if [ "$name" = twirl ]; then
    [ $rc -eq 1 ] && grep -q "valence 1" "$out.err" && [ ! -e "$out.quad.obj" ] && ok \
      || bad "twirl: exit $rc, $(cat "$out.err")"
    continue
  fi
  if [ $rc -ne 0 ]; then bad "$name: exit $rc: $(cat "$out.err")"; continue; fi
  for s in quad.obj closed.obj sides.txt svg; do
    [ -s "$out.$s" ] || bad "$name: missing $out.$s"
  done
  vals=$(valences_of "$cfile")
  if python3 "$referee" --topology-only --genus "$genus" --valences "$vals" "$out.closed.obj" \
      >"$out.ref" 2>&1; then ok; else bad "$name: referee: $(tail -3 "$out.ref")"; fi
  python3 - "$out.json" "$out.sides.txt" "$genus" <<'PY' && ok || bad "$name: json/sides"
import json, sys
j = json.load(open(sys.argv[1]))
g = int(sys.argv[3])
assert j["ok"] and j["genus"] == g
k = j["sides"]
sides = [l.split() for l in open(sys.argv[2]) if l.startswith("side ")]
assert len(sides) == k, (len(sides), k)
length = {int(s[1]): int(s[2]) for s in sides}
for s in sides:
    assert length[int(s[3])] == int(s[2]), s  # partner has the same length
assert j["quads"] == j["quads_before_padding"] + j["quads_added_by_padding"]
PY
done <"$shared/data/MANIFEST.tsv"

# --- genus 0 (the bundled cube): Q is a sphere cut along one edge; its
# picture is a planar drawing of the sphere (one quad outside), not every
# quad on one segment, and the closed mesh lies on a sphere with no quad
# folded (the referee against the cube itself) -------------------------------
"$bin" domain "$root/examples/cube.obj" --cones "$root/examples/cube.cones" -o "$tmp/cube" >/dev/null \
  && python3 "$referee" "$root/examples/cube.obj" "$tmp/cube.closed.obj" >"$tmp/cube.ref" 2>&1 \
  && grep -q "folded=0" "$tmp/cube.ref" \
  && python3 - "$tmp/cube.svg" <<'PY' && ok || bad "genus-0 pictures: $(tail -1 "$tmp/cube.ref")"
import re, sys
s = open(sys.argv[1]).read()
right = [re.findall(r"([\d.]+),([\d.]+)", p) for p in re.findall(r'<polygon points="([^"]+)"', s)][2:]
assert len(right) == 23, len(right)  # 24 quads, one of them the outer face
for q in right:  # every quad has area
    pts = [(float(x), float(y)) for x, y in q]
    area = sum(pts[i][0] * pts[(i + 1) % 4][1] - pts[(i + 1) % 4][0] * pts[i][1] for i in range(4)) / 2
    assert abs(area) > 1.0, q
PY

# --- combinatorial mode and errors -----------------------------------------
"$bin" domain --genus 3 --valences 3,3,3,3,3,3,5,7,22 -o "$tmp/h" >/dev/null \
  && python3 "$referee" --topology-only --genus 3 --valences 3,3,3,3,3,3,5,7,22 "$tmp/h.closed.obj" >/dev/null \
  && ok || bad "helmet valences"
"$bin" domain --genus 3 --valences 3,3,3,3,3,3,5,7,22 -o "$tmp/ho" --omega --no-svg --json >"$tmp/ho.json" \
  && [ -s "$tmp/ho.omega.svg" ] && [ ! -e "$tmp/ho.svg" ] \
  && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["omega"]["tree_edges"] > 0' "$tmp/ho.json" \
  && ok || bad "--omega"
# a genus-2 pattern of rank 1: padding alone cannot equalize it, one slide can
v=3,5,5,5,5,5,5,5,5,5
"$bin" domain --genus 2 --valences $v --pattern "$root/tests/data/rank1_genus2.pattern" -o "$tmp/r1" \
  --json >"$tmp/r1.json" \
  && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["slide"]["length"] > 0' "$tmp/r1.json" \
  && python3 "$referee" --topology-only --genus 2 --valences $v "$tmp/r1.closed.obj" >/dev/null \
  && ok || bad "slide on a rank-1 pattern"
for seed in 1 2 3; do
  "$bin" domain --genus 4 --valences 3,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5 --seed $seed \
    -o "$tmp/s$seed" >/dev/null \
    && python3 "$referee" --topology-only --genus 4 \
      --valences 3,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5,5 "$tmp/s$seed.closed.obj" >/dev/null \
    && ok || bad "--seed $seed"
done
"$bin" domain --genus 1 --valences 3,5 -o "$tmp/t35" >/dev/null 2>"$tmp/t35.err"
[ $? -eq 1 ] && grep -q Jucovic "$tmp/t35.err" && [ ! -e "$tmp/t35.quad.obj" ] && ok || bad "torus 3-5"
"$bin" domain --genus 2 --valences 3,5,5 -o "$tmp/gb" >/dev/null 2>"$tmp/gb.err"
[ $? -eq 1 ] && grep -q Gauss-Bonnet "$tmp/gb.err" && ok || bad "Gauss-Bonnet"
"$bin" domain --genus 2 --valences 1,5,5,5,5,5,5,5,5,5 -o "$tmp/v1" >/dev/null 2>"$tmp/v1.err"
[ $? -eq 1 ] && grep -q "valence 1" "$tmp/v1.err" && ok || bad "valence 1"
"$bin" domain --genus 2 --valences 6,6 -o "$tmp/nodir/x" >/dev/null 2>"$tmp/nd.err"
[ $? -eq 1 ] && [ ! -e "$tmp/nodir" ] && ok || bad "unwritable output"
"$bin" domain --genus 2 --valences 6,6 >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "missing -o"
"$bin" domain --genus 2 --valences 6,x -o "$tmp/y" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "bad list"
"$bin" domain --help | grep -q "padding" && ok || bad "--help"

echo "cli_domain: $pass passed, $fail failed"
[ $fail -eq 0 ]
