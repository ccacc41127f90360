#version 450
// Fetches one control point: draw slot = vertex / PATCH_POINTS, patch = drawList[slot]
// (an entry: index and flags, shared/draw_layout.h kDrawList*, passed on to the later stages).
// Non-indexed draws with firstVertex = firstSlot * PATCH_POINTS.
#include "patch_common.glsl"

layout(location = 0) out vec3 vPoint;
layout(location = 1) flat out uint vPatch;

void main() {
  uint slot = uint(gl_VertexIndex) / uint(PATCH_POINTS);
  uint k = uint(gl_VertexIndex) % uint(PATCH_POINTS);
  uint entry = drawList[slot];
  vPoint = controlPoint(firstPoint(entry & kDrawListPatchMask) + k);
  vPatch = entry;
}
