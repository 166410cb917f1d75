#!/usr/bin/env bash
# Chooses regpath's default footprint K by measurement (the kernels from the pixel's footprint,
# --reg-footprint K, docs/regularization.md): for each shared scene with specular paths and a
# reference, renders regpath at equal time with K = each of the given values (0: the world-space
# radius r0 = 0.04 x diagonal everywhere) and prints the pixel RMSE against the pbrt-v4 reference
# and the RMSE of 8x8-block means (which hides the noise and shows the blur), next to plain
# path's. One run each (`lucerna converge`, seed 1). Usage: bench/reg_footprint.sh [SECONDS] [K...]
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=data   # the shared scenes and references (data/README.md)
T=${1:-20}; shift || true
KS=${*:-0 1 2 4 8 16}
BIN=${LUCERNA_BIN:-build/lucerna}
SCENES=${SCENES:-bs_p caustic-glass water-caustic volumetric-caustic bs_c veach-bidir}
out=$(mktemp -d)
printf "%-20s %-8s %6s %12s %12s\n" scene K spp pixel-rmse block-rmse
for name in $SCENES; do
  txt="$DATA/refs/$name.txt"
  dir=$(sed -n 's/^scene variant: shared\/\(.*\)\/ref-.*\.pbrt.*/\1/p' "$txt")
  file=$(ls "$DATA/$dir"/smallvcm-$name.pbrt "$DATA/$dir"/scene-v4-nomedium.pbrt "$DATA/$dir"/scene-v4.pbrt 2>/dev/null | head -1 || true)
  res=$(sed -n 's/^resolution: \([0-9]*x[0-9]*\).*/\1/p' "$txt")
  for k in path $KS; do
    if [ "$k" = path ]; then args=(--integrators path); else args=(--integrators regpath --reg-footprint "$k"); fi
    rm -rf "$out/c"
    "$BIN" converge "$file" --ref "$DATA/refs/$name.exr" --res "$res" --time "$T" --runs 1 --seed 1 --no-report \
        "${args[@]}" -o "$out/c" >/dev/null 2>&1
    row=$(grep ",time," "$out/c/final.csv")
    spp=$(echo "$row" | cut -d, -f4); rmse=$(echo "$row" | cut -d, -f7)
    img=$(ls "$out"/c/*_time.exr)
    b=$("$BIN" diff "$img" "$DATA/refs/$name.exr" --metric rmse --block 8 | awk '{print $2}')
    printf "%-20s %-8s %6.0f %12.5g %12.5g\n" "$name" "$k" "$spp" "$rmse" "$b"
  done
done
rm -rf "$out"
