#!/usr/bin/env bash
# Opens a convergence report (DIR/index.html from `lucerna converge`) in headless Chromium
# (Debian's chromium package; installed on demand) and saves a screenshot.
# Usage: scripts/screenshot_report.sh DIR OUT.png [WIDTHxHEIGHT]
set -euo pipefail
dir=$(cd "$1" && pwd); out=$2; size=${3:-1280x1800}
if ! command -v chromium >/dev/null; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
fi
profile=$(mktemp -d)
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
  --disable-component-update --disable-sync --user-data-dir="$profile" --window-size="${size/x/,}" \
  --screenshot="$out" "file://$dir/index.html" 2>/dev/null
rm -rf "$profile"
echo "wrote $out"
