#!/usr/bin/env bash
# Lucerna CPU render benchmark: renders fixed shared scenes at the pbrt-v4 reference resolution
# with fixed spp, maxdepth and 2 threads, and prints samples/s and rays/s next to pbrt-v4's own
# throughput on the same machine class (computed from ../shared/refs/NAME.txt: W*H*spp / wall s,
# only where that reference was rendered with pbrt-v4's `path` integrator).
# Usage: bench/render_bench.sh [SPP] [THREADS]
set -euo pipefail
cd "$(dirname "$0")/.."
SHARED=${LUCERNA_SHARED_DIR:-../shared}
SPP=${1:-64}
THREADS=${2:-2}
BIN=${LUCERNA_BIN:-build/lucerna}
[ -x "$BIN" ] || { echo "build first (scripts/build.sh)"; exit 1; }
out=$(mktemp -d)
printf "%-22s %-9s %5s %9s %8s %12s %12s %14s %8s\n" scene res spp maxdepth seconds samples/s rays/s pbrt-samples/s ratio
for name in cornell-box water-caustic veach-mis volumetric-caustic bs_c; do
  txt="$SHARED/refs/$name.txt"
  scene=$(sed -n 's/^scene variant: shared\/\(.*\)\/ref-\(.*\)\.pbrt.*/\1/p' "$txt")
  file=$(ls "$SHARED/$scene"/scene-v4-nomedium.pbrt "$SHARED/$scene"/scene-v4.pbrt "$SHARED/$scene"/smallvcm-$name.pbrt 2>/dev/null | head -1 || true)
  res=$(sed -n 's/^resolution: \([0-9]*x[0-9]*\).*/\1/p' "$txt")
  maxdepth=$(sed -n 's/.*"integer maxdepth" \[ \([0-9]*\) \].*/\1/p' "$txt")
  pbrtspp=$(sed -n 's/.*spp: \([0-9]*\).*/\1/p' "$txt")
  wall=$(sed -n 's/.*wall seconds: \([0-9.]*\).*/\1/p' "$txt")
  integ=$(sed -n 's/^integrator: "\([a-z]*\)".*/\1/p' "$txt")
  "$BIN" render "$file" --res "$res" --spp "$SPP" --maxdepth "$maxdepth" --threads "$THREADS" --seed 1 -q \
        -o "$out/$name.exr" --stats-json "$out/$name.json" >/dev/null
  python3 - "$out/$name.json" "$name" "$res" "$SPP" "$maxdepth" "$pbrtspp" "$wall" "$integ" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); name, res, spp, md, pspp, wall, integ = sys.argv[2:]
w, h = map(int, res.split('x'))
pbrt = w * h * int(pspp) / float(wall) if integ == 'path' else None
ratio = f"{j['samples_per_second'] / pbrt:.2f}x" if pbrt else f"({integ})"
print(f"{name:22s} {res:9s} {spp:>5s} {md:>9s} {j['seconds']:8.2f} {j['samples_per_second']:12.4g} {j['rays_per_second']:12.4g} "
      f"{(f'{pbrt:.4g}' if pbrt else 'n/a'):>14s} {ratio:>8s}")
PY
done
rm -rf "$out"
