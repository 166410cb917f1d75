# Sourced by bench/reg_radius.sh and bench/reg_footprint.sh: one equal-time regpath (or path)
# render of a shared scene against its pbrt-v4 reference. Needs DATA, BIN, T and out (a scratch
# folder) set by the caller.

# reg_scene NAME: sets file (the scene the reference's note names, or its Lucerna variant) and res.
reg_scene() {
  local txt="$DATA/refs/$1.txt" dir
  dir=$(sed -n 's/^scene variant: shared\/\(.*\)\/ref-.*\.pbrt.*/\1/p' "$txt")
  file=$(ls "$DATA/$dir"/smallvcm-$1.pbrt "$DATA/$dir"/scene-v4-nomedium.pbrt "$DATA/$dir"/scene-v4.pbrt 2>/dev/null | head -1 || true)
  res=$(sed -n 's/^resolution: \([0-9]*x[0-9]*\).*/\1/p' "$txt")
}

# reg_measure NAME CONVERGE-ARGS...: renders $file for T seconds (`lucerna converge`, one run,
# seed 1, directly visible emitters excluded) and prints "spp pixel-rmse block-rmse" (the RMSE of
# 8x8-block means hides the noise and shows the blur).
reg_measure() {
  local name=$1 row spp rmse img b
  shift
  rm -rf "$out/c"
  "$BIN" converge "$file" --ref "$DATA/refs/$name.exr" --res "$res" --time "$T" --runs 1 --seed 1 --no-report \
      "$@" -o "$out/c" >/dev/null 2>&1
  row=$(grep ",time," "$out/c/final.csv")
  spp=$(echo "$row" | cut -d, -f4); rmse=$(echo "$row" | cut -d, -f7)
  img=$(ls "$out"/c/*_time.exr)
  b=$("$BIN" diff "$img" "$DATA/refs/$name.exr" --metric rmse --block 8 | awk '{print $2}')
  echo "$spp $rmse $b"
}
