#!/usr/bin/env bash
# Lucerna: repeatable instruction counts of the render loop (callgrind, 1 thread), per camera
# sample, for judging CPU optimizations on a shared, noisy machine.
# Usage: bench/instr_count.sh [BIN] [RES] [SPP]   (defaults: build-perf/lucerna 32x32 4)
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=data   # the shared scenes (data/README.md)
BIN=${1:-build-perf/lucerna}
RES=${2:-32x32}
SPP=${3:-4}
out=$(mktemp -d)
printf "%-42s %9s %5s %14s %12s\n" scene res spp instructions instr/sample
# scene-v4.pbrt: the scene's own sampler ("sobol" -> ZSobol); ref-*.pbrt: what pbrt-v4 rendered
# for the references (independent sampler).
for scene in bitterli-cornell-box/scene-v4 bitterli-veach-mis/scene-v4 bitterli-cornell-box/ref-cornell-box \
             bitterli-veach-mis/ref-veach-mis; do
  valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" --toggle-collect='tbb::detail::r1::execute_and_wait*' \
    "$BIN" render "$DATA/scenes/$scene.pbrt" --res "$RES" --spp "$SPP" --threads 1 -q \
    -o "$out/img.exr" >/dev/null 2>"$out/log"
  ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$out/log")
  w=${RES%x*}; h=${RES#*x}
  printf "%-42s %9s %5s %14s %12.0f\n" "$scene" "$RES" "$SPP" "$ir" "$(echo "$ir / ($w * $h * $SPP)" | bc -l)"
done
rm -rf "$out"
