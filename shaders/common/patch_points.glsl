// Patch control points and finite tests, shared by the cull kernel (cull/cull_common.glsl)
// and the bounds pass (bounds/bounds_common.glsl). The includer declares a push-constant
// block `pc` with bezierCount, pointOffset and pointStride, and defines POINTS_BINDING and
// OSD_CULL_POINTS_BDA for controlPoint() (control_points.glsl: GpuPatchSet::points(),
// PatchSet layout: Bezier patches first, then Gregory).
#ifndef OSD_CULL_COMMON_PATCH_POINTS_GLSL
#define OSD_CULL_COMMON_PATCH_POINTS_GLSL

// Finite test on the bits, so that no fast-math assumption can fold it away.
bool isFiniteF(float x) { return (floatBitsToUint(x) & 0x7F800000u) != 0x7F800000u; }
bool isFiniteF(vec3 v) { return isFiniteF(v.x) && isFiniteF(v.y) && isFiniteF(v.z); }
bool isFiniteF(vec4 v) { return isFiniteF(v.xyz) && isFiniteF(v.w); }

bool isBezier(uint patchIndex) { return patchIndex < pc.bezierCount; }
uint pointCount(uint patchIndex) { return isBezier(patchIndex) ? 16u : 20u; }

// Index of the first control point of a patch.
uint firstPoint(uint patchIndex) {
  return isBezier(patchIndex) ? patchIndex * 16u
                              : pc.bezierCount * 16u + (patchIndex - pc.bezierCount) * 20u;
}

#include "control_points.glsl"
#endif
