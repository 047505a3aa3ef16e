#!/usr/bin/env bash
# The combinatorial domain (seamquad domain) on every cone file of
# ../shared/data: quads before and after padding and the time of the
# construction (median of N runs; the domain only, not reading the mesh or
# writing files), beside the seed's Table 1. Builds in Release mode.
# usage: bench/bench_domain.sh [N]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SQ_SHARED_DIR:-$root/../shared}
reps=${1:-5}
build=$root/build-bench
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSQ_WITH_OPENMESH=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target seamquad >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$build/bin/seamquad" "$shared" "$tmp" "$reps" <<'PY'
import json, statistics, subprocess, sys
bin_, shared, tmp, reps = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
# seed Table 1: cones, genus, #F init, #F pad, time (s) (geometrically guided,
# time includes the seed's surface work)
seed = {"helmet": (9, 3, 220, 1452, 0.13), "genus3": (22, 3, 348, 576, 0.25),
        "holes3": (24, 3, 452, 1120, 0.3), "block": (46, 3, 2568, 2288, 0.7),
        "fertility_tri": (60, 4, 2332, 3952, 1.2), "elephant": (125, 3, 15000, 63000, 12)}
rows = []
for line in open(shared + "/data/MANIFEST.tsv"):
    f = line.rstrip("\n").split("\t")
    if f[0] == "file" or f[7] != "yes" or f[9] == "-":
        continue
    mesh = shared + "/data/" + f[0]
    cones = mesh.rsplit("/", 1)[0] + "/" + f[9]
    name = f[0].rsplit("/", 1)[1].rsplit(".", 1)[0]
    times, j = [], None
    for _ in range(reps):
        p = subprocess.run([bin_, "domain", mesh, "--cones", cones, "-o", tmp + "/d",
                            "--no-svg", "--json"], capture_output=True, text=True)
        j = json.loads(p.stdout) if p.stdout.strip() else {"ok": False}
        if not j.get("ok"):
            break
        times.append(j["time_domain_s"])
    if not j.get("ok"):
        err = j.get("error", {}).get("message", p.stderr.strip())
        rows.append((f[0], f[8], f[10], "-", "-", "-", err[:60]))
        continue
    rows.append((f[0], f[8], str(j["cones"]), str(j["quads_before_padding"]),
                 str(j["quads_added_by_padding"]), "%.1f" % (1e3 * statistics.median(times)),
                 name))
print("| model | genus | cones | quads init | quads pad | time (ms) | seed: cones, init + pad, time |")
print("|---|---:|---:|---:|---:|---:|---|")
for r in rows:
    s = seed.get(r[6].split()[0] if r[5] != "-" else "", None)
    ref = "%d, %d + %d, %.2f s" % (s[0], s[2], s[3], s[4]) if s else ""
    if r[5] == "-":
        print("| %s | %s | %s | - | - | - | %s |" % (r[0], r[1], r[2], r[6]))
    else:
        print("| %s | %s | %s | %s | %s | %s | %s |" % (r[0], r[1], r[2], r[3], r[4], r[5], ref))
PY
