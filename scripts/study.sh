#!/usr/bin/env bash
# The accuracy-versus-time study (issue 12): every cull method x option on one mesh, the
# same views for each, then docs/results/accuracy-vs-time.md and its Pareto plot.
#
#   scripts/study.sh [MESH]       (default: shared/data/characters/bigguy.obj, level 2)
#
# Environment: BUILD (default build), OUT (default docs/results/accuracy-vs-time), VIEWS
# (views per back-patch verify run, default 100), OCC_VIEWS (Hi-Z and displaced runs,
# default VIEWS), FRAME_VIEWS (default 6), REPEATS (default 3), RESUME=1 (keep the runs
# whose JSON exists), BACK_PATCH (verify's back-patch methods), FRAME_METHODS (bench-cull's),
# TESS (default "4 8 16": back-patch options), OCC_TESS (default "4 16": Hi-Z and displaced
# options), FRAME_TESS (default "1 2 4 8 16": frame ratios and the break-even plot), WIDTH x
# HEIGHT (default 1280 x 720), LEVEL (default 2).
#
# Per tessellation level, `osd-cull verify` (same seed, so the same views in every run)
# gives each point its cull rate, the oracle's rate of invisible patches on those views,
# false culls against the item buffer, culls outside the double reference and the kernel's
# ns/patch; `bench-cull --parts 12` gives the kernels' ns/patch interleaved per view (used for
# the plot) and the frame-time ratio against no culling, like for like (back faces culled
# by the rasterizer on both sides) and interleaved per view.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mesh=${1:-$root/../shared/data/characters/bigguy.obj}
build=${BUILD:-$root/build}
out=${OUT:-$root/docs/results/accuracy-vs-time}
views=${VIEWS:-100}
occViews=${OCC_VIEWS:-$views}
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
common=(--level "$level" --seed 1 --view-set sphere --width "$width" --height "$height")
backPatch=${BACK_PATCH:-tcone,ncone,tangent-plane,tangent-plane-16,tcone-fp64,ncone-fp64}

run() {  # NAME ARGS...: one verify run, its table to NAME.txt and JSON to NAME.json
  local name=$1
  shift
  [ "${RESUME:-0}" = 1 ] && [ -f "$out/$name.json" ] && return
  echo "study: $name" >&2
  # verify exits 1 when a surface-exact run loses silhouette pixels; the JSON says so.
  "$cli" verify "$mesh" "${common[@]}" "$@" --json "$out/$name.json" >"$out/$name.txt" ||
    [ -f "$out/$name.json" ]
}

for t in $tessLevels; do
  run "listed-tess$t" --views "$views" --tess "$t" --methods "$backPatch" --drawn-enumerate
  run "surface-tess$t" --views "$views" --tess "$t" --methods "$backPatch" --surface-exact
  run "bound-tess$t" --views "$views" --tess "$t" --methods "$backPatch"
done

# bench-cull: part 1 the kernels' ns/patch interleaved per view (the Pareto plot's x axis),
# part 2 the frame ratios, both at the frame levels.
modes=""
kernels=empty
for m in ${FRAME_METHODS:-tcone ncone tangent-plane tangent-plane-16}; do
  modes+="$m,$m/surface,$m/listed,"
done
for m in ${BACK_PATCH//,/ }; do
  kernels+=",$m,$m/surface,$m/listed"
done
if [ "${RESUME:-0}" != 1 ] || [ ! -s "$out/frames.md" ]; then
  echo "study: frames" >&2
  "$build/benchmarks/bench-cull" --mesh "$mesh" --parts 12 --levels "$level" \
    --tess "$(echo "$frameTessLevels" | tr ' ' ',')" --kernel-tess "$(echo "$frameTessLevels" | tr ' ' ',')" \
    --views "$frameViews" --repeats "$repeats" --width "$width" --height "$height" \
    --methods "$kernels" --frame-modes "${modes%,}" >"$out/frames.md"
fi

for t in $occTessLevels; do
  run "hiz-half-paper-tess$t" --views "$occViews" --tess "$t" --methods hiz
  run "hiz-full-paper-tess$t" --views "$occViews" --tess "$t" --methods hiz --hiz-full
  run "hiz-half-tight-tess$t" --views "$occViews" --tess "$t" --methods hiz --hiz-tight
  run "hiz-full-tight-tess$t" --views "$occViews" --tess "$t" --methods hiz --hiz-full --hiz-tight
  run "displaced-tess$t" --views "$occViews" --tess "$t" --displacement procedural --displacement-scale 0.64 \
    --displaced-bound all
done

/usr/bin/python3 "$root/scripts/plots/accuracy_vs_time.py" "$out" \
  "$root/docs/results/accuracy-vs-time.md"
