#!/usr/bin/env bash
# End-to-end tests of `seamquad check`: every broken input of
# tests/data/broken/EXPECTED*.tsv gets its own error (status and message),
# exit code 1; valid inputs pass with the right numbers; --help, --version
# and --json behave. Environment (set by ctest): SQ_BIN, SQ_SHARED_DIR.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

json_field() { # json_field FILE EXPR  (python expression on `j`)
  python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- broken inputs -------------------------------------------------------
for tsv in "$root"/tests/data/broken/EXPECTED*.tsv; do
  while IFS=$'\t' read -r c1 c2 c3 c4; do
    case "$c1" in "#"*|"") continue ;; esac
    if [ -n "${c4:-}" ]; then mesh=$root/$c1; cones=$c2; status=$c3; sub=$c4
    else mesh=$root/tests/data/broken/$c1; cones=-; status=$c2; sub=$c3; fi
    args=("$mesh")
    [ "$cones" != "-" ] && args+=(--cones "$root/$cones")
    "$bin" check "${args[@]}" --json >"$tmp/out.json" 2>"$tmp/err.txt"
    rc=$?
    [ $rc -eq 1 ] || { bad "$c1 ${cones}: exit code $rc, expected 1"; continue; }
    code=$(json_field "$tmp/out.json" 'j["error"]["code"]')
    msg=$(json_field "$tmp/out.json" 'j["error"]["message"]')
    [ "$code" = "$status" ] || { bad "$c1 $cones: status '$code', expected '$status' ($msg)"; continue; }
    case "$msg" in *"$sub"*) ;; *) bad "$c1 $cones: message lacks '$sub': $msg"; continue ;; esac
    grep -qF "$sub" "$tmp/err.txt" || { bad "$c1 $cones: stderr lacks the message"; continue; }
    ok
  done <"$tsv"
done

# --- valid inputs --------------------------------------------------------
"$bin" check "$root/examples/cube.obj" --cones "$root/examples/cube.cones" >"$tmp/cube.txt" 2>&1 \
  && grep -q "genus         0" "$tmp/cube.txt" && grep -q "cones         8" "$tmp/cube.txt" \
  && grep -q "3:8" "$tmp/cube.txt" && ok || { bad "cube check"; cat "$tmp/cube.txt"; }
"$bin" check "$root/examples/cube.obj" --cones "$root/tests/data/cube_Th_hat" --json >"$tmp/c.json" \
  && [ "$(json_field "$tmp/c.json" 'j["cones"]["format"], j["cones"]["count"], j["ok"]')" = "th_hat 8 True" ] \
  && ok || bad "cube Th_hat check"
"$bin" check "$root/tests/data/torus.obj" --json >"$tmp/t.json" \
  && [ "$(json_field "$tmp/t.json" 'j["mesh"]["genus"]')" = 1 ] && ok || bad "torus genus"

el=$shared/data/cid/elephant.obj
if [ -f "$el" ]; then
  "$bin" check "$el" --cones "$shared/data/cid/elephant_Th_hat" --json >"$tmp/e.json" 2>&1
  [ "$(json_field "$tmp/e.json" 'j["mesh"]["genus"], j["cones"]["count"], j["cones"]["gauss_bonnet"]["ok"], j["ok"]')" \
    = "3 118 True True" ] && ok || { bad "elephant"; cat "$tmp/e.json"; }
  "$bin" check "$shared/data/cid/fertility_tri.obj" >"$tmp/f.txt" 2>&1
  [ $? -eq 1 ] && grep -q "boundary edge" "$tmp/f.txt" && ok || bad "fertility_tri must be rejected as open"
  "$bin" check "$shared/data/mpz/twirl.obj" --cones "$shared/data/mpz/twirl_Th_hat" >"$tmp/tw.txt" 2>&1
  [ $? -eq 1 ] && grep -q "valence 1" "$tmp/tw.txt" && grep -q "gauss-bonnet  satisfied" "$tmp/tw.txt" \
    && ok || { bad "twirl must fail on its valence-1 cone"; cat "$tmp/tw.txt"; }
else
  bad "shared data not found at $shared"
fi

# --- usage -----------------------------------------------------------------
"$bin" --help | grep -q "check" && "$bin" --help | grep -q "remesh" && ok || bad "--help"
"$bin" --version | grep -qE '^seamquad [0-9]+\.[0-9]+\.[0-9]+$' && ok || bad "--version"
"$bin" check --help | grep -q "Th_hat" && ok || bad "check --help"
"$bin" check >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "check without mesh: exit 2"
"$bin" check "$root/examples/cube.obj" --bogus >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "unknown option: exit 2"
"$bin" frobnicate >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "unknown command: exit 2"
"$bin" check "$tmp/does-not-exist.obj" >/dev/null 2>"$tmp/nx.txt"; rc=$?
[ $rc -eq 1 ] && grep -q "does-not-exist.obj" "$tmp/nx.txt" && ok || bad "missing file: exit $rc"

echo "cli_check: $pass passed, $fail failed"
[ $fail -eq 0 ]
