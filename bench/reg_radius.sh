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
. bench/reg_common.sh
for name in $SCENES; do
  reg_scene "$name"
  diag=$("$BIN" info "$file" 2>/dev/null | sed -n 's/^bounds: (\(.*\)) - (\(.*\))$/\1 \2/p' | tr -d ',' |
         awk '{print sqrt(($4-$1)^2+($5-$2)^2+($6-$3)^2)}')
  for f in path $FRACS; do
    if [ "$f" = path ]; then args=(--integrators path); r=-; else
      r=$(awk -v f="$f" -v d="$diag" 'BEGIN{print f*d}'); args=(--integrators regpath --reg-radius "$r"); fi
    read -r spp rmse b < <(reg_measure "$name" "${args[@]}")
    printf "%-20s %-8s %10s %6.0f %12.5g %12.5g\n" "$name" "$f" "$r" "$spp" "$rmse" "$b"
  done
done
rm -rf "$out"
