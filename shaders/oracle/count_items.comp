#version 450
// Hierarchical item buffer count (Engelhardt & Dachsbacher, "Granular Visibility Queries
// on the GPU", section 3.2): every pixel of the item buffer adds one to its patch's
// total and to the bin of (patch, screen tile) of a 2^t x 2^t tiling, i.e. bin
// patch * 2^(2t) + y * 2^t + x as in the paper's ID = baseID + instance * 2^(2t) + x + y * 2^t.
// The paper scatters with point primitives and blending; compute atomics do the same.
#include <shared/oracle_layout.h>
#include <shared/draw_layout.h>

layout(local_size_x = 8, local_size_y = 8) in;

layout(push_constant) uniform Push { CountConstants pc; };
layout(set = 0, binding = 0, r32ui) uniform readonly uimage2D items;
layout(std430, set = 0, binding = 1) buffer Counts { uint counts[]; };
layout(std430, set = 0, binding = 2) buffer Tiles { uint tiles[]; };

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= pc.width || pixel.y >= pc.height) return;
  uint item = imageLoad(items, ivec2(pixel)).x;
  if (item == kItemBackground) {
    atomicAdd(counts[pc.patchCount + kCountBackground], 1u);
  } else if (item == kItemOccluder) {
    atomicAdd(counts[pc.patchCount + kCountOccluder], 1u);
  } else if (item > pc.patchCount) {
    atomicAdd(counts[pc.patchCount + kCountUnknown], 1u);
  } else {
    uint patchIndex = item - 1u;
    atomicAdd(counts[patchIndex], 1u);
    uvec2 tile = pixel / uvec2(pc.tileWidth, pc.tileHeight);
    uint bin = (patchIndex << (2u * pc.tileLog2)) + (tile.y << pc.tileLog2) + tile.x;
    atomicAdd(tiles[bin], 1u);
  }
}
