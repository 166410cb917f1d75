#!/usr/bin/env bash
# Lucerna CPU render benchmark: renders fixed shared scenes at the pbrt-v4 reference resolution
# with fixed spp, maxdepth and 2 threads, and prints samples/s and rays/s next to pbrt-v4's own
# throughput on the same machine class (computed from data/refs/NAME.txt: W*H*spp / wall s,
# only where that reference was rendered with pbrt-v4's `path` integrator).
# Two rows per scene: "scene" is the scene's own file (scene-v4*.pbrt: its sampler, e.g. "sobol",
# which Lucerna renders with ZSobol); "pbrt-ref" is the exact file pbrt-v4 rendered for the
# reference and its timing (refs/NAME.txt "scene variant": Film/Sampler/Integrator replaced, e.g.
# Sampler "independent"), the like-for-like comparison. VARIANTS="scene" or "pbrt-ref" picks one.
# REPEAT=N renders each row N times and prints the median samples/s (ratio on the median) with the
# min-max range: this VM's speed drifts by +-25% between minutes, so one run proves little.
# SCENES="cornell-box veach-mis" selects scenes.
# Usage: bench/render_bench.sh [SPP] [THREADS]
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=data   # the shared scenes and references (data/README.md)
SPP=${1:-64}
THREADS=${2:-2}
BIN=${LUCERNA_BIN:-build/lucerna}
[ -x "$BIN" ] || { echo "build first (scripts/build.sh)"; exit 1; }
out=$(mktemp -d)
VARIANTS=${VARIANTS:-scene pbrt-ref}
REPEAT=${REPEAT:-1}
SCENES=${SCENES:-cornell-box water-caustic veach-mis volumetric-caustic bs_c}
printf "%-22s %-9s %-9s %5s %9s %8s %12s %12s %14s %8s %s\n" scene variant res spp maxdepth seconds samples/s rays/s pbrt-samples/s ratio "(min-max over REPEAT runs)"
for name in $SCENES; do
 for variant in $VARIANTS; do
  txt="$DATA/refs/$name.txt"
  scene=$(sed -n 's/^scene variant: shared\/\(.*\)\/ref-\(.*\)\.pbrt.*/\1/p' "$txt")
  if [ "$variant" = pbrt-ref ]; then
    file=$(sed -n 's/^scene variant: shared\/\([^ ]*\.pbrt\).*/\1/p' "$txt")
    file="$DATA/$file"
    [ -f "$file" ] || continue
  else
    file=$(ls "$DATA/$scene"/scene-v4-nomedium.pbrt "$DATA/$scene"/scene-v4.pbrt "$DATA/$scene"/smallvcm-$name.pbrt 2>/dev/null | head -1 || true)
  fi
  res=$(sed -n 's/^resolution: \([0-9]*x[0-9]*\).*/\1/p' "$txt")
  maxdepth=$(sed -n 's/.*"integer maxdepth" \[ \([0-9]*\) \].*/\1/p' "$txt")
  pbrtspp=$(sed -n 's/.*spp: \([0-9]*\).*/\1/p' "$txt")
  wall=$(sed -n 's/.*wall seconds: \([0-9.]*\).*/\1/p' "$txt")
  integ=$(sed -n 's/^integrator: "\([a-z]*\)".*/\1/p' "$txt")
  jsons=()
  for rep in $(seq "$REPEAT"); do
    "$BIN" render "$file" --res "$res" --spp "$SPP" --maxdepth "$maxdepth" --threads "$THREADS" --seed "$rep" -q \
          -o "$out/$name.exr" --stats-json "$out/$name.$rep.json" >/dev/null
    jsons+=("$out/$name.$rep.json")
  done
  python3 - "$name" "$res" "$SPP" "$maxdepth" "$pbrtspp" "$wall" "$integ" "$variant" "${jsons[@]}" <<'PY'
import json, statistics, sys
name, res, spp, md, pspp, wall, integ, variant = sys.argv[1:9]
js = [json.load(open(f)) for f in sys.argv[9:]]
w, h = map(int, res.split('x'))
pbrt = w * h * int(pspp) / float(wall) if integ == 'path' else None
sps = [j['samples_per_second'] for j in js]
med = statistics.median(sps)
rays = statistics.median([j['rays_per_second'] for j in js])
secs = statistics.median([j['seconds'] for j in js])
ratio = f"{med / pbrt:.2f}x" if pbrt else f"({integ})"
spread = ""
if len(js) > 1:
    spread = f"({min(sps):.4g}-{max(sps):.4g}" + (f", {min(sps) / pbrt:.2f}x-{max(sps) / pbrt:.2f}x)" if pbrt else ")")
print(f"{name:22s} {variant:9s} {res:9s} {spp:>5s} {md:>9s} {secs:8.2f} {med:12.4g} {rays:12.4g} "
      f"{(f'{pbrt:.4g}' if pbrt else 'n/a'):>14s} {ratio:>8s} {spread}")
PY
 done
done
rm -rf "$out"
