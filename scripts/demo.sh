#!/usr/bin/env bash
# Fresh Debian 12: install what the renderer needs, build only build/lucerna (Release), and render
# the demo scene to out/ twice at equal time: plain path tracing, then regularized path tracing.
# The CUDA backend is built only when a GPU answers `nvidia-smi -L` and nvcc is present (for that
# GPU's architecture only), or when asked: LUCERNA_CUDA=ON scripts/demo.sh. LUCERNA_CUDA=OFF: never.
# DEMO_SECONDS: render time of each image (default 20).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
elapsed() { echo "$(( $(date +%s) - start ))s"; }

scripts/setup.sh demo

gpu=0
if command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L >/dev/null 2>&1; then gpu=1; fi
cuda=${LUCERNA_CUDA:-}
if [ -z "$cuda" ]; then
  if [ $gpu = 1 ] && { command -v nvcc >/dev/null 2>&1 || [ -x /usr/local/cuda/bin/nvcc ]; }; then cuda=ON; else cuda=OFF; fi
fi
args=(-DLUCERNA_TESTS=OFF -DLUCERNA_BENCH=OFF -DLUCERNA_CUDA="$cuda")
if [ "$cuda" = ON ] && [ $gpu = 1 ]; then args+=(-DCMAKE_CUDA_ARCHITECTURES=native); fi
echo "demo: building build/lucerna (CUDA backend: $cuda) at $(elapsed)"
TARGET=lucerna scripts/build.sh "${args[@]}"
echo "demo: built at $(elapsed)"

mkdir -p out
SECONDS_EACH=${DEMO_SECONDS:-20}
build/lucerna render scenes/demo/demo.pbrt --integrator path    --time "$SECONDS_EACH" -o out/demo_path.exr    --png
echo "demo: wrote out/demo_path.{exr,png} at $(elapsed)"
build/lucerna render scenes/demo/demo.pbrt --integrator regpath --time "$SECONDS_EACH" -o out/demo_regpath.exr --png
echo "demo: wrote out/demo_regpath.{exr,png} at $(elapsed) (${SECONDS_EACH}s of rendering each)"
