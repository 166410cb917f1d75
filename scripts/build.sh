#!/usr/bin/env bash
# Configures and builds Lucerna (Release) into build/. The CUDA backend is compiled whenever
# nvcc is found (/usr/local/cuda); a machine without it still builds the CPU renderer.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$BUILD" -j "$JOBS"
