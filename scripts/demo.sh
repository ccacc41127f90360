#!/usr/bin/env bash
# Sets up (packages, configure, build) and runs the demo: the built-in scene (subdivision
# objects, a character, a wall and a ground slab) played along a 1 s camera path with GPU
# culling on (frustum, back-patch, Hi-Z occlusion in one kernel, two passes per frame).
# Every frame prints what was culled and what it saved against the same frame drawn without
# culling (same tessellation, back-face culling and image size), and writes the frame and
# its status view (patches colored by status) to out/demo/. Extra arguments go to
# `osd-cull render` (see --help).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/setup.sh"
build=${OSD_CULL_BUILD_DIR:-$root/build}
out=${OSD_CULL_DEMO_OUT:-$root/out}
mkdir -p "$out/demo"
"$build/samples/osd-cull" info
echo
"$build/samples/osd-cull" render built-in:scene --frames 24 --width 640 --height 360 \
  --backpatch-method ncone --verbose --compare --status-view --out-dir "$out/demo" --out "$out/demo.png" \
  --stats "$out/demo/stats.json" "$@" |
  awk '
    /^view .* frame [0-9]+:/ {
      match($0, /frame [0-9]+/); f = substr($0, RSTART + 6, RLENGTH - 6)
      match($0, /[0-9]+ patches/); n = substr($0, RSTART, RLENGTH - 8)
      match($0, /culled frustum [0-9]+, back-patch [0-9]+, occlusion [0-9]+/)
      c = substr($0, RSTART + 7, RLENGTH - 7); next }
    /^  vs unculled:/ {
      sub(/^  vs unculled: /, "")
      printf "frame %2d  of %s patches culled %-40s | %s\n", f, n, c, $0; next }
    { print }'
echo "status views (green drawn, yellow newly visible, blue frustum-, purple back-patch-,"
echo "red occlusion-culled): $out/demo/main_status_NNNN.png; frames: $out/demo/main_NNNN.png"
