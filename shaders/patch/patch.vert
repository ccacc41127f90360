#version 450
// Fetches one control point: draw slot = vertex / PATCH_POINTS, patch = drawList[slot].
// Non-indexed draws with firstVertex = firstSlot * PATCH_POINTS.
#include "patch_common.glsl"

layout(location = 0) out vec3 vPoint;
layout(location = 1) flat out uint vPatch;

void main() {
  uint slot = uint(gl_VertexIndex) / uint(PATCH_POINTS);
  uint k = uint(gl_VertexIndex) % uint(PATCH_POINTS);
  uint patchIndex = drawList[slot];
  vPoint = controlPoint(firstPoint(patchIndex) + k);
  vPatch = patchIndex;
}
