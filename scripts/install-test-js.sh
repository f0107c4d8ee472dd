#!/usr/bin/env bash
# Installs the reference JavaScript clients the bridge tests drive (Foxglove WebSocket,
# ROS 2 CDR decoding, MCAP readers) from the npm registry into a test folder, at the versions
# pinned in tests/js/package-lock.json. Idempotent: does nothing when they are already there.
# Usage: scripts/install-test-js.sh [FOLDER]   (default build/js)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
dest="${1:-$here/build/js}"
if ! command -v npm >/dev/null 2>&1; then
  echo "install-test-js: npm is missing; run scripts/install-deps.sh first" >&2
  exit 1
fi
mkdir -p "$dest"
if [ -f "$dest/.installed" ] && cmp -s "$here/tests/js/package-lock.json" "$dest/package-lock.json"; then
  exit 0
fi
cp "$here/tests/js/package.json" "$here/tests/js/package-lock.json" "$dest/"
echo "install-test-js: npm ci into $dest"
(cd "$dest" && npm ci --no-audit --no-fund --loglevel=error)
touch "$dest/.installed"
