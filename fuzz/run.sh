#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan+UBSan) in build-fuzz, replays fuzz/regressions, then
# runs each target for SECONDS with a seed corpus from the shared scenes and fuzz/seeds.
# Usage: fuzz/run.sh SECONDS [JOBS]   (JOBS > 1 runs the two targets at the same time)
# Crashes are written to build-fuzz/fuzz-work/crash-*; minimize one with
#   build-fuzz/fuzz/fuzz_scene -minimize_crash=1 -runs=20000 CRASHFILE
# and keep the result in fuzz/regressions/ (replayed here and by the scene tests).
set -euo pipefail
secs=${1:?usage: fuzz/run.sh SECONDS [JOBS]}
jobs=${2:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
shared=$root/data   # the shared scenes (data/README.md)
build=$root/build-fuzz

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DLUCERNA_FUZZ=ON -DLUCERNA_CUDA=OFF \
    -DLUCERNA_BENCH=OFF -DLUCERNA_TESTS=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target fuzz_scene fuzz_ply fuzz_gzip -j2

work=$build/fuzz-work
mkdir -p "$work/seed-scene" "$work/seed-ply" "$work/seed-gzip" "$work/corpus-scene" "$work/corpus-ply" "$work/corpus-gzip"
# Seeds: the small shared scene files; PLY headers with small bodies (the small shared meshes
# whole, the first 2 KiB of the large ones) and the hand-made files in fuzz/seeds.
while IFS= read -r -d "" f; do cp -f "$f" "$work/seed-scene/$(basename "$(dirname "$f")")-$(basename "$f")"; done < <(find "$shared/scenes" -name "*.pbrt" -size -64k -print0 2>/dev/null)
cp -f "$root"/fuzz/seeds/*.pbrt "$work/seed-scene/"
i=0
while IFS= read -r -d '' f; do
    i=$((i + 1))
    head -c 2048 "$f" > "$work/seed-ply/shared$i.ply"
done < <(find "$shared/scenes" -name '*.ply' -print0 2>/dev/null)
find "$shared/scenes" -name '*.ply' -size -20k -exec cp -f {} "$work/seed-ply/" \; 2>/dev/null || true
cp -f "$root"/fuzz/seeds/*.ply "$work/seed-ply/"
cp -f "$root"/fuzz/seeds/*.gz "$work/seed-gzip/"

# Replay the regression inputs first: any crash here is a regression.
for t in fuzz_scene fuzz_ply fuzz_gzip; do
    "$build/fuzz/$t" -runs=0 "$root/fuzz/regressions" "$root/fuzz/seeds" 2>&1 | tail -1
done

run() {  # target corpus seeds dict maxlen
    "$build/fuzz/$1" -max_total_time="$secs" -max_len="$5" -timeout=10 -rss_limit_mb=2048 \
        -dict="$root/fuzz/$4" -artifact_prefix="$work/crash-$1-" -print_final_stats=1 \
        "$work/$2" "$work/$3" > "$work/$1.log" 2>&1
}
status=0
if [ "$jobs" -gt 1 ]; then
    run fuzz_scene corpus-scene seed-scene pbrt.dict 16384 & p1=$!
    run fuzz_ply corpus-ply seed-ply ply.dict 8192 & p2=$!
    wait $p1 || status=1
    wait $p2 || status=1
    run fuzz_gzip corpus-gzip seed-gzip gzip.dict 4096 || status=1
else
    run fuzz_scene corpus-scene seed-scene pbrt.dict 16384 || status=1
    run fuzz_ply corpus-ply seed-ply ply.dict 8192 || status=1
    run fuzz_gzip corpus-gzip seed-gzip gzip.dict 4096 || status=1
fi
for t in fuzz_scene fuzz_ply fuzz_gzip; do
    echo "== $t: $(grep -E '^Done [0-9]+ runs' "$work/$t.log" | tail -1)" \
         "$(grep -E 'stat::number_of_executed_units' "$work/$t.log" | tail -1)"
    grep -E 'ERROR|SUMMARY|Test unit written' "$work/$t.log" | head -5 || true
done
exit $status
