#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan+UBSan) in build-fuzz, replays fuzz/regressions and
# fuzz/seeds through each, then runs each target for SECONDS from a seed corpus: the small shared
# scenes, the hand-made files in fuzz/seeds (features, and the bad inputs of issue 15: singular
# transforms, negative light scales, partial spectra, no lights, an empty file, corrupted and old
# checkpoints) and the corpus kept from earlier runs in build-fuzz/fuzz-work.
# Usage: fuzz/run.sh SECONDS [JOBS]   (JOBS > 1 runs that many targets at the same time)
# Environment: TARGETS="fuzz_scene fuzz_build" (default: all five); RUNS=N stops each target
# after N executions instead of SECONDS (pass 0 for SECONDS); NICE=19 runs the fuzzers niced;
# TIMEOUT=S (default 10) is libFuzzer's per-input wall-clock limit: raise it for niced runs on a
# loaded machine (at nice 19 under load 12 a 0.1 s-CPU input took 11 s of wall time).
# Crashes are written to build-fuzz/fuzz-work/crash-TARGET-*; minimize one with
#   build-fuzz/fuzz/fuzz_scene -minimize_crash=1 -runs=20000 CRASHFILE
# and keep the result in fuzz/regressions/ (replayed here and by ctest -L fuzz in build-fuzz).
set -euo pipefail
secs=${1:?usage: fuzz/run.sh SECONDS [JOBS]}
jobs=${2:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
shared=$root/data   # the shared scenes (data/README.md)
build=$root/build-fuzz
targets=(${TARGETS:-fuzz_scene fuzz_ply fuzz_gzip fuzz_build fuzz_checkpoint})

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DLUCERNA_FUZZ=ON -DLUCERNA_CUDA=OFF \
    -DLUCERNA_BENCH=OFF -DLUCERNA_TESTS=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target "${targets[@]}" -j2

work=$build/fuzz-work
mkdir -p "$work"
for d in seed-scene seed-ply seed-ckpt seed-gzip corpus-scene corpus-ply corpus-gzip corpus-build corpus-checkpoint; do mkdir -p "$work/$d"; done
# Seeds: the small shared scene files; PLY headers with small bodies (the small shared meshes
# whole, the first 2 KiB of the large ones) and the hand-made files in fuzz/seeds.
while IFS= read -r -d "" f; do cp -f "$f" "$work/seed-scene/$(basename "$(dirname "$f")")-$(basename "$f")"; done < <(find "$shared/scenes" -name "*.pbrt" -size -64k -print0 2>/dev/null)
cp -f "$root"/fuzz/seeds/*.pbrt "$root"/fuzz/regressions/*.pbrt "$work/seed-scene/"
i=0
while IFS= read -r -d '' f; do
    i=$((i + 1))
    head -c 2048 "$f" > "$work/seed-ply/shared$i.ply"
done < <(find "$shared/scenes" -name '*.ply' -print0 2>/dev/null)
find "$shared/scenes" -name '*.ply' -size -20k -exec cp -f {} "$work/seed-ply/" \; 2>/dev/null || true
cp -f "$root"/fuzz/seeds/*.ply "$work/seed-ply/"
cp -f "$root"/fuzz/seeds/*.gz "$work/seed-gzip/"
cp -f "$root"/fuzz/seeds/*.ckpt "$work/seed-ckpt/"

# Replay the regression inputs first: any crash here is a regression.
for t in "${targets[@]}"; do
    "$build/fuzz/$t" -runs=0 "$root/fuzz/regressions" "$root/fuzz/seeds" 2>&1 | tail -1
done

run() {  # target corpus seeds dict maxlen
    local limit=(-max_total_time="$secs")
    [ "${RUNS:-0}" != 0 ] && limit=(-runs="$RUNS")
    local dict=()
    [ -n "$4" ] && dict=(-dict="$root/fuzz/$4")
    nice -n "${NICE:-0}" "$build/fuzz/$1" "${limit[@]}" -max_len="$5" -timeout="${TIMEOUT:-10}" -rss_limit_mb=2048 \
        "${dict[@]}" -artifact_prefix="$work/crash-$1-" -print_final_stats=1 \
        "$work/$2" "$work/$3" > "$work/$1.log" 2>&1
}
args_for() {
    case $1 in
        fuzz_scene) echo "corpus-scene seed-scene pbrt.dict 16384" ;;
        fuzz_ply) echo "corpus-ply seed-ply ply.dict 8192" ;;
        fuzz_gzip) echo "corpus-gzip seed-gzip gzip.dict 4096" ;;
        fuzz_build) echo "corpus-build seed-scene pbrt.dict 16384" ;;
        fuzz_checkpoint) echo "corpus-checkpoint seed-ckpt '' 4096" ;;
    esac
}
status=0
pids=()
for t in "${targets[@]}"; do
    eval "set -- $(args_for "$t")"
    if [ "$jobs" -gt 1 ]; then
        run "$t" "$1" "$2" "$3" "$4" & pids+=($!)
        if [ ${#pids[@]} -ge "$jobs" ]; then wait "${pids[0]}" || status=1; pids=("${pids[@]:1}"); fi
    else
        run "$t" "$1" "$2" "$3" "$4" || status=1
    fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
for t in "${targets[@]}"; do
    echo "== $t: $(grep -E '^Done [0-9]+ runs' "$work/$t.log" | tail -1)" \
         "$(grep -E 'stat::number_of_executed_units' "$work/$t.log" | tail -1)"
    grep -E 'ERROR|SUMMARY|Test unit written' "$work/$t.log" | head -5 || true
done
exit $status
