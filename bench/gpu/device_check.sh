#!/usr/bin/env bash
# One prepared GPU session (docs/gpu.md): the GPU tests, a memory check of the megakernel, the
# BVH and render benchmarks (GPU against the same machine's CPU), equal-time demo renders on the
# GPU and one Nsight Compute profile, each step under its own time limit so that one slow step
# cannot eat the others. Nothing is built here: BUILD holds lucerna and tests/test_gpu, configured
# with -DLUCERNA_CUDA=ON (a build directory, or binaries carried from one; LD_LIBRARY_PATH finds
# their libraries). Logs and images go to OUT.
# Usage: bench/gpu/device_check.sh [BUILD] [OUT]      (defaults: build, out/gpu)
# Environment: STEPS (space-separated subset of: tests memcheck bench rays demo profile; default all),
#   DEMO_SECONDS (8).
set -uo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build}
OUT=${2:-out/gpu}
STEPS=${STEPS:-"tests memcheck bench rays demo profile"}
DEMO_SECONDS=${DEMO_SECONDS:-8}
mkdir -p "$OUT"
BIN="$BUILD/lucerna"
CORNELL=data/scenes/bitterli-cornell-box/scene-v4.pbrt
want() { [[ " $STEPS " == *" $1 "* ]]; }
step() { echo; echo "== $* ($(date -u +%H:%M:%S))"; }

step "device"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader || true
echo "CPU: $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
for exe in "$BIN" "$BUILD/tests/test_gpu"; do   # do the binaries start here (their libraries found)?
  "$exe" --help >/dev/null 2>&1 || { echo "$exe does not start:"; "$exe" --help 2>&1 | tail -3; exit 1; }
done

if want tests; then
  step "test_gpu (GPU tests; CPU-only tests of this binary run in CI)"
  timeout 200 "$BUILD/tests/test_gpu" --gtest_filter='Gpu*.*' 2>&1 | tee "$OUT/test_gpu.log" | grep -vE '^\[ RUN' | sed -n 1,150p
  echo "test_gpu exit: ${PIPESTATUS[0]}"
fi

if want memcheck && command -v compute-sanitizer >/dev/null; then
  step "compute-sanitizer memcheck, path and regpath, 32x32 x 2 spp"
  for integ in path regpath; do
    timeout 60 compute-sanitizer --tool memcheck --leak-check no --error-exitcode 9 \
      "$BIN" render data/scenes/smallvcm-cornell/smallvcm-bs_c.pbrt --res 32x32 --spp 2 --integrator "$integ" \
      --device cuda -q -o /tmp/memcheck.exr 2>&1 | tail -4
    echo "memcheck $integ exit: ${PIPESTATUS[0]}"
  done
fi

if want bench; then
  for integ in path regpath; do
    step "render_bench: $integ, 1024x1024, GPU 64 spp, CPU 4 spp"
    SKIP_BUILD=1 INTEGRATOR=$integ RES=1024x1024 SPP=64 CPU_SPP=4 timeout 200 bench/gpu/render_bench.sh "$BUILD" 2>&1 | \
      tee "$OUT/render_bench_${integ}_1024.txt"
  done
fi

if want rays; then
  step "GPU BVH rays/s (primary, incoherent, shadow; bench/gpu/rays_bench.sh without its single-thread CPU part)"
  timeout 90 "$BUILD/tests/test_gpu" --gtest_also_run_disabled_tests --gtest_filter='GpuBVH.DISABLED_RaysPerSecond' 2>&1 | \
    tee "$OUT/rays_gpu.txt" | grep -E '^\[ (bvh|rays/s) |FAILED|SKIPPED'
fi

if want demo; then
  step "demo at equal time on the GPU (${DEMO_SECONDS} s each)"
  for integ in path regpath; do
    timeout $((DEMO_SECONDS + 60)) "$BIN" render scenes/demo/demo.pbrt --integrator "$integ" --time "$DEMO_SECONDS" \
      --device cuda -q -o "$OUT/demo_gpu_$integ.exr" --png --stats-json "$OUT/demo_gpu_$integ.json" 2>&1 | tail -3
  done
fi

if want profile && command -v ncu >/dev/null; then
  step "Nsight Compute: PathKernel, cornell-box 1024x1024, third pass"
  timeout 90 ncu --clock-control none --kernel-name regex:PathKernel --launch-skip 2 --launch-count 1 \
    --section SpeedOfLight --section Occupancy --section LaunchStats --section WarpStateStats \
    --section SchedulerStats --section MemoryWorkloadAnalysis \
    "$BIN" render "$CORNELL" --res 1024x1024 --spp 4 --device cuda -q -o /tmp/ncu.exr 2>&1 | \
    tee "$OUT/ncu_cornell.txt" | grep -vE '^==PROF==' | sed -n 1,120p
fi
step "done"
