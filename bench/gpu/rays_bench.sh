#!/usr/bin/env bash
# Lucerna BVH benchmark: BVH statistics and build times, single-thread CPU Mrays/s of the shared
# traversal (SBVH and binned) next to Embree, and, with a CUDA device, GPU Mrays/s of primary,
# incoherent and shadow rays (1024x1024 rays x 8 passes) on every shared scene.
# Usage: bench/gpu/rays_bench.sh [BUILD_DIR]   (default build; configure with -DLUCERNA_CUDA=ON for GPU numbers)
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build}
[ -n "${SKIP_BUILD:-}" ] || cmake --build "$BUILD" --target test_gpu -j"$(nproc)" >/dev/null  # SKIP_BUILD=1: binaries built elsewhere (bench/gpu/device_check.sh)
"$BUILD/tests/test_gpu" --gtest_also_run_disabled_tests \
    --gtest_filter='BVHSharedScenes.MatchEmbree:BVHSharedScenes.DISABLED_CpuThroughput:GpuBVH.DISABLED_RaysPerSecond' \
    | grep -E '^\[ (bvh|cpu Mr/s|rays/s) ' || true
"$BUILD/tests/test_gpu" --gtest_filter='GpuBVH.*' 2>&1 | grep -E 'SKIPPED|no usable|without CUDA' | head -1 || true
