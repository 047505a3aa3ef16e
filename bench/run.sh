#!/usr/bin/env bash
# Builds the benchmarks in Release mode into build-bench/ and runs sq_bench_io.
# Arguments go to sq_bench_io, e.g.:  bench/run.sh --reps 30 --json FILE...
# SQ_SHARED_DIR (environment) overrides the shared/ folder used for the
# default files.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-bench"
args=(-DCMAKE_BUILD_TYPE=Release -DSQ_WITH_OPENMESH=OFF)
if [[ -n "${SQ_SHARED_DIR:-}" ]]; then
  args+=("-DSQ_SHARED_DIR=$SQ_SHARED_DIR")
fi
cmake -S "$root" -B "$build" "${args[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" --target sq_bench_io >/dev/null
exec "$build/bin/sq_bench_io" "$@"
