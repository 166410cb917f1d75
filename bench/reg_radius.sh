#!/usr/bin/env bash
# Chooses regpath's default r0 by measurement: for each shared scene with specular paths and a
# reference, renders regpath at equal time with r0 = f * (scene bounding-box diagonal) for several
# f (`lucerna converge`, one run each, directly visible emitters excluded) and prints the pixel
# RMSE against the pbrt-v4 reference and the RMSE of 8x8-block means (which hides the noise and
# shows the blur), next to plain path's. Usage: bench/reg_radius.sh [SECONDS] [fractions...]
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=data   # the shared scenes and references (data/README.md)
T=${1:-20}; shift || true
FRACS=${*:-0.01 0.02 0.04 0.08 0.16}
BIN=${LUCERNA_BIN:-build/lucerna}
SCENES=${SCENES:-bs_p caustic-glass water-caustic volumetric-caustic bs_c veach-bidir}
out=$(mktemp -d)
printf "%-20s %-8s %10s %6s %12s %12s\n" scene f r0 spp pixel-rmse block-rmse
for name in $SCENES; do
  txt="$DATA/refs/$name.txt"
  dir=$(sed -n 's/^scene variant: shared\/\(.*\)\/ref-.*\.pbrt.*/\1/p' "$txt")
  file=$(ls "$DATA/$dir"/smallvcm-$name.pbrt "$DATA/$dir"/scene-v4-nomedium.pbrt "$DATA/$dir"/scene-v4.pbrt 2>/dev/null | head -1 || true)
  res=$(sed -n 's/^resolution: \([0-9]*x[0-9]*\).*/\1/p' "$txt")
  diag=$("$BIN" info "$file" 2>/dev/null | sed -n 's/^bounds: (\(.*\)) - (\(.*\))$/\1 \2/p' | tr -d ',' |
         awk '{print sqrt(($4-$1)^2+($5-$2)^2+($6-$3)^2)}')
  for f in path $FRACS; do
    if [ "$f" = path ]; then args=(--integrators path); r=-; else
      r=$(awk -v f="$f" -v d="$diag" 'BEGIN{print f*d}'); args=(--integrators regpath --reg-radius "$r"); fi
    rm -rf "$out/c"
    "$BIN" converge "$file" --ref "$DATA/refs/$name.exr" --res "$res" --time "$T" --runs 1 --seed 1 --no-report \
        "${args[@]}" -o "$out/c" >/dev/null 2>&1
    row=$(grep ",time," "$out/c/final.csv")
    spp=$(echo "$row" | cut -d, -f4); rmse=$(echo "$row" | cut -d, -f7)
    img=$(ls "$out"/c/*_time.exr)
    b=$("$BIN" diff "$img" "$DATA/refs/$name.exr" --metric rmse --block 8 | awk '{print $2}')
    printf "%-20s %-8s %10s %6.0f %12.5g %12.5g\n" "$name" "$f" "$r" "$spp" "$rmse" "$b"
  done
done
rm -rf "$out"
