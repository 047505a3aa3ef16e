#!/usr/bin/env bash
# seamquad param on every cone file of a closed mesh in ../shared/data (the
# seed's Table-1 models mpz/block, fertility_tri, genus3, helmet, holes3 and
# cid/elephant first, then the other models with cones; mpz/twirl is left
# out: its valence-1 cone is refused by design). Prints a markdown table:
# result (and the interior map kept: cells or overlay), attempts, mean
# conformal ratio of the map, time per step (of the successful attempt) and wall time
# in total (median of N runs), peak RSS,
# faces in, as built and out (after simplification), quads of the domain,
# beside the seed's Table 1. Default
# options (up to 16 attempts with the next cut-graph seed, guidance auto);
# a failed model shows the wall time and memory until its clean failure, and
# the domain of its last attempt (--json "last_attempt").
# Builds in Release mode into build-bench/.
# usage: bench/bench_param.sh [N]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SQ_SHARED_DIR:-$root/../shared}
reps=${1:-3}
build=$root/build-bench
if [ -z "${SQ_BIN:-}" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSQ_WITH_OPENMESH=OFF >/dev/null
  cmake --build "$build" -j"$(nproc)" --target seamquad >/dev/null
fi
bin=${SQ_BIN:-$build/bin/seamquad}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); $reps runs per model (median)"
echo
python3 - "$bin" "$shared" "$tmp" "$reps" <<'PY'
import json, os, statistics, subprocess, sys, time
bin_, shared, tmp, reps = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
# seed Table 1: cones, genus, #F input, #F init, #F pad, time (s)
seed = {"helmet": (9, 3, 1.6e3, 220, 1452, 0.13), "genus3": (22, 3, 13e3, 348, 576, 0.25),
        "holes3": (24, 3, 12e3, 452, 1120, 0.3), "block": (46, 3, 4.6e3, 2568, 2288, 0.7),
        "fertility_tri": (60, 4, 28e3, 2332, 3952, 1.2), "elephant": (125, 3, 50e3, 15000, 63000, 12)}
table1 = ["mpz/block.obj", "mpz/fertility_tri.obj", "mpz/genus3.obj", "mpz/helmet.obj",
          "mpz/holes3.obj", "cid/elephant.obj"]
models = []
for line in open(shared + "/data/MANIFEST.tsv"):
    f = line.rstrip("\n").split("\t")
    if f[0] == "file" or f[7] != "yes" or f[9] == "-" or f[0] == "mpz/twirl.obj":
        continue
    models.append((f[0], f[9]))
models.sort(key=lambda m: (m[0] not in table1, m[0]))
steps = ["cut", "domain", "omega", "tree", "boundary", "cells", "tutte", "check", "overlay", "simplify"]

def run(mesh, cfile):
    """one `param` run with the default options; (json or None, wall s, peak RSS MB)"""
    t0 = time.time()
    with open(tmp + "/out.json", "w") as out, open(tmp + "/err.txt", "w") as errf:
        p = subprocess.Popen([bin_, "param", mesh, "--cones", cfile, "-o", tmp + "/p.obj", "--json",
                              "--quiet"], stdout=out, stderr=errf)
        _, status, ru = os.wait4(p.pid, 0)
    wall = time.time() - t0
    try:
        j = json.load(open(tmp + "/out.json"))
    except ValueError:
        j = {"ok": False, "error": {"message": open(tmp + "/err.txt").read().strip()}}
    return j, wall, ru.ru_maxrss / 1024.0

print("| model | genus | cones | result (interior map) | attempts | faces in | faces built | faces out | Steiner | conformal mean | quads (init + pad) | "
      + " | ".join(steps) + " | total (s) | peak RSS (MB) | seed Table 1: init + pad, time |")
print("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|" + "---:|" * len(steps) + "---:|---:|---|")
for path, cones in models:
    mesh = shared + "/data/" + path
    cfile = mesh.rsplit("/", 1)[0] + "/" + cones
    name = path.rsplit("/", 1)[1].rsplit(".", 1)[0]
    runs = [run(mesh, cfile) for _ in range(reps)]
    s = seed.get(name)
    ref = "%d + %d, %.2f s" % (s[3], s[4], s[5]) if s else ""
    wall = statistics.median(r[1] for r in runs)
    rss = max(r[2] for r in runs)
    j = runs[0][0]
    if not j.get("ok"):
        msg = j.get("error", {}).get("message", "")
        why = ("not injective in doubles" if "not injective" in msg else
               "Steiner budget" if "Steiner" in msg else msg[:40].replace("|", "/"))
        la = j.get("last_attempt", {})
        quads = "%d + %d" % (la["quads_before_padding"], la["quads_added_by_padding"]) if la else ""
        cells = ([path, str(la.get("genus", "")), str(la.get("cones", "")), "FAIL: " + why,
                  str(la.get("attempts", ""))] + [""] * 5 + [quads] + [""] * len(steps)
                 + ["%.2f" % wall, "%.0f" % rss, ref])
        print("| " + " | ".join(cells) + " |")
        continue
    med = lambda key: statistics.median(r[0]["time_s"][key] for r in runs)
    print("| %s | %d | %d | PASS (%s) | %d (seed %d) | %d | %d | %d | %d | %.3g | %d + %d | %s | %.2f | %.0f | %s |" % (
        path, j["genus"], j["cones"], j["interior"], j["attempts"], j["seed_used"], j["faces_in"],
        j["faces_unsimplified"] or j["faces_out"], j["faces_out"], j["steiner"], j["distortion"]["conformal_mean"],
        j["quads_before_padding"], j["quads_added_by_padding"],
        " | ".join("%.3f" % med(k) for k in steps), wall, rss, ref))
PY
echo
echo "command: bench/bench_param.sh $reps"
