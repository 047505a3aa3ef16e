#!/usr/bin/env bash
# End-to-end tests of `seamquad subdiv`: on a cube built here and on a
# QuadriFlow quad mesh of ../shared/data/quads it writes a watertight limit
# OBJ with one unit normal per vertex, STEP and IGES files with one surface
# per patch (and, when the test-only OpenCASCADE checker occt_check sits next
# to the binary, OpenCASCADE imports them as valid shapes), --json is valid
# JSON with a ~0 gap between patches; bad command lines exit 2; a triangle
# mesh or an open quad mesh exits 1 with a message; an unwritable output
# exits 1 and leaves no file. Environment (set by ctest): SQ_BIN,
# SQ_SHARED_DIR.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=$shared/data
checker=$(dirname "$bin")/occt_check
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
json_field() { # json_field FILE EXPR  (python expression on `j`)
  python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"
}

tmp=$(mktemp -d)
trap 'chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
[ -d "$data/quads" ] || { echo "FAIL: shared data not found at $data"; exit 1; }

cat >"$tmp/cube.obj" <<'OBJ'
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 3 4 8 7
f 2 3 7 6
f 1 5 8 4
OBJ

# limit OBJ: v and vn counts equal; faces are quads `a//a`; every undirected
# edge used twice (watertight); normals unit length; expected counts.
check_limit() { # FILE EXPECTED_QUADS
  python3 - "$1" "$2" <<'PY'
import sys, math, collections
v = vn = 0; faces = []; bad = []
for line in open(sys.argv[1]):
    t = line.split()
    if not t: continue
    if t[0] == 'v': v += 1
    elif t[0] == 'vn':
        vn += 1
        l = math.sqrt(sum(float(x)**2 for x in t[1:4]))
        if abs(l - 1) > 1e-9: bad.append('normal length %g' % l)
    elif t[0] == 'f':
        c = [x.split('//') for x in t[1:]]
        if len(c) != 4 or any(a != b for a, b in c): bad.append('face ' + line.strip())
        faces.append([int(a) for a, _ in c])
if v != vn: bad.append('%d v but %d vn' % (v, vn))
if len(faces) != int(sys.argv[2]): bad.append('%d quads, expected %s' % (len(faces), sys.argv[2]))
edges = collections.Counter()
for f in faces:
    for i in range(4):
        a, b = f[i], f[(i + 1) % 4]
        edges[(a, b)] += 1
for (a, b), n in edges.items():
    if n != 1 or edges.get((b, a)) != 1: bad.append('edge %d-%d not shared once each way' % (a, b)); break
chi = v - len(edges) // 2 + len(faces)
print(chi)
if bad: print('; '.join(bad[:3])); sys.exit(1)
PY
}

# --- cube: every output ------------------------------------------------------
"$bin" subdiv "$tmp/cube.obj" --step "$tmp/c.step" --iges "$tmp/c.igs" --limit "$tmp/c.obj" \
  --level 3 --isolation 3 --json >"$tmp/c.json" 2>"$tmp/err.txt"
rc=$?
if [ $rc -ne 0 ]; then
  bad "cube: exit $rc: $(cat "$tmp/err.txt")"
else
  ok
  chi=$(check_limit "$tmp/c.obj" 384) && [ "$chi" = 2 ] && ok || bad "cube limit OBJ: $chi"
  np=$(json_field "$tmp/c.json" 'j["patches"]')
  gap=$(json_field "$tmp/c.json" 'j["seams"]["max_gap_rel"] < 1e-12 and j["seams"]["normal_jump_max_regular_deg"] < 1e-6')
  [ "$gap" = True ] && ok || bad "cube: seams $(json_field "$tmp/c.json" 'j["seams"]')"
  head -1 "$tmp/c.step" | grep -q '^ISO-10303-21;$' && ok || bad "cube: STEP header"
  n=$(grep -c 'B_SPLINE_SURFACE_WITH_KNOTS' "$tmp/c.step")
  [ "$n" = "$np" ] && ok || bad "cube: $n STEP surfaces for $np patches"
  n=$(grep -c '^     128' "$tmp/c.igs")
  [ "$n" = $((2 * np)) ] && ok || bad "cube: $n IGES directory lines for $np patches"
  awk 'length($0) != 80 { exit 1 }' "$tmp/c.igs" && ok || bad "cube: IGES lines not 80 columns"
  if [ -x "$checker" ]; then
    for f in c.step c.igs; do
      out=$(ASAN_OPTIONS=detect_leaks=0 "$checker" "$tmp/$f" | grep '^format')
      case "$out" in
        *"faces $np valid 1 bspline $np "*) ok ;;
        *) bad "cube: OpenCASCADE on $f: $out" ;;
      esac
    done
  fi
fi

# --- a real quad mesh, refined once, limit level 1 ----------------------------
mesh=$data/quads/fertility_quadriflow5k.obj
"$bin" subdiv "$mesh" --limit "$tmp/f.obj" --level 1 --iges "$tmp/f.igs" --json \
  >"$tmp/f.json" 2>"$tmp/err.txt"
rc=$?
if [ $rc -ne 0 ]; then
  bad "fertility: exit $rc: $(cat "$tmp/err.txt")"
else
  nf=$(json_field "$tmp/f.json" 'j["mesh"]["faces"]')
  g=$(json_field "$tmp/f.json" 'j["mesh"]["genus"]')
  chi=$(check_limit "$tmp/f.obj" $((4 * nf))) && [ "$chi" = $((2 - 2 * g)) ] && ok ||
    bad "fertility limit OBJ: $chi (genus $g)"
  [ "$(json_field "$tmp/f.json" 'j["seams"]["max_gap_rel"] < 1e-12')" = True ] && ok ||
    bad "fertility: gap $(json_field "$tmp/f.json" 'j["seams"]')"
  [ "$(json_field "$tmp/f.json" 'j["patches"] >= j["mesh"]["faces"]')" = True ] && ok || bad "fertility: too few patches"
fi
# text report
"$bin" subdiv "$tmp/cube.obj" --isolation 2 >"$tmp/t.txt" 2>&1 && grep -q '^seams ' "$tmp/t.txt" &&
  grep -q '^patches ' "$tmp/t.txt" && ok || bad "text report: $(cat "$tmp/t.txt")"

# --- errors --------------------------------------------------------------------
expect() { # expect CODE DESCRIPTION -- ARGS...
  local want=$1 what=$2; shift 3
  "$bin" subdiv "$@" >"$tmp/o.txt" 2>"$tmp/e.txt"
  local rc=$?
  [ $rc -eq "$want" ] && ok || bad "$what: exit $rc, expected $want ($(cat "$tmp/e.txt"))"
}
expect 2 "no mesh" --
expect 2 "unknown option" -- "$tmp/cube.obj" --bogus
expect 2 "bad level" -- "$tmp/cube.obj" --limit "$tmp/x.obj" --level 9
expect 2 "level without limit" -- "$tmp/cube.obj" --level 2
expect 2 "bad isolation" -- "$tmp/cube.obj" --isolation 0
expect 2 "missing file name" -- "$tmp/cube.obj" --step
expect 2 "two meshes" -- "$tmp/cube.obj" "$tmp/cube.obj"
expect 0 "help" -- --help
expect 1 "missing mesh file" -- "$tmp/cube.obj.missing"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n' >"$tmp/tet.obj"
expect 1 "triangle mesh" -- "$tmp/tet.obj" --step "$tmp/tet.step"
grep -q 'quad' "$tmp/e.txt" && ok || bad "triangle mesh message: $(cat "$tmp/e.txt")"
[ ! -e "$tmp/tet.step" ] && ok || bad "triangle mesh: output written"
head -n 13 "$tmp/cube.obj" >"$tmp/open.obj"
expect 1 "open quad mesh" -- "$tmp/open.obj" --step "$tmp/open.step"
grep -q 'open.obj' "$tmp/e.txt" && ok || bad "open mesh message: $(cat "$tmp/e.txt")"
mkdir -p "$tmp/ro" && chmod a-w "$tmp/ro"
if [ ! -w "$tmp/ro" ]; then  # root ignores permissions: use a missing directory
  expect 1 "unwritable STEP" -- "$tmp/cube.obj" --step "$tmp/ro/x.step"
  [ ! -e "$tmp/ro/x.step" ] && ok || bad "unwritable: file left"
fi
expect 1 "missing directory" -- "$tmp/cube.obj" --iges "$tmp/nodir/x.igs"
[ -z "$(ls "$tmp" | grep -v -E '^(cube.obj|c\..*|f\..*|t.txt|o.txt|e.txt|err.txt|tri.obj|tet.obj|open.obj|ro)$')" ] && ok ||
  bad "stray files: $(ls "$tmp")"

echo "cli_subdiv: $pass passed, $fail failed"
[ $fail -eq 0 ]
