#!/usr/bin/env bash
# Benchmark of `seamquad subdiv` (docs/subdiv.md): one uniform Catmull-Clark
# step by OpenSubdiv turns a ~5K-quad QuadriFlow mesh into ~20K quads, then
# patches (isolation 6), seam report, limit mesh (level 2), STEP and IGES
# export are timed, with file sizes and peak RSS. Usage:
#   bench/bench_subdiv.sh [SEAMQUAD_BINARY]   (default build/bin/seamquad)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/bin/seamquad}
shared=${SQ_SHARED_DIR:-$root/../shared}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for m in bunny fertility; do
  /usr/bin/time -f "peak RSS %M KiB, wall %e s" "$bin" subdiv "$shared/data/quads/${m}_quadriflow5k.obj" \
    --refine 1 --isolation 6 --step "$tmp/$m.step" --iges "$tmp/$m.igs" --limit "$tmp/$m.obj" --level 2
done
