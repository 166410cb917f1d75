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
. bench/reg_common.sh
for name in $SCENES; do
  reg_scene "$name"
  for k in path $KS; do
    if [ "$k" = path ]; then args=(--integrators path); else args=(--integrators regpath --reg-footprint "$k"); fi
    read -r spp rmse b < <(reg_measure "$name" "${args[@]}")
    printf "%-20s %-8s %6.0f %12.5g %12.5g\n" "$name" "$k" "$spp" "$rmse" "$b"
  done
done
rm -rf "$out"
