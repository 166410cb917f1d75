#!/usr/bin/env bash
# Fresh Debian 12: install dependencies, build Release, render the bundled demo scene to out/
# with plain path tracing and with regularized path tracing at equal time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
SECONDS_EACH=${DEMO_SECONDS:-20}
build/lucerna render scenes/demo/demo.pbrt --integrator path    --time "$SECONDS_EACH" -o out/demo_path.exr    --png
build/lucerna render scenes/demo/demo.pbrt --integrator regpath --time "$SECONDS_EACH" -o out/demo_regpath.exr --png
echo "demo: wrote out/demo_path.{exr,png} and out/demo_regpath.{exr,png} (${SECONDS_EACH}s each)"
