#!/usr/bin/env bash
# seamquad param's modes beside its defaults, on every cone file of a closed
# mesh in ../shared/data (mpz/twirl left out: refused by design). Each mode
# is one set of extra flags; each model runs once per mode (timeout 300 s).
# Prints a markdown table per model (result, mean conformal ratio, faces
# out, wall time, peak RSS) and, per mode, where it wins against the
# defaults: it passes where they fail, or its map is at least 10% less
# distorted, or it is at least 25% faster with a map no more distorted.
# A mode that never wins has no reason to exist (DEVELOPERS.md).
# Builds in Release mode into build-bench/ (or uses $SQ_BIN).
# usage: bench/bench_param_modes.sh [MODEL_SUBSTRING...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SQ_SHARED_DIR:-$root/../shared}
build=$root/build-bench
if [ -z "${SQ_BIN:-}" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSQ_WITH_OPENMESH=OFF >/dev/null
  cmake --build "$build" -j"$(nproc)" --target seamquad >/dev/null
fi
bin=${SQ_BIN:-$build/bin/seamquad}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); one run per model and mode"
echo
python3 - "$bin" "$shared" "$tmp" "$@" <<'PY'
import json, os, signal, subprocess, sys, time
bin_, shared, tmp, only = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
modes = [("default", []),
         ("tree surface", ["--tree", "surface"]),
         ("tree qtri", ["--tree", "qtri"]),
         ("interior cells", ["--interior", "cells"]),
         ("interior overlay", ["--interior", "overlay"]),
         ("variants 1", ["--variants", "1"]),
         ("fans off", ["--fans", "off"])]
models = []
for line in open(shared + "/data/MANIFEST.tsv"):
    f = line.rstrip("\n").split("\t")
    if f[0] == "file" or f[7] != "yes" or f[9] == "-" or f[0] == "mpz/twirl.obj":
        continue
    if only and not any(s in f[0] for s in only):
        continue
    models.append((f[0], f[9]))
models.sort()

def run(mesh, cfile, flags):
    """one `param` run; (ok, conformal mean, faces out, wall s, peak MB, why)"""
    t0 = time.time()
    with open(tmp + "/out.json", "w") as out, open(tmp + "/err.txt", "w") as errf:
        p = subprocess.Popen([bin_, "param", mesh, "--cones", cfile, "-o", tmp + "/p.obj", "--json",
                              "--quiet"] + flags, stdout=out, stderr=errf, start_new_session=True)
        killed = False
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if not killed and time.time() - t0 > 300:
                os.killpg(p.pid, signal.SIGKILL)
                killed = True
            time.sleep(0.02)
    wall = time.time() - t0
    rss = ru.ru_maxrss / 1024.0
    try:
        j = json.load(open(tmp + "/out.json"))
    except ValueError:
        return (False, None, None, wall, rss, "killed at 300 s" if killed
                else open(tmp + "/err.txt").read().strip()[-60:])
    if not j.get("ok"):
        return (False, None, None, wall, rss, j.get("error", {}).get("message", "")[:60])
    return (True, j["distortion"]["conformal_mean"], j["faces_out"], wall, rss, "")

res = {}
print("| model | mode | result | conformal mean | faces out | wall (s) | peak RSS (MB) |")
print("|---|---|---|---:|---:|---:|---:|")
for path, cones in models:
    mesh = shared + "/data/" + path
    cfile = mesh.rsplit("/", 1)[0] + "/" + cones
    for name, flags in modes:
        r = run(mesh, cfile, flags)
        res[(path, name)] = r
        ok, conf, faces, wall, rss, why = r
        print("| %s | %s | %s | %s | %s | %.2f | %.0f |" % (
            path, name, "PASS" if ok else "FAIL: " + why.replace("|", "/"),
            "%.3g" % conf if ok else "", str(faces) if ok else "", wall, rss), flush=True)
print()
print("| mode | passes | wins against the defaults |")
print("|---|---:|---|")
for name, _ in modes[1:]:
    wins = []
    for path, _ in models:
        d, m = res[(path, "default")], res[(path, name)]
        if not m[0]:
            continue
        if not d[0]:
            wins.append(path + " (passes)")
        elif m[1] <= 0.9 * d[1]:
            wins.append("%s (%.3g vs %.3g)" % (path, m[1], d[1]))
        elif m[3] <= 0.75 * d[3] and m[1] <= d[1] * 1.0001:
            wins.append("%s (%.2f s vs %.2f s)" % (path, m[3], d[3]))
    print("| %s | %d of %d | %s |" % (name, sum(res[(p, name)][0] for p, _ in models), len(models),
                                      ", ".join(wins) or "none"))
PY
echo
echo "command: bench/bench_param_modes.sh $*"
