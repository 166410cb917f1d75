#!/usr/bin/env bash
# Chooses regpath's default r0 by measurement: for each shared scene with specular paths and a
# reference, renders regpath at equal time with r0 = f * (scene bounding-box diagonal) for several
# f, and prints the 8x8-block RMSE against the pbrt-v4 reference (block means: the SPPM references
# are grainy) next to plain path's. Usage: bench/reg_radius.sh [SECONDS] [fractions...]
set -euo pipefail
cd "$(dirname "$0")/.."
SHARED=${LUCERNA_SHARED_DIR:-../shared}
T=${1:-20}; shift || true
FRACS=${*:-0.002 0.005 0.01 0.02 0.05}
BIN=${LUCERNA_BIN:-build/lucerna}
out=$(mktemp -d)
printf "%-20s %-8s %10s %12s\n" scene f r0 block-rmse
for name in bs_p caustic-glass water-caustic volumetric-caustic bs_c; do
  txt="$SHARED/refs/$name.txt"
  dir=$(sed -n 's/^scene variant: shared\/\(.*\)\/ref-.*\.pbrt.*/\1/p' "$txt")
  file=$(ls "$SHARED/$dir"/smallvcm-$name.pbrt "$SHARED/$dir"/scene-v4-nomedium.pbrt "$SHARED/$dir"/scene-v4.pbrt 2>/dev/null | head -1 || true)
  res=$(sed -n 's/^resolution: \([0-9]*x[0-9]*\).*/\1/p' "$txt")
  diag=$("$BIN" info "$file" 2>/dev/null | sed -n 's/^bounds: (\(.*\)) - (\(.*\))$/\1 \2/p' | tr -d ',' |
         awk '{print sqrt(($4-$1)^2+($5-$2)^2+($6-$3)^2)}')
  "$BIN" render "$file" --res "$res" --time "$T" --seed 1 -q -o "$out/p.exr" >/dev/null 2>&1
  e=$("$BIN" diff "$out/p.exr" "$SHARED/refs/$name.exr" --metric rmse --block 8 | awk '{print $2}')
  printf "%-20s %-8s %10s %12s\n" "$name" path - "$e"
  for f in $FRACS; do
    r=$(awk -v f="$f" -v d="$diag" 'BEGIN{print f*d}')
    "$BIN" render "$file" --res "$res" --time "$T" --seed 1 -q --integrator regpath --reg-radius "$r" -o "$out/r.exr" >/dev/null 2>&1
    e=$("$BIN" diff "$out/r.exr" "$SHARED/refs/$name.exr" --metric rmse --block 8 | awk '{print $2}')
    printf "%-20s %-8s %10.5f %12s\n" "$name" "$f" "$r" "$e"
  done
done
rm -rf "$out"
