#!/usr/bin/env bash
# Lucerna render benchmark, GPU against CPU: rays/s (camera + extension + shadow rays, as
# RenderStats counts them) and samples/s of `lucerna render` on every shared scene and on a
# generated terrain of 1,048,352 triangles whose BVH exceeds the GPU's L2 (bench/gpu/make_terrain.py),
# with --device cpu (Embree, all cores) and --device cuda (only when a usable GPU exists), and the
# GPU/CPU ratio. Times exclude scene loading and the BVH build (RenderStats::seconds).
# Usage: bench/gpu/render_bench.sh [BUILD_DIR]   (configure BUILD_DIR with -DLUCERNA_CUDA=ON for GPU numbers)
# Environment: RES (512x512), SPP (16), CPU_SPP (default SPP; fewer keeps slow CPUs short, rates stay
# comparable), INTEGRATOR (path or regpath), TERRAIN_N (724: 2 N^2 triangles), SCENES (space-separated
# subset of the shared scene files, paths under data/scenes/).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build}
DATA=data   # the shared scenes (data/README.md)
RES=${RES:-512x512}
SPP=${SPP:-16}
CPU_SPP=${CPU_SPP:-$SPP}
INTEGRATOR=${INTEGRATOR:-path}
[ -n "${SKIP_BUILD:-}" ] || cmake --build "$BUILD" --target lucerna -j"$(nproc)" >/dev/null  # SKIP_BUILD=1: binaries built elsewhere (bench/gpu/device_check.sh)
BIN="$BUILD/lucerna"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

python3 bench/gpu/make_terrain.py "$tmp/terrain" "${TERRAIN_N:-724}" >/dev/null
SCENES=${SCENES:-"bitterli-cornell-box/scene-v4.pbrt bitterli-veach-mis/scene-v4.pbrt bitterli-veach-bidir/scene-v4.pbrt
  bitterli-volumetric-caustic/scene-v4-nomedium.pbrt bitterli-water-caustic/scene-v4.pbrt pbrt-v3-caustic-glass/scene-v4.pbrt
  smallvcm-cornell/smallvcm-bs_c.pbrt smallvcm-cornell/smallvcm-bs_p.pbrt"}
files=()
for s in $SCENES; do files+=("$DATA/scenes/$s"); done
files+=("$tmp/terrain/terrain.pbrt")

# Is there a usable GPU? (`--device cuda` exits 2 with the reason when not.)
gpu=""
if "$BIN" render "${files[0]}" --res 8x8 --spp 1 --device cuda -q -o "$tmp/probe.exr" >/dev/null 2>"$tmp/probe.txt"; then
  gpu=$(sed -n 's/^device: //p' "$tmp/probe.txt" | head -1)
  echo "GPU: $gpu"
else
  echo "GPU: none ($(grep -o 'no usable CUDA GPU.*' "$tmp/probe.txt" | head -1 || true)); CPU numbers only"
fi
echo "CPU: $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "res $RES, integrator $INTEGRATOR, spp: gpu $SPP, cpu $CPU_SPP; maxdepth from each scene file"
printf "%-44s %9s %9s %9s %9s %9s %9s %8s\n" scene cpu-Ms/s cpu-Mr/s r/sample gpu-Ms/s gpu-Mr/s r/sample gpu/cpu

for f in "${files[@]}"; do
  name=${f#"$DATA/scenes/"}
  [[ $f == "$tmp"/* ]] && name="generated terrain (1M triangles)"
  "$BIN" render "$f" --res "$RES" --spp "$CPU_SPP" --integrator "$INTEGRATOR" --device cpu --seed 1 -q \
      -o "$tmp/cpu.exr" --stats-json "$tmp/cpu.json" >/dev/null 2>&1 || { echo "$name: CPU render failed"; continue; }
  rm -f "$tmp/gpu.json"
  if [ -n "$gpu" ]; then
    "$BIN" render "$f" --res "$RES" --spp "$SPP" --integrator "$INTEGRATOR" --device cuda --seed 1 -q \
        -o "$tmp/gpu.exr" --stats-json "$tmp/gpu.json" >/dev/null 2>"$tmp/gpu.err" || { echo "$name: GPU render failed: $(tail -1 "$tmp/gpu.err")"; }
  fi
  python3 - "$name" "$tmp/cpu.json" "$tmp/gpu.json" <<'PY'
import json, os, sys
name, cpuPath, gpuPath = sys.argv[1:]
def rates(p):
    if not os.path.exists(p):
        return None
    j = json.load(open(p))
    return j["samples_per_second"] * 1e-6, j["rays_per_second"] * 1e-6, j["rays"] / max(1, j["samples"])
c, g = rates(cpuPath), rates(gpuPath)
cell = lambda r: "%9.2f %9.2f %9.2f" % r if r else "%9s %9s %9s" % ("-", "-", "-")
ratio = "%7.1fx" % (g[1] / c[1]) if c and g and c[1] > 0 else "%8s" % "-"
print("%-44s %s %s %s" % (name[:44], cell(c), cell(g), ratio))
PY
done
