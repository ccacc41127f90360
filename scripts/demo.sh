#!/usr/bin/env bash
# Sets up (packages, configure, build) and runs the demo: renders the built-in scene of
# subdivision surfaces (tessellated Bézier and Gregory patches) with osd-cull and prints
# where the image went. Extra arguments go to `osd-cull render` (see --help).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/setup.sh"
build=${OSD_CULL_BUILD_DIR:-$root/build}
out=${OSD_CULL_DEMO_OUT:-$root/out}
mkdir -p "$out"
"$build/samples/osd-cull" info
echo
exec "$build/samples/osd-cull" render --out "$out/demo.png" --width 960 --height 540 "$@"
