#!/usr/bin/env bash
# Installs Lucerna's dependencies from Debian 12's packages (idempotent, non-interactive; needs
# root or sudo). Skips apt entirely when everything is present.
# Usage: scripts/setup.sh [demo|all]   demo: what building build/lucerna needs; all (default):
# also the tests, benchmarks, report scripts and fuzzers.
set -euo pipefail
profile=${1:-all}
PKGS=(build-essential cmake ninja-build pkg-config
      libembree-dev libtbb-dev libopenexr-dev libpng-dev zlib1g-dev libcli11-dev libfmt-dev libnanovdb-dev)
case "$profile" in
  demo) ;;
  all) PKGS+=(libgtest-dev libgmock-dev libbenchmark-dev
              libopenmpi-dev openmpi-bin
              python3 python3-matplotlib python3-numpy
              clang libclang-rt-14-dev) ;;
  *) echo "usage: scripts/setup.sh [demo|all]" >&2; exit 2 ;;
esac
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
echo "setup: dependencies present ($profile)"
