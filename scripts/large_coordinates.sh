#!/usr/bin/env bash
# Measures cull rates of the cube cage authored at 0, 1e3, 1e4 and 1e5 from the origin, read
# by a scene file with and without recentring ("recentre": false keeps the offset in the
# control points, which the GPU holds in fp32), with `osd-cull verify SCENE --views V`.
# Writes DIR/offset_<X>_<recentred|baked>.json and DIR/large_coordinates.csv.
# Usage: scripts/large_coordinates.sh BUILD_DIR OUT_DIR [VIEWS]
set -euo pipefail
build=$1
out=$2
views=${3:-100}
mkdir -p "$out"
echo "offset,mode,method,cull_rate,false_culls,not_in_reference,oracle_invisible_rate" >"$out/large_coordinates.csv"
for offset in 0 1000 10000 100000; do
  obj="$out/cube_$offset.obj"
  for i in 0 1 2 3 4 5 6 7; do
    echo "v $((offset + (i & 1 ? 1 : -1))) $((i & 2 ? 1 : -1)) $((i & 4 ? 1 : -1))"
  done >"$obj"
  printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n' >>"$obj"
  for mode in recentred baked; do
    recentre=$([ $mode = recentred ] && echo true || echo false)
    scene="$out/offset_${offset}_$mode.scene.json"
    cat >"$scene" <<JSON
{"version": 1,
 "meshes": [{"name": "cube", "file": "cube_$offset.obj", "level": 3, "recentre": $recentre}],
 "views": [{"name": "v", "camera": {"eye": [$((offset + 4)), -5, 3], "target": [$offset, 0, 0]}}]}
JSON
    "$build/samples/osd-cull" verify "$scene" --frames 1 --views "$views" --width 128 \
      --height 128 --tess 4 --methods frustum,tcone,ncone,tangent-plane \
      --json "$out/offset_${offset}_$mode.json" >/dev/null 2>&1 || true
    /usr/bin/python3 - "$out/offset_${offset}_$mode.json" "$offset" "$mode" >>"$out/large_coordinates.csv" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
for m in j["methods"]:
    print(f'{sys.argv[2]},{sys.argv[3]},{m["name"]},{m["cull_rate"]:.5f},{m["false_culls"]},'
          f'{m["culled_not_in_reference"]},{m["oracle_invisible_rate"]:.5f}')
PY
  done
done
cat "$out/large_coordinates.csv"
