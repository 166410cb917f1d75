#!/usr/bin/env bash
# Configures and builds Lucerna (Release) into build/ (BUILD_DIR). Arguments go to cmake's
# configure step; TARGET=NAME builds only that target (scripts/demo.sh: TARGET=lucerna), else
# everything. The CUDA backend is compiled whenever nvcc is found (/usr/local/cuda) unless
# -DLUCERNA_CUDA=OFF; a machine without it still builds the CPU renderer.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
if [ -n "${TARGET:-}" ]; then
  cmake --build "$BUILD" -j "$JOBS" --target "$TARGET"
else
  cmake --build "$BUILD" -j "$JOBS"
fi
