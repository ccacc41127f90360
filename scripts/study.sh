#!/usr/bin/env bash
# The accuracy-versus-time study (issue 12): every cull method x option on one mesh, the
# same views for each, then docs/results/accuracy-vs-time.md and its Pareto plot.
#
#   scripts/study.sh [MESH]       (default: shared/data/characters/bigguy.obj, level 2)
#
# Environment: BUILD (default build), OUT (default docs/results/accuracy-vs-time), VIEWS
# (views per verify run, default 100), FRAME_VIEWS (default 6), REPEATS (default 3),
# TESS (default "4 8 16": back-patch options), OCC_TESS (default "4 16": Hi-Z and displaced
# options), FRAME_TESS (default "1 2 4 8 16": frame ratios and the break-even plot), WIDTH x
# HEIGHT (default 1280 x 720), LEVEL (default 2).
#
# Per tessellation level, `osd-cull verify` (same seed, so the same views in every run)
# gives each point its cull rate, the oracle's rate of invisible patches on those views,
# false culls against the item buffer, culls outside the double reference and the kernel's
# ns/patch; `bench-cull --parts 2` gives the frame-time ratio against no culling, like for
# like (back faces culled by the rasterizer on both sides) and interleaved per view.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mesh=${1:-$root/../shared/data/characters/bigguy.obj}
build=${BUILD:-$root/build}
out=${OUT:-$root/docs/results/accuracy-vs-time}
views=${VIEWS:-100}
frameViews=${FRAME_VIEWS:-6}
repeats=${REPEATS:-3}
tessLevels=${TESS:-4 8 16}
occTessLevels=${OCC_TESS:-4 16}
frameTessLevels=${FRAME_TESS:-1 2 4 8 16}
width=${WIDTH:-1280}
height=${HEIGHT:-720}
level=${LEVEL:-2}
mkdir -p "$out"
cli=$build/samples/osd-cull
common=(--level "$level" --views "$views" --seed 1 --view-set sphere --width "$width"
  --height "$height")
backPatch=tcone,ncone,tangent-plane,tangent-plane-16,tcone-fp64,ncone-fp64

run() {  # NAME ARGS...: one verify run, its table to NAME.txt and JSON to NAME.json
  local name=$1
  shift
  echo "study: $name" >&2
  # verify exits 1 when a surface-exact run loses silhouette pixels; the JSON says so.
  nice "$cli" verify "$mesh" "${common[@]}" "$@" --json "$out/$name.json" >"$out/$name.txt" ||
    [ -f "$out/$name.json" ]
}

for t in $tessLevels; do
  run "bound-tess$t" --tess "$t" --methods "$backPatch"
  run "surface-tess$t" --tess "$t" --methods "$backPatch" --surface-exact
  run "listed-tess$t" --tess "$t" --methods "$backPatch" --drawn-enumerate
done
for t in $occTessLevels; do
  run "hiz-half-paper-tess$t" --tess "$t" --methods hiz
  run "hiz-full-paper-tess$t" --tess "$t" --methods hiz --hiz-full
  run "hiz-half-tight-tess$t" --tess "$t" --methods hiz --hiz-tight
  run "hiz-full-tight-tess$t" --tess "$t" --methods hiz --hiz-full --hiz-tight
  run "displaced-tess$t" --tess "$t" --displacement procedural --displacement-scale 0.64 \
    --displaced-bound all
done

modes=""
for m in tcone ncone tangent-plane tangent-plane-16; do
  modes+="$m,$m/surface,$m/listed,"
done
echo "study: frames" >&2
nice "$build/benchmarks/bench-cull" --mesh "$mesh" --parts 2 --levels "$level" \
  --tess "$(echo "$frameTessLevels" | tr ' ' ',')" --views "$frameViews" --repeats "$repeats" \
  --width "$width" --height "$height" --frame-modes "${modes%,}" >"$out/frames.md"

/usr/bin/python3 "$root/scripts/plots/accuracy_vs_time.py" "$out" \
  "$root/docs/results/accuracy-vs-time.md"
