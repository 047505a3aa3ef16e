#!/usr/bin/env bash
# End-to-end tests of `seamquad cones`: the cone files it writes (both
# formats) are accepted by `seamquad check`, --json is valid JSON that agrees
# with check, bad command lines exit 2, unwritable output exits 1 and leaves
# no file, an invalid mesh exits 1. Environment (set by ctest): SQ_BIN,
# SQ_SHARED_DIR.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=$shared/data
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

json_field() { # json_field FILE EXPR  (python expression on `j`)
  python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"
}

tmp=$(mktemp -d)
trap 'chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT

if [ ! -d "$data" ]; then
  echo "FAIL: shared data not found at $data"
  exit 1
fi

# --- cones that check accepts ------------------------------------------------
# mesh, output name, extra options
cases=(
  "libigl/bunny.off|bunny.cones|"
  "mpz/knot1.obj|knot1_Th_hat|--align smooth"
  "gpjs/double-torus.obj|dt.cones|--align curvature"
  "odedstein/spot_low_resolution.obj|spot_Th_hat|--cancel-radius 0"
  "avaxman/Kitten.off|kitten.cones|--align smooth --cancel-radius 5"
)
for c in "${cases[@]}"; do
  IFS='|' read -r mesh out opts <<<"$c"
  # shellcheck disable=SC2086
  "$bin" cones "$data/$mesh" -o "$tmp/$out" $opts --json >"$tmp/out.json" 2>"$tmp/err.txt"
  rc=$?
  [ $rc -eq 0 ] || { bad "$mesh: cones exit $rc: $(cat "$tmp/err.txt")"; continue; }
  [ -f "$tmp/$out" ] || { bad "$mesh: no output file"; continue; }
  json_field "$tmp/out.json" 'j["ok"]' >/dev/null 2>&1 || { bad "$mesh: invalid JSON"; cat "$tmp/out.json"; continue; }
  "$bin" check "$data/$mesh" --cones "$tmp/$out" --json >"$tmp/check.json" 2>"$tmp/cerr.txt"
  rc=$?
  [ $rc -eq 0 ] || { bad "$mesh: check rejects the cones (exit $rc): $(cat "$tmp/cerr.txt")"; continue; }
  mine=$(json_field "$tmp/out.json" 'j["ok"], j["cones"]["count"], j["cones"]["histogram"]')
  theirs=$(json_field "$tmp/check.json" 'j["ok"], j["cones"]["count"], j["cones"]["histogram"]')
  [ "$mine" = "$theirs" ] || { bad "$mesh: cones says '$mine', check says '$theirs'"; continue; }
  fmt=$(json_field "$tmp/check.json" 'j["cones"]["format"]')
  case "$out" in
    *.cones) want=list ;;
    *) want=th_hat ;;
  esac
  [ "$fmt" = "$want" ] || { bad "$mesh: wrote format $fmt, expected $want"; continue; }
  if [ "$want" = th_hat ]; then
    nv=$(json_field "$tmp/check.json" 'j["mesh"]["vertices"]')
    [ "$(wc -l <"$tmp/$out")" -eq "$nv" ] || { bad "$mesh: Th_hat has not $nv lines"; continue; }
  fi
  ok
done

# text report and overwrite of an existing file
echo old >"$tmp/over.cones"
"$bin" cones "$data/libigl/bumpy.off" -o "$tmp/over.cones" >"$tmp/t.txt" 2>&1 \
  && grep -q "^cones " "$tmp/t.txt" && grep -q "gauss-bonnet  satisfied" "$tmp/t.txt" \
  && ! grep -q old "$tmp/over.cones" && ok || { bad "text report / overwrite"; cat "$tmp/t.txt"; }

# --- failures: exit code, message, no file -----------------------------------
"$bin" cones "$data/libigl/bumpy.off" -o "$tmp/missing/dir/x.cones" >/dev/null 2>"$tmp/e.txt"
rc=$?
[ $rc -eq 1 ] && grep -q "missing/dir/x.cones" "$tmp/e.txt" && [ ! -e "$tmp/missing" ] \
  && ok || bad "missing output dir: exit $rc, $(cat "$tmp/e.txt")"

mkdir "$tmp/ro"
chmod 555 "$tmp/ro"
if [ "$(id -u)" -ne 0 ]; then
  "$bin" cones "$data/libigl/bumpy.off" -o "$tmp/ro/x.cones" --json >"$tmp/ro.json" 2>/dev/null
  rc=$?
  [ $rc -eq 1 ] && [ -z "$(ls -A "$tmp/ro")" ] \
    && [ "$(json_field "$tmp/ro.json" 'j["ok"], j["error"]["stage"]')" = "False write" ] \
    && ok || bad "read-only output dir: exit $rc"
fi
# a directory as output (fails even for root)
"$bin" cones "$data/libigl/bumpy.off" -o "$tmp/ro/" >/dev/null 2>&1
rc=$?
[ $rc -eq 1 ] && [ -z "$(ls -A "$tmp/ro")" ] && ok || bad "directory as output: exit $rc"
chmod 755 "$tmp/ro"

"$bin" cones "$data/cid/fertility_tri.obj" -o "$tmp/open.cones" >/dev/null 2>"$tmp/e.txt"
rc=$?
[ $rc -eq 1 ] && grep -q "boundary" "$tmp/e.txt" && [ ! -e "$tmp/open.cones" ] \
  && ok || bad "open mesh: exit $rc"
"$bin" cones "$tmp/nope.obj" -o "$tmp/nope.cones" >/dev/null 2>&1
rc=$?
[ $rc -eq 1 ] && [ ! -e "$tmp/nope.cones" ] && ok || bad "missing mesh: exit $rc"

# --- command line -------------------------------------------------------------
m=$data/libigl/bumpy.off
usage_case() { # usage_case NAME ARGS...
  local name=$1
  shift
  "$bin" cones "$@" >/dev/null 2>"$tmp/u.txt"
  local rc=$?
  [ $rc -eq 2 ] && [ -s "$tmp/u.txt" ] && ok || bad "$name: exit $rc, expected 2"
}
usage_case "no arguments"
usage_case "no -o" "$m"
usage_case "-o without file" "$m" -o
usage_case "bad --align" "$m" -o "$tmp/a.cones" --align sideways
usage_case "--align without value" "$m" -o "$tmp/a.cones" --align
usage_case "negative radius" "$m" -o "$tmp/a.cones" --cancel-radius -1
usage_case "non-numeric radius" "$m" -o "$tmp/a.cones" --cancel-radius 3x
usage_case "unknown option" "$m" -o "$tmp/a.cones" --bogus
usage_case "two meshes" "$m" "$m" -o "$tmp/a.cones"
[ ! -e "$tmp/a.cones" ] && ok || bad "a usage error wrote a file"
"$bin" cones --help | grep -q "Th_hat" && ok || bad "cones --help"

echo "cli_cones: $pass passed, $fail failed"
[ $fail -eq 0 ]
