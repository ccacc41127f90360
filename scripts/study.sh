#!/usr/bin/env bash
# The accuracy-versus-time study (issue 12): every cull method x option on one mesh, the
# same views for each, the break-even cull rate against tessellation (measured and
# predicted), the effect plan of each case, then docs/results/accuracy-vs-time.md with its
# Pareto plots and break-even plot. One command:
#
#   scripts/study.sh [--quick] [MESH]   (default: shared/data/characters/bigguy.obj, level 2)
#
# --quick (or QUICK=1): a small run (3 views, 1 repeat, tess 4 only, break-even at tess 1
# and 4) into build/study-quick/ and build/study-quick.md, to check the pipeline in minutes.
#
# Environment (defaults of the full run): BUILD (build), OUT (docs/results/accuracy-vs-time),
# PAGE (docs/results/accuracy-vs-time.md), WIDTH x HEIGHT (1280 x 720), LEVEL (2),
# VIEWS (20: views of every verify run and of the kernel timing), TESS ("4 8 16": the
# back-patch options' levels), OCC_TESS ("4 16": Hi-Z and displaced options), FRAME_TESS
# ("4 16": frame ratios), FRAME_VIEWS (4), REPEATS (2: frames and kernels per view),
# BREAK_EVEN_TESS ("1 2 4 8 16 32"), BREAK_EVEN_VIEWS (3), BACK_PATCH (verify's back-patch
# methods), DISPLACEMENT_SCALE (0.64 with the procedural map, about 2% of BigGuy's size),
# PARALLEL (0: one run after the other, the default; 1: the verify runs, whose timings are
# not used, run beside the bench-cull runs: faster on 2 cores, noisier timings), RESUME=1 (keep the runs whose output exists).
#
# Per tessellation level, `osd-cull verify` (same seed, so the same views in every run)
# gives each point its cull rate, the oracle's rate of invisible patches on those views,
# false culls against the item buffer and culls outside the double reference. One
# bench-cull run times every kernel interleaved per view at every study level (kernels.md:
# the ns/patch of every point); one gives the frame-time ratio culled / unculled of every
# point, like for like and interleaved (frames.md); one measures the break-even cull rate
# (breakeven.md). `osd-cull calibrate` gives the model's prediction (calibration.txt) and
# `osd-cull plan` the plan of each case (plan-*.md), which the page compares with the
# study's Pareto front.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=${QUICK:-0}
if [ "${1:-}" = --quick ]; then
  quick=1
  shift
fi
mesh=${1:-$root/../shared/data/characters/bigguy.obj}
build=${BUILD:-$root/build}
if [ "$quick" = 1 ]; then
  : "${OUT:=$build/study-quick}" "${PAGE:=$build/study-quick.md}" "${VIEWS:=3}" "${TESS:=4}"
  : "${OCC_TESS:=4}" "${FRAME_TESS:=4}" "${FRAME_VIEWS:=2}" "${REPEATS:=1}"
  : "${BREAK_EVEN_TESS:=1 4}" "${BREAK_EVEN_VIEWS:=1}"
fi
out=${OUT:-$root/docs/results/accuracy-vs-time}
page=${PAGE:-$root/docs/results/accuracy-vs-time.md}
views=${VIEWS:-20}
tessLevels=${TESS:-4 8 16}
occTessLevels=${OCC_TESS:-4 16}
frameTessLevels=${FRAME_TESS:-4 16}
frameViews=${FRAME_VIEWS:-4}
repeats=${REPEATS:-2}
breakEvenTess=${BREAK_EVEN_TESS:-1 2 4 8 16 32}
breakEvenViews=${BREAK_EVEN_VIEWS:-3}
width=${WIDTH:-1280}
height=${HEIGHT:-720}
level=${LEVEL:-2}
scale=${DISPLACEMENT_SCALE:-0.64}
parallel=${PARALLEL:-0}
backPatch=${BACK_PATCH:-tcone,ncone,tangent-plane,tangent-plane-16,tcone-fp64,ncone-fp64}
displacedKernels=full-oobb,acon-oobb,con-oobb,full-caf,acon-caf,con-caf
hizModes=hiz,hiz/full,hiz/tight,hiz/full-tight
mkdir -p "$out"
cli=$build/samples/osd-cull
bench=$build/benchmarks/bench-cull
for exe in "$cli" "$bench"; do
  [ -x "$exe" ] || { echo "study: $exe is missing: build first (scripts/setup.sh)" >&2; exit 1; }
done
common=(--level "$level" --seed 1 --view-set sphere --width "$width" --height "$height")
displacement=(--displacement procedural --displacement-scale "$scale")
commas() { echo "$*" | tr ' ' ','; }
union() { echo "$@" | tr ' ' '\n' | sort -n | uniq | tr '\n' ' '; }

# The exact command and settings, for the page (the python prints them).
{
  echo "QUICK=$quick VIEWS=$views TESS=\"$tessLevels\" OCC_TESS=\"$occTessLevels\"" \
    "FRAME_TESS=\"$frameTessLevels\" FRAME_VIEWS=$frameViews REPEATS=$repeats" \
    "BREAK_EVEN_TESS=\"$breakEvenTess\" BREAK_EVEN_VIEWS=$breakEvenViews WIDTH=$width" \
    "HEIGHT=$height LEVEL=$level DISPLACEMENT_SCALE=$scale PARALLEL=$parallel" \
    "scripts/study.sh $([ "$quick" = 1 ] && echo '--quick ')${1:-}"
  echo "mesh $mesh"
  echo "commit $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "started $(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
} >"$out/run.txt"

# Progress: each step's weight is its estimated seconds on lavapipe with 2 loaded cores
# (measured 2026-12-02 at load 8-10: a BigGuy verify view at 1280x720 costs about 1 s at
# tess 4, 2 s at 8, 3 s at 16 with the listed-triangle test; a frame of the study's modes
# 0.4 s at tess 4, 2 s at 16, 6 s at 32); the remaining time is scaled by the measured pace.
start=$(date +%s)
declare -A weight
perView() { case $1 in 1 | 2 | 4) echo 1 ;; 8) echo 2 ;; 16) echo 3 ;; *) echo 6 ;; esac; }
frameSec() { case $1 in 1 | 2) echo 0.2 ;; 4) echo 0.4 ;; 8) echo 0.8 ;; 16) echo 2 ;; *) echo 6 ;; esac; }
verifySteps=() benchSteps=()
for t in $tessLevels; do
  for o in listed surface bound; do
    verifySteps+=("$o-tess$t")
    f=1
    [ "$o" = listed ] && f=2
    weight[$o-tess$t]=$((views * $(perView "$t") * f / 2))
  done
done
for t in $occTessLevels; do
  for o in hiz-half-paper hiz-full-paper hiz-half-tight hiz-full-tight displaced; do
    verifySteps+=("$o-tess$t")
    weight[$o-tess$t]=$((views * 2))
  done
done
kernelTess=$(union $tessLevels $occTessLevels)
w=0
for t in $kernelTess; do w=$((w + views * repeats * $(perView "$t"))); done
weight[kernels]=$w
frameSum() { for t in "$@"; do frameSec "$t"; done | awk '{ s += $1 } END { print s }'; }
weight[frames]=$(awk -v r="$repeats" -v v="$frameViews" -v s="$(frameSum $frameTessLevels)" \
  'BEGIN { printf "%d", 42 * r * v * s + 30 }')
weight[breakeven]=$(awk -v r="$repeats" -v v="$breakEvenViews" -v s="$(frameSum $breakEvenTess)" \
  'BEGIN { printf "%d", 10 * r * v * s + 30 }')
benchSteps=(kernels frames breakeven)
total=0
for s in "${verifySteps[@]}" "${benchSteps[@]}"; do total=$((total + weight[$s])); done
chain() {  # STEPS...: the summed weights
  local sum=0
  for s in "$@"; do sum=$((sum + weight[$s])); done
  echo "$sum"
}
if [ "$parallel" = 1 ]; then
  estimate=$(($(chain "${verifySteps[@]}") > $(chain "${benchSteps[@]}") ? $(chain "${verifySteps[@]}") : $(chain "${benchSteps[@]}")))
  estimate=$((estimate * 3 / 2))  # the two chains share the cores
  estimate=$((estimate < total ? estimate : total))
else
  estimate=$total
fi
estimate=$((estimate + 150))  # calibrate (when not cached) and the plans
echo "study: ${#verifySteps[@]} verify runs, 3 bench-cull runs, estimated $((estimate / 60)) min" \
  "(load $(cut -d' ' -f1 /proc/loadavg)); outputs in $out" >&2
doneFile=$out/.done-weight
echo 0 >"$doneFile"
step() {  # NAME: a progress line before the step
  local name=$1 now done
  now=$(date +%s)
  done=$(cat "$doneFile")
  local left=$((estimate - now + start))
  # The measured pace (weights done per second since the runs began; both chains count).
  [ "$done" -gt 0 ] && left=$(((now - runStart) * (total - done) / done))
  echo "study: [$(date -u +%H:%M:%S), $((now - start)) s] $name (about $((left > 0 ? left / 60 : 0)) min left)" >&2
}
finished() { echo $(($(cat "$doneFile") + weight[$1])) >"$doneFile"; }

verify() {  # NAME ARGS...: one verify run, its table to NAME.txt and JSON to NAME.json
  local name=$1
  shift
  if [ "${RESUME:-0}" != 1 ] || [ ! -f "$out/$name.json" ]; then
    step "verify $name"
    # verify exits 1 when a surface-exact run loses silhouette pixels; the JSON says so.
    "$cli" verify "$mesh" "${common[@]}" "$@" --json "$out/$name.json" >"$out/$name.txt" 2>&1 ||
      [ -f "$out/$name.json" ]
  fi
  finished "$name"
}

verifyChain() {
  for t in $tessLevels; do
    verify "listed-tess$t" --views "$views" --tess "$t" --methods "$backPatch" --drawn-enumerate
    verify "surface-tess$t" --views "$views" --tess "$t" --methods "$backPatch" --surface-exact
    verify "bound-tess$t" --views "$views" --tess "$t" --methods "$backPatch"
  done
  for t in $occTessLevels; do
    verify "hiz-half-paper-tess$t" --views "$views" --tess "$t" --methods hiz
    verify "hiz-full-paper-tess$t" --views "$views" --tess "$t" --methods hiz --hiz-full
    verify "hiz-half-tight-tess$t" --views "$views" --tess "$t" --methods hiz --hiz-tight
    verify "hiz-full-tight-tess$t" --views "$views" --tess "$t" --methods hiz --hiz-full --hiz-tight
    verify "displaced-tess$t" --views "$views" --tess "$t" "${displacement[@]}" --displaced-bound all
  done
}

benchRun() {  # NAME ARGS...: one bench-cull run into NAME.md
  local name=$1
  shift
  if [ "${RESUME:-0}" != 1 ] || [ ! -s "$out/$name.md" ]; then
    step "bench-cull $name"
    "$bench" --mesh "$mesh" --levels "$level" --width "$width" --height "$height" \
      --repeats "$repeats" --displacement procedural --displacement-scale "$scale" "$@" \
      >"$out/$name.md.part" 2>"$out/$name.log"
    mv "$out/$name.md.part" "$out/$name.md"
  fi
  finished "$name"
}

benchChain() {
  local kernels=empty,frustum modes=""
  for m in ${backPatch//,/ }; do
    kernels+=",$m,$m/surface,$m/listed"
    modes+="$m,$m/surface,$m/listed,"
  done
  # Part 1: every kernel, interleaved per view, at every level of the study.
  benchRun kernels --parts 1 --views "$views" --kernel-tess "$(commas $kernelTess)" \
    --methods "$kernels,$hizModes,$displacedKernels"
  # Part 2: the frame ratio of every point (back faces culled on both sides).
  benchRun frames --parts 2 --views "$frameViews" --tess "$(commas $frameTessLevels)" \
    --frame-modes "$modes$hizModes,$displacedKernels"
  # Part 3: the break-even sweep.
  benchRun breakeven --parts 3 --break-even-views "$breakEvenViews" \
    --break-even-tess "$(commas $breakEvenTess)" --break-even-methods frustum,tcone,tangent-plane
}

# The device calibration (cached per device, driver and library version: measured if
# absent) and the plan of each case: static, deforming and displaced BigGuy in one view.
step "calibrate and plan"
"$cli" calibrate --out "$out/calibration.txt" >"$out/calibrate.log" 2>&1
sceneFile() {  # CASE: a scene of the mesh, framed, one view at WIDTH x HEIGHT
  local extra=""
  case $1 in
    deforming) extra=', "animation": {"deformer": "twist", "axis": 1, "amount": 0.5, "frequency": 0.5}' ;;
    displaced) extra=", \"displacement\": {\"map\": \"procedural\", \"scale\": $scale}" ;;
  esac
  cat <<EOF
{"version": 1, "settings": {"width": $width, "height": $height, "frameCount": 2},
 "meshes": [{"name": "bigguy", "file": "$mesh", "level": $level$extra}],
 "views": [{"name": "main", "camera": {"eye": [18, 8, 36], "target": [0, 0, 0], "up": [0, 1, 0], "fovy": 40}}]}
EOF
}
for c in static deforming displaced; do
  sceneFile "$c" >"$out/$c.scene.json"
  for t in $(union $frameTessLevels); do
    # Frame 1: a deforming mesh has moved (frame 0 is its rest pose).
    "$cli" plan "$out/$c.scene.json" --frame 1 --tess "$t" --calibration "$out/calibration.txt" \
      >"$out/plan-$c-tess$t.md" 2>&1
  done
done

runStart=$(date +%s)
if [ "$parallel" = 1 ]; then
  verifyChain &
  verifyPid=$!
  benchChain
  wait "$verifyPid"
else
  verifyChain
  benchChain
fi
echo "finished $(date -u '+%Y-%m-%d %H:%M UTC') after $((($(date +%s) - start) / 60)) min," \
  "load average $(cut -d' ' -f1-3 /proc/loadavg)" >>"$out/run.txt"
step "page"
/usr/bin/python3 "$root/scripts/plots/accuracy_vs_time.py" "$out" "$page"
rm -f "$doneFile"
echo "study: wrote $page" >&2
