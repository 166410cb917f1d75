#!/usr/bin/env bash
# Packs lucerna and tests/test_gpu from a CUDA build (sm_90 machine code) with the shared libraries
# they load, for a GPU machine that has the NVIDIA driver but none of Debian's libraries and takes
# at most 64 MiB of files per call (docs/gpu.md, "On a lent GPU machine"). The two binaries are
# 66 MB each, 38 MB of which are the four RGB->spectrum tables: they are zeroed for the transfer
# and fitted again there by a static build of the table fitter (2 s), then both binaries are
# checked against their sha256 from here. Output: OUT (default .devpack/), about 41 MB:
#   dev.tar.zst    bin/ (the binaries), lib/ (libraries), build/ (wrappers that set
#                  LD_LIBRARY_PATH, laid out as a build directory), rgb2spec_gen, tables.txt
#   zstd/          zstd and its libraries, for a machine without it
#   restore.sh     run there from the repository root: unpacks into .dev/ and restores the tables
# There: `bash .devpack/restore.sh && bench/gpu/device_check.sh .dev/build OUTDIR`.
# Usage: bench/gpu/pack_for_device.sh [BUILD] [OUT]
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build}
OUT=${2:-.devpack}
SPECTRA="$BUILD/src/lucerna/spectra"
for f in "$BUILD/lucerna" "$BUILD/tests/test_gpu" "$SPECTRA/CMakeFiles/lucerna_rgb2spec_gen.dir/tools/rgb2spec_gen.cpp.o"; do
  [ -f "$f" ] || { echo "pack_for_device: $f missing (configure BUILD with -DLUCERNA_CUDA=ON -DLUCERNA_TESTS=ON and build)" >&2; exit 2; }
done
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
dev="$stage/.dev"
mkdir -p "$dev/bin" "$dev/lib" "$dev/build/tests"
cp "$BUILD/lucerna" "$BUILD/tests/test_gpu" "$dev/bin/"
pwd > "$dev/source_dir"   # the tests read scenes under the source path compiled into them
strip "$dev/bin/lucerna" "$dev/bin/test_gpu"
# Every library they load except glibc's own and the C++ runtime (the machine's is newer).
ldd "$BUILD/lucerna" "$BUILD/tests/test_gpu" | awk '/=>/ {print $3}' | sort -u |
  grep -vE '/(libc|libm|libdl|libpthread|librt|libresolv|libstdc\+\+|libgcc_s)\.so' |
  while read -r lib; do cp -L "$lib" "$dev/lib/"; done
for name in lucerna tests/test_gpu; do
  cat > "$dev/build/$name" <<EOF
#!/bin/sh
d=\$(cd "\$(dirname "\$0")" && pwd); while [ ! -d "\$d/bin" ]; do d=\$(dirname "\$d"); done
LD_LIBRARY_PATH="\$d/lib" exec "\$d/bin/$(basename "$name")" "\$@"
EOF
  chmod +x "$dev/build/$name"
done
# The table fitter, linked statically (no libm of the other machine's glibc in the fit).
g++ -static -O3 "$SPECTRA/CMakeFiles/lucerna_rgb2spec_gen.dir/tools/rgb2spec_gen.cpp.o" \
    "$SPECTRA/CMakeFiles/lucerna_rgb2spec_gen.dir/cie_data.cpp.o" -pthread -o "$dev/rgb2spec_gen"
python3 - "$dev" "$SPECTRA" <<'PY'
import hashlib, os, subprocess, sys
dev, spectra = sys.argv[1:]
spaces = ["srgb", "dci-p3", "rec2020", "aces2065-1"]
lines = []
for s in spaces:  # the static fitter must reproduce the build's tables exactly
    subprocess.run([dev + "/rgb2spec_gen", "64", dev + "/check.bin", s], check=True, capture_output=True)
    ok = open(dev + "/check.bin", "rb").read() == open("%s/%s_rgb2spec_64.bin" % (spectra, s), "rb").read()
    os.remove(dev + "/check.bin")
    if not ok:
        sys.exit("pack_for_device: the static fitter does not reproduce the %s table" % s)
for exe in ("lucerna", "test_gpu"):
    path = dev + "/bin/" + exe
    data = bytearray(open(path, "rb").read())
    lines.append("sha256 %s %s" % (exe, hashlib.sha256(data).hexdigest()))
    for s in spaces:
        table = open("%s/%s_rgb2spec_64.bin" % (spectra, s), "rb").read()
        off = data.find(table)
        if off < 0 or data.find(table, off + 1) >= 0:
            sys.exit("pack_for_device: the %s table is not once in %s" % (s, exe))
        data[off:off + len(table)] = bytes(len(table))
        lines.append("%s %s %d" % (exe, s, off))
    open(path, "wb").write(data)
open(dev + "/tables.txt", "w").write("\n".join(lines) + "\n")
PY
rm -rf "$OUT"
mkdir -p "$OUT/zstd"
tar cf - -C "$stage" .dev | zstd -q --long=27 -19 -T"$(nproc)" > "$OUT/dev.tar.zst"
cp /usr/bin/zstd "$OUT/zstd/"
ldd /usr/bin/zstd | awk '/=>/ {print $3}' | grep -vE '/(libc|libm|libpthread)\.so' | while read -r lib; do cp -L "$lib" "$OUT/zstd/"; done
cat > "$OUT/restore.sh" <<'EOF'
#!/usr/bin/env bash
# From the repository root: unpack .devpack/dev.tar.zst into .dev/, fit the four tables again and
# put them back, check both binaries against their sha256 from the build machine, and link the
# source path compiled into the tests to this checkout when it does not exist here.
set -euo pipefail
if command -v zstd >/dev/null; then zstd -q -d --long=27 -c .devpack/dev.tar.zst; else
  LD_LIBRARY_PATH=$PWD/.devpack/zstd .devpack/zstd/zstd -q -d --long=27 -c .devpack/dev.tar.zst; fi | tar xf -
for s in srgb dci-p3 rec2020 aces2065-1; do .dev/rgb2spec_gen 64 "/tmp/rgb2spec_$s.bin" "$s"; done
while read -r exe space offset; do
  [ "$exe" = sha256 ] && continue
  dd if="/tmp/rgb2spec_$space.bin" of=".dev/bin/$exe" bs=1M seek="$offset" oflag=seek_bytes conv=notrunc status=none
done < .dev/tables.txt
grep ^sha256 .dev/tables.txt | while read -r _ exe sum; do echo "$sum  .dev/bin/$exe"; done | sha256sum -c -
src=$(cat .dev/source_dir)   # test_gpu finds its scenes there: make it this checkout
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
EOF
chmod +x "$OUT/restore.sh"
du -sh "$OUT"
