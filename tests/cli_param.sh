#!/usr/bin/env bash
# End-to-end tests of `seamquad param` (issue 4): every cone file of a closed
# mesh in ../shared/data (all of mpz/ and cid/elephant) gives a
# parametrization that the referee passes with --integer
# (shared/tools/check_param.py MESH CONES OUT.obj --integer), with complete
# --json stats and SVGs; mpz/twirl's valence-1 cone is refused with a message
# naming the vertex, and nothing is written. Bad input (arguments, a missing
# cones file, Gauss-Bonnet, an unrealizable cone set, a broken mesh) and an
# unwritable output give the documented exit code and write nothing.
# Under the sanitizers (SQ_SANITIZE=ON) the six largest maps are skipped and
# the loop over the cone files leaves the referee to the plain run.
# Prints PASS/FAIL per model and a total.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SQ_BIN:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
data=${SQ_TEST_DATA_DIR:-$root/tests/data}
referee=$shared/tools/check_param.py
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
# models whose parametrization must pass the referee today, with the
# cut-graph seed that does it (docs/param.md); every other model runs one
# attempt and must either pass or fail cleanly
must_pass="eight cup knot1 holes3 sculpt helmet genus3 femur fandisk homer rocker_arm trim-star"
seed_of() { case $1 in femur) echo 3 ;; homer) echo 2 ;; *) echo 1 ;; esac; }
# the largest maps (40K to 700K output faces, 20 to 50 s each under ASan)
heavy="femur homer rocker_arm trim-star fertility_tri block"
known=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- every cone file of a closed mesh ----------------------------------------
while IFS=$'\t' read -r file _ _ _ _ _ _ closed genus cones _; do
  [ "$file" = file ] && continue
  [ "$closed" = yes ] && [ "$cones" != - ] || continue
  mesh=$shared/data/$file
  cfile=$(dirname "$mesh")/$cones
  name=$(basename "$file" .obj)
  out=$tmp/$name
  # under the sanitizers the largest maps are left to the plain run (CI
  # time); the smaller models take the same code paths
  if [ "${SQ_SANITIZE:-OFF}" = ON ] && echo " $heavy " | grep -q " $name "; then
    echo "SKIP $file (sanitizer build: a large map)"
    continue
  fi
  "$bin" param "$mesh" --cones "$cfile" -o "$out.obj" --svg "$out.svg" --domain-svg "$out.omega.svg" --cut-svg "$out.cut.svg" \
    --seed "$(seed_of "$name")" --attempts 1 --tree surface --json --quiet >"$out.json" 2>"$out.err"
  rc=$?
  if [ "$name" = twirl ]; then
    if [ $rc -eq 1 ] && grep -q "vertex 4865 has a cone of valence 1" "$out.err" \
        && [ -z "$(ls -A "$tmp" | grep "^twirl\.\(obj\|svg\|omega\.svg\|cut\.svg\)$")" ] \
        && [ -z "$(ls -A "$tmp" | grep partial)" ]; then
      ok; echo "PASS $file: refused (valence-1 cone at vertex 4865), nothing written"
    else
      bad "$file: exit $rc, expected 1 naming the valence-1 vertex 4865: $(cat "$out.err")"
    fi
    continue
  fi
  if [ $rc -ne 0 ]; then
    # Known limit (docs/param.md, "Limits"): the interior map
    # may be impossible in doubles, or the cut may need too many Steiner
    # vertices. Then the run must fail cleanly: exit 3, that message, and
    # nothing written. Models in $must_pass must succeed.
    if [ $rc -eq 3 ] && grep -q "not injective in floating point\|Steiner vertices were needed\|cut graph: .*no route" "$out.err" \
        && [ ! -e "$out.obj" ] && [ ! -e "$out.svg" ] && [ ! -e "$out.omega.svg" ] && [ ! -e "$out.cut.svg" ] \
        && ! echo " $must_pass " | grep -q " $name " \
        && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); a=j["last_attempt"]; assert not j["ok"] and j["error"]["code"]=="solver" and a["attempts"]==1 and a["genus"]==int(sys.argv[2]) and a["cones"]>0, j' "$out.json" "$genus"; then
      ok; known=$((known + 1)); echo "KNOWN $file: clean failure, nothing written: $(grep -o 'not injective[^;]*;\|more than [0-9]* Steiner\|cut graph: [^(]*' "$out.err" | head -1)"
    else
      bad "$file: exit $rc: $(tail -1 "$out.err")"
    fi
    continue
  fi
  # the plain run has the referee judge these maps; under the sanitizers
  # this loop looks for memory errors and leaves the referee (about a
  # third of its time) to the plain run (CI time)
  if [ "${SQ_SANITIZE:-OFF}" = ON ]; then
    echo "written, verified by param (the referee runs in the plain build)" >"$out.ref"
  elif ! python3 "$referee" "$mesh" "$cfile" "$out.obj" --integer >"$out.ref" 2>&1; then
    bad "$file: referee: $(tail -1 "$out.ref")"
    continue
  fi
  if ! python3 - "$out.json" "$genus" <<'PY'; then bad "$file: --json stats"; continue; fi
import json, sys
j = json.load(open(sys.argv[1]))
assert j["ok"] and j["genus"] == int(sys.argv[2]), j
assert j["verts_out"] == j["verts_in"] + j["steiner"], j
assert j["faces_out"] >= j["faces_in"] and j["seam_edges"] > 0 and j["uv_points"] > 0, j
assert j["quads"] == j["quads_before_padding"] + j["quads_added_by_padding"] > 0, j
assert j["peak_rss_mb"] > 0 and j["time_s"]["total"] > 0, j
assert len(j["outputs"]) == 4, j
PY
  # the cut on the surface: three views, each with every cone once
  ncones=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["cones"])' "$out.json")
  if [ -s "$out.svg" ] && [ -s "$out.omega.svg" ] && head -c 4 "$out.svg" | grep -q "<svg" \
      && head -c 4 "$out.cut.svg" | grep -q "<svg" && [ "$(grep -c "<circle" "$out.cut.svg")" -eq $((3 * ncones)) ] \
      && grep -q "d7191c" "$out.cut.svg"; then
    ok; echo "PASS $file: $(tail -1 "$out.ref")"
  else
    bad "$file: missing SVG"
  fi
done <"$shared/data/MANIFEST.tsv"

# --- retries: without refinement rounds mpz/cup fails its exact check with
# seed 8 and passes with the next seed; --attempts 2 must find it and say so
# in --json (with the surface tree alone: tree qtri passes at seed 8) --------
cup=$shared/data/mpz/cup.obj
"$bin" param "$cup" --cones "$shared/data/mpz/cup_Th_hat" -o "$tmp/cup_retry.obj" --seed 8 --attempts 2 \
  --refine 0 --tree surface --json >"$tmp/cup_retry.json" 2>"$tmp/cup_retry.err"
if [ $? -eq 0 ] && grep -q "retry" "$tmp/cup_retry.err" \
    && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["attempts"]==2 and j["seed_used"]==9 and j["guided"], j' "$tmp/cup_retry.json" \
    && python3 "$referee" "$cup" "$shared/data/mpz/cup_Th_hat" "$tmp/cup_retry.obj" --integer >"$tmp/cup_retry.ref" 2>&1; then
  ok; echo "PASS retry: mpz/cup seed 8 fails, seed 9 passes: $(tail -1 "$tmp/cup_retry.ref")"
else
  bad "retry: mpz/cup --seed 8 --attempts 2: $(tail -1 "$tmp/cup_retry.err") $(cat "$tmp/cup_retry.json")"
fi
# --guide off on the same cut: the unguided construction (seed 5.3) fails there
# (without refinement rounds)
"$bin" param "$cup" --cones "$shared/data/mpz/cup_Th_hat" -o "$tmp/e_cup.obj" --seed 9 --attempts 1 --guide off \
  --refine 0 --quiet >/dev/null 2>"$tmp/cup_off.err"
if [ $? -eq 3 ] && grep -q "not injective in floating point" "$tmp/cup_off.err" && [ ! -e "$tmp/e_cup.obj" ]; then
  ok; echo "PASS --guide off: mpz/cup seed 9 fails cleanly without guidance"
else
  bad "--guide off: $(tail -1 "$tmp/cup_off.err")"
fi

# passes_at MODEL SEED [OPTIONS...]: mpz/MODEL at that seed, one attempt,
# gives a map the referee passes with --integer, whose --json stats j
# satisfy $want (a Python expression; none when unset)
passes_at() {
  local name=$1 seed=$2
  shift 2
  local mesh=$shared/data/mpz/$name.obj cones=$shared/data/mpz/${name}_Th_hat out=$tmp/at_$name
  "$bin" param "$mesh" --cones "$cones" -o "$out.obj" --seed "$seed" --attempts 1 --json --quiet "$@" \
    >"$out.json" 2>"$out.err"
  if [ $? -eq 0 ] \
      && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert eval(sys.argv[2]), j' "$out.json" "${want:-True}" \
      && python3 "$referee" "$mesh" "$cones" "$out.obj" --integer >"$out.ref" 2>&1; then
    ok; echo "PASS mpz/$name seed $seed $*: $(tail -1 "$out.ref")"
  else
    bad "mpz/$name seed $seed $*: $(tail -1 "$out.err") $(tail -1 "$out.ref" 2>/dev/null) $(cat "$out.json")"
  fi
}

# --- mpz/holes3 (genus 3, 24 cones; one of the seed's Table-1 models)
# with the surface tree at seed 111 ------------------------------------------
want='j["guided"] and j["surface_tree"] and not j["tree_qtri"]' passes_at holes3 111 --tree surface

# --- --interior overlay: the cut surface and Omega on one disk, their
# common refinement (no chords, no cells, no rounds): genus 2 (eight),
# genus 1 (knot1), genus 3 (helmet) ------------------------------------------
want='j["interior"]=="overlay" and j["chords"]==0 and j["faces_unsimplified"] > 20000 and 2 * j["faces_out"] < j["faces_unsimplified"]' passes_at eight 1 --interior overlay
# --simplify off: the map as built (tree qtri's 17,134 faces on eight,
# 5,484 simplified)
want='j["simplified"]==0 and j["faces_unsimplified"]==0 and j["faces_out"] > 10000' passes_at eight 1 --simplify off
# the default (--tree auto): tree qtri's first attempt, the overlay's map
# (eight, genus3: a mean conformal ratio of about 200); the surface tree
# with --interior auto: the cells, then the overlay, kept where it passes,
# the cells' map where it does not (genus3 seed 1: 5.2e10)
want='j["interior"]=="overlay" and j["tree_qtri"] and j["attempts"]==1 and not j["fallback"] and j["distortion"]["conformal_mean"] < 1000' passes_at eight 1
want='j["interior"]=="cells" and j["chords"] > 0 and not j["tree_qtri"]' passes_at genus3 1 --tree surface
want='j["tree_qtri"] and not j["fallback"] and j["attempts"]==1 and j["interior"]=="overlay" and j["distortion"]["conformal_mean"] < 1000' passes_at genus3 1
# block and fertility_tri (genus 3 and 4, 46 and 60 cones) pass with tree
# qtri; with the surface tree alone, at every seed tried, the cells need
# more Steiner vertices than allowed (a clean failure above)
if [ "${SQ_SANITIZE:-OFF}" != ON ]; then
  want='j["tree_qtri"] and j["attempts"]==1' passes_at block 1
  want='j["tree_qtri"] and j["attempts"]==1' passes_at fertility_tri 5
fi
want='j["interior"]=="overlay" and j["genus"]==1' passes_at knot1 1 --interior overlay
want='j["interior"]=="overlay" and j["genus"]==3' passes_at helmet 1 --interior overlay
# where Omega's shape is far from the surface's the crossings pass the
# Steiner budget: a clean failure (status 3, the cause named, nothing written)
"$bin" param "$shared/data/mpz/femur.obj" --cones "$shared/data/mpz/femur_Th_hat" -o "$tmp/ov_femur.obj" \
  --attempts 1 --interior overlay --quiet >/dev/null 2>"$tmp/ov_femur.err"
rc=$?
if [ $rc -eq 3 ] && grep -q 'crossings of surface and domain edges' "$tmp/ov_femur.err" && [ ! -e "$tmp/ov_femur.obj" ]; then
  ok; echo "PASS --interior overlay: mpz/femur seed 1 over the budget, exit 3, nothing written"
else
  bad "--interior overlay femur: rc=$rc $(tail -1 "$tmp/ov_femur.err")"
fi

# --tree qtri: the surface tree copied into Q triangulated (seed 9.4, edge
# splits where paths need room), Omega of triangles, the overlay's map:
# genus 2 (eight), genus 3 (genus3), cup (genus 2, 36 cones)
want='j["tree_qtri"] and j["interior"]=="overlay" and j["qtri_verts"] > 0' passes_at eight 1 --tree qtri
want='j["tree_qtri"] and j["genus"]==3' passes_at genus3 1 --tree qtri
# domain variants (docs/param.md): with a gate every domain misses, the one
# whose overlay expects the fewest crossings of 4; on mpz/holes3 that is
# not the first (whose sample expects 64,864), and the summary says so
want='j["tree_qtri"] and j["domain_variant"]>0 and 0<j["crossings_expected"]<64864' \
  passes_at holes3 1 --tree qtri --variants 4 --variant-gate 1
if "$bin" param "$shared/data/mpz/holes3.obj" --cones "$shared/data/mpz/holes3_Th_hat" -o "$tmp/var.obj" \
    --tree qtri --attempts 1 --variants 4 --variant-gate 1 2>/dev/null | grep -q "^variant *domain [2-4]: "; then
  ok
else
  bad "holes3 --variants 4 --variant-gate 1: the summary does not name the domain variant"
fi
want='j["tree_qtri"]' passes_at cup 1 --tree qtri
# the text summary names the tree that was built
for t in surface qtri; do
  "$bin" param "$shared/data/mpz/eight.obj" --cones "$shared/data/mpz/eight_Th_hat" -o "$tmp/tree_$t.obj" \
    --tree "$t" --attempts 1 >"$tmp/tree_$t.txt" 2>&1
done
if grep -q "^attempt .*cone tree from the surface (seed 9.4)" "$tmp/tree_surface.txt" \
    && grep -q "^attempt .*the surface cone tree copied into Q triangulated (tree qtri)" "$tmp/tree_qtri.txt"; then
  ok
else
  bad "eight: the summary does not name the tree built: $(grep '^attempt' "$tmp"/tree_*.txt)"
fi

# --- tree qtri for genus 1 (the default --tree auto): mpz/elk, where
# every attempt with the surface tree fails, passes at the first, with the
# guided domain, the surface tree copied into Q triangulated and the
# overlay (seed 2). About 15 s in Release and a 330,000-face output for
# the referee: not under the sanitizers, which would take many minutes
if [ "${SQ_SANITIZE:-OFF}" != ON ]; then
  want='not j["fallback"] and j["tree_qtri"] and j["guided"] and j["interior"]=="overlay" and j["attempts"]==1 and j["seed_used"]==2 and j["genus"]==1' passes_at elk 2
else
  echo "SKIP mpz/elk --tree auto (sanitizer build)"
fi

# --- the fallback (default --tree auto): where tree qtri's attempts fail
# (here forced by an overlay budget of 1 crossing), the surface tree
# replicated in Q's quads and the cells' map; the summary says so. The
# order of the attempts: qtri's 4 (failing here), then the surface tree's
# first passes: attempt 5, seed 1
want='j["fallback"] and not j["tree_qtri"] and j["attempts"]==5 and j["seed_used"]==1 and j["interior"]=="cells"' passes_at eight 1 --max-crossings 1 --attempts 16
"$bin" param "$shared/data/mpz/eight.obj" --cones "$shared/data/mpz/eight_Th_hat" -o "$tmp/fb2.obj" --attempts 1 \
  --max-crossings 1 >"$tmp/fb2.txt" 2>&1
if grep -q "^fallback *tree qtri's attempts failed; the surface tree replicated in Q's quads" "$tmp/fb2.txt"; then
  ok
else
  bad "eight --max-crossings 1: the summary does not name the fallback: $(grep -i fallback "$tmp/fb2.txt")"
fi
# mpz/femur: every cut-graph seed walls a cone in (the surface tree cannot
# reach it past the cut's vertices and the cones); tree qtri splits the
# input edges between two such vertices at their midpoints and passes at
# attempt 1, seed 1 (the surface tree: the cells at attempt 7, seed 3, a
# mean conformal ratio of 2.55e8 against about 41)
want='not j["fallback"] and j["attempts"]==1 and j["seed_used"]==1 and j["wall_splits"]>0 and j["distortion"]["conformal_mean"]<1000' passes_at femur 1 --attempts 16

# --- genus 1 with --guide on: Algorithm 1 for the meta-6-gon, the
# meta-2-gon's cones near the circle (seed 9.2 per piece): mpz/knot1
# passes with the surface tree, in fewer faces than unguided ------------------
want='j["guided"] and j["surface_tree"] and j["genus"]==1 and j["faces_out"] < 8000' passes_at knot1 1 --guide on --interior cells
# a torus without cones has no pieces: --guide on still maps it
torus=$shared/data/gpjs/torus.obj
python3 -c 'import math,sys; print("\n".join(["%.17g" % (2 * math.pi)] * int(sys.argv[1])))' \
  "$(grep -c '^v ' "$torus")" >"$tmp/torus0_Th_hat"
if "$bin" param "$torus" --cones "$tmp/torus0_Th_hat" -o "$tmp/t0.obj" --attempts 1 --guide on --quiet \
    >/dev/null 2>"$tmp/t0.err" \
    && python3 "$referee" "$torus" "$tmp/torus0_Th_hat" "$tmp/t0.obj" --integer >"$tmp/t0.ref" 2>&1; then
  ok; echo "PASS --guide on: gpjs/torus without cones: $(tail -1 "$tmp/t0.ref")"
else
  bad "--guide on, torus without cones: $(tail -1 "$tmp/t0.err")"
fi

# --- refinement rounds (step 7c): mpz/helmet seed 1 fails without them and
# passes with them; --json counts the rounds, the text report names them
# (the surface tree and the cells alone: tree qtri passes there) ------------
helmet=$shared/data/mpz/helmet.obj
"$bin" param "$helmet" --cones "$shared/data/mpz/helmet_Th_hat" -o "$tmp/h0.obj" --attempts 1 --refine 0 \
  --tree surface --quiet >/dev/null 2>"$tmp/h0.err"
rc0=$?
"$bin" param "$helmet" --cones "$shared/data/mpz/helmet_Th_hat" -o "$tmp/h1.obj" --attempts 1 --json \
  --interior cells --quiet >"$tmp/h1.json" 2>"$tmp/h1.err"
rc1=$?
"$bin" param "$helmet" --cones "$shared/data/mpz/helmet_Th_hat" -o "$tmp/h2.obj" --attempts 1 \
  --interior cells >"$tmp/h2.txt" 2>/dev/null
if [ $rc0 -eq 3 ] && grep -q "not injective in floating point" "$tmp/h0.err" && [ ! -e "$tmp/h0.obj" ] \
    && [ $rc1 -eq 0 ] && grep -q "^refinement  *[0-9]* rounds" "$tmp/h2.txt" \
    && python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["refine_rounds"]>=1 and j["cells_halved"]>=j["refine_rounds"] and j["attempts"]==1 and j["cells"]==j["chords"]+1, j' "$tmp/h1.json" \
    && python3 "$referee" "$helmet" "$shared/data/mpz/helmet_Th_hat" "$tmp/h1.obj" --integer >"$tmp/h1.ref" 2>&1; then
  ok; echo "PASS --refine: mpz/helmet seed 1 fails with --refine 0, passes after $(grep -o '"refine_rounds": [0-9]*' "$tmp/h1.json"): $(tail -1 "$tmp/h1.ref")"
else
  bad "--refine: exit $rc0/$rc1: $(tail -1 "$tmp/h0.err") $(tail -1 "$tmp/h1.err") $(tail -1 "$tmp/h1.ref" 2>/dev/null)"
fi

# --- --diagnose: mpz/holes3 seed 1 fails by a few triangles (without
# refinement rounds, with the surface tree alone: tree qtri would pass);
# the failing cells are drawn and reported, the map is still not written -------------------------------------------------------------
h3=$shared/data/mpz/holes3.obj
"$bin" param "$h3" --cones "$shared/data/mpz/holes3_Th_hat" -o "$tmp/diag.obj" --seed 1 --attempts 1 --refine 0 \
  --tree surface --diagnose "$tmp/diag.svg" --json --quiet >"$tmp/diag.json" 2>"$tmp/diag.err"
if [ $? -eq 3 ] && [ ! -e "$tmp/diag.obj" ] && grep -q "<svg" "$tmp/diag.svg" && grep -q "</svg>" "$tmp/diag.svg" \
    && grep -q "diagnosis (seed 1)" "$tmp/diag.err" \
    && python3 -c '
import json, sys
j = json.load(open(sys.argv[1]))
d = j["diagnosis"]
assert not j["ok"] and d["bad_cells"] >= 1 and d["cells"], j
for c in d["cells"]:
    assert c["bad"] >= 1 and c["faces"] >= c["bad"] and c["rect"][2] > c["rect"][0] and c["rect"][3] > c["rect"][1], c
    assert all(x >= 0 for x in c["side_length"]) and c["runs"] >= 4, c
' "$tmp/diag.json"; then
  ok; echo "PASS --diagnose: $(grep -c '^  cell' "$tmp/diag.err") failing cells reported and drawn, no map written"
else
  bad "--diagnose: $(tail -3 "$tmp/diag.err") $(cat "$tmp/diag.json")"
fi

# --- random admissible cone sets on meshes without cones (CI subset of
# scripts/param_sweep.sh): genus 0, 1, 2, 3, one seed each -----------------
for m in libigl/decimated-knight.off odedstein/torus.obj gpjs/double-torus.obj libigl/3holes.off; do
  mesh=$shared/data/$m
  base=$tmp/rand_$(basename "$m" | sed 's/\.[^.]*$//')
  python3 "$root/scripts/random_cones.py" "$mesh" "${base}_Th_hat" --seed 7 >/dev/null \
    || { bad "$m: random_cones.py"; continue; }
  "$bin" param "$mesh" --cones "${base}_Th_hat" -o "$base.obj" --seed 7 --attempts 1 --quiet >/dev/null 2>"$base.err"
  rc=$?
  if [ $rc -eq 0 ] && python3 "$referee" "$mesh" "${base}_Th_hat" "$base.obj" --integer >"$base.ref" 2>&1; then
    ok; echo "PASS $m (random cones): $(tail -1 "$base.ref")"
  elif [ $rc -eq 3 ] && grep -q "not injective in floating point\|Steiner vertices were needed\|cut graph: .*no route" "$base.err" \
      && [ ! -e "$base.obj" ]; then
    ok; known=$((known + 1)); echo "KNOWN $m (random cones): clean failure, nothing written"
  else
    bad "$m (random cones): $(tail -1 "$base.err") $(tail -1 "$base.ref" 2>/dev/null)"
  fi
done

# --- errors: exit code, message, nothing written ------------------------------
nothing_written() { [ -z "$(ls -A "$tmp/e" 2>/dev/null)" ]; }
mkdir -p "$tmp/e"
knot=$shared/data/mpz/knot1.obj
knot_cones=$shared/data/mpz/knot1_Th_hat
expect() { # expect NAME CODE SUBSTRING -- ARGS...
  local name=$1 code=$2 sub=$3
  shift 4
  "$bin" param "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"
  local rc=$?
  if [ $rc -eq "$code" ] && grep -q -- "$sub" "$tmp/err.txt" && nothing_written; then
    ok; echo "PASS $name"
  else
    bad "$name: exit $rc (want $code), stderr: $(head -c 400 "$tmp/err.txt"); written: $(ls -A "$tmp/e")"
  fi
  rm -rf "$tmp/e" && mkdir -p "$tmp/e"
}
expect "no arguments" 2 "give MESH" --
expect "missing -o" 2 "give MESH" -- "$knot" --cones "$knot_cones"
expect "missing --cones" 2 "give MESH" -- "$knot" -o "$tmp/e/x.obj"
expect "unknown option" 2 "unknown option" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --bogus
expect "bad --seed" 2 "seed" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --seed x
expect "bad --attempts" 2 "attempts" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --attempts 0
expect "bad --refine" 2 "refine" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --refine 65
expect "bad --max-steiner" 2 "max-steiner" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --max-steiner 0
# a Steiner budget the cut cannot keep: a clean failure that names it
# genus 2 with the surface tree alone: its attempt's failure alone
expect "--tree surface (genus 2)" 3 "Steiner vertices" -- "$shared/data/mpz/eight.obj" \
  --cones "$shared/data/mpz/eight_Th_hat" -o "$tmp/e/x.obj" --attempts 1 --max-steiner 50 --tree surface
expect "--max-steiner 10" 3 "more than 10 Steiner vertices" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" \
  --max-steiner 10 --attempts 1 --tree surface
for v in 0 10M 2T abc -1; do
  expect "bad --max-memory $v" 2 "max-memory needs a size" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --max-memory "$v"
done
# a memory limit the overlay cannot keep: refused by its sample before the
# walk allocates, the message naming the limit (fertility_tri's fallback
# expects about 1.6 million crossings; 64M allow 134,217)
if [ "${SQ_SANITIZE:-OFF}" != ON ]; then
  expect "--max-memory 64M (overlay)" 3 "the memory limit: 64 MB allow 134217 crossings" -- \
    "$shared/data/mpz/fertility_tri.obj" --cones "$shared/data/mpz/fertility_tri_Th_hat" -o "$tmp/e/x.obj" \
    --attempts 1 --max-memory 64M
  # the domain checked as soon as it is built: elephant's Q (73,504 quads)
  expect "--max-memory 64M (domain)" 3 "domain: Q has 73504 quads (10904 of padding); Omega and the interior map would need about 140 MB, more than the memory limit of 64 MB" -- \
    "$shared/data/cid/elephant.obj" --cones "$shared/data/cid/elephant_Th_hat" -o "$tmp/e/x.obj" \
    --attempts 1 --max-memory 64M
fi
expect "bad --guide" 2 "guide" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --guide sometimes
expect "bad --tree" 2 "tree" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --tree random
# a crossing budget the overlay cannot keep: a clean failure that names it
expect "--max-crossings 100" 3 "more than 100 crossings" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" \
  --interior overlay --max-crossings 100 --attempts 1
expect "bad --max-crossings" 2 "max-crossings" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --max-crossings 0
expect "bad --variants" 2 "variants" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --variants 0
# a device as the output (/dev/null) is written in place, never replaced
# by a regular file (the staging rename once did that)
if [ -c /dev/null ]; then
  "$bin" param "$shared/data/mpz/eight.obj" --cones "$shared/data/mpz/eight_Th_hat" -o /dev/null --quiet >/dev/null 2>&1
  rc=$?
  if [ $rc -eq 0 ] && [ -c /dev/null ]; then
    ok; echo "PASS -o /dev/null: written, still a character device"
  else
    bad "-o /dev/null: rc=$rc, now $(ls -l /dev/null)"
  fi
fi
# --optimize on: param's map of eight (5,484 faces, mean conformal ratio
# 19.4) optimized and simplified in rounds; the referee passes the map
# written (without --integer: its translations are real), far less
# distorted than the published map's 1.44 and with fewer faces than
# param's; --json "optimize" gives the figures; the integer check fails
# (the translations moved), so the map written is the optimized one
eo=$tmp/eight_opt
if "$bin" param "$shared/data/mpz/eight.obj" --cones "$shared/data/mpz/eight_Th_hat" -o "$eo.obj" \
    --optimize on --json --quiet >"$eo.json" 2>"$eo.err" \
  && python3 "$referee" "$shared/data/mpz/eight.obj" "$shared/data/mpz/eight_Th_hat" "$eo.obj" \
    --json "$eo.ref.json" >"$eo.ref" 2>&1 \
  && python3 -c '
import json, sys
j = json.load(open(sys.argv[1])); o = j["optimize"]
r = json.load(open(sys.argv[2]))["f_stats"]
assert o["faces_after"] < o["faces_before"] == j["faces_out"], o
assert o["conformal_after"] < 1.35 < o["conformal_before"], o
assert abs(r["conformal_mean"] - o["conformal_after"]) < 0.01 * o["conformal_after"], (r, o)
assert r["conformal_mean"] < 1.35 and r["conformal_max"] < 3, r
assert o["integer_translations"] is False and o["iterations"] > 0 and o["rounds"] > 0, o
' "$eo.json" "$eo.ref.json" \
  && ! python3 "$referee" "$shared/data/mpz/eight.obj" "$shared/data/mpz/eight_Th_hat" "$eo.obj" --integer \
    >/dev/null 2>&1; then
  ok; echo "PASS eight --optimize on: $(grep -o 'sigma1/sigma2 max=[^ ]* mean=[^ ]*' "$eo.ref")"
else
  bad "eight --optimize on: $(tail -1 "$eo.err") $(tail -1 "$eo.ref" 2>/dev/null) $(head -c 600 "$eo.json")"
fi
expect "bad --optimize" 2 "optimize" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --optimize maybe
expect "bad --iterations" 2 "iterations" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --optimize on --iterations 0
# tree qtri where the cut walls a cone in (helmet at seed 1): the edges
# between two blocked vertices split at their midpoints, the tree passes
want='j["tree_qtri"] and j["wall_splits"]>0' passes_at helmet 1 --tree qtri
expect "bad --tree" 2 "tree" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --tree pair
expect "bad --simplify" 2 "simplify" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --simplify maybe
expect "two meshes" 2 "unexpected argument" -- "$knot" "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj"
expect "same output twice" 2 "two outputs" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --svg "$tmp/e/x.obj"
expect "missing cones file" 1 "no_such_cones" -- "$knot" --cones "$tmp/no_such_cones" -o "$tmp/e/x.obj"
expect "missing mesh" 1 "no_such_mesh" -- "$tmp/no_such_mesh.obj" --cones "$knot_cones" -o "$tmp/e/x.obj"
expect "cones of another mesh" 1 "$shared/data/mpz/helmet_Th_hat" -- "$knot" --cones "$shared/data/mpz/helmet_Th_hat" -o "$tmp/e/x.obj"
expect "unwritable output" 1 "$tmp/e/nodir/x.obj" -- "$knot" --cones "$knot_cones" -o "$tmp/e/nodir/x.obj"
expect "unwritable svg" 1 "$tmp/e/nodir/x.svg" -- "$knot" --cones "$knot_cones" -o "$tmp/e/x.obj" --svg "$tmp/e/nodir/x.svg"
# the broken inputs of tests/data/broken/EXPECTED.tsv: the same errors as check
while IFS=$'\t' read -r mesh cones status sub; do
  case "$mesh" in \#*|"") continue ;; esac
  if [ "$cones" = - ]; then c=$knot_cones; else c=$root/$cones; fi
  expect "$(basename "$mesh") + $(basename "$c") ($status)" 1 "$sub" -- "$root/$mesh" --cones "$c" \
    -o "$tmp/e/x.obj" --svg "$tmp/e/x.svg"
done <"$data/broken/EXPECTED.tsv"
# --json reports the error too
"$bin" param "$root/tests/data/torus.obj" --cones "$data/broken/torus_gauss_bonnet.cones" -o "$tmp/e/x.obj" \
  --json >"$tmp/gb.json" 2>/dev/null
python3 -c '
import json, sys
j = json.load(open(sys.argv[1]))
assert not j["ok"] and j["error"]["code"] == "gauss-bonnet", j' "$tmp/gb.json" && nothing_written \
  && { ok; echo "PASS --json error"; } || bad "--json error: $(cat "$tmp/gb.json")"
"$bin" param --help | grep -q "check_param.py" && { ok; echo "PASS --help"; } || bad "--help"
"$bin" --help | grep -q "param .*parametrization" && { ok; echo "PASS listed"; } || bad "not listed in seamquad --help"

echo "cli_param: $pass passed ($known of them known clean failures, docs/param.md), $fail failed"
[ $fail -eq 0 ]
