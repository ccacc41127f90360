#version 450
// Passes the control points through and sets the tessellation levels (tess_levels.glsl).
// A draw-list entry flagged kDrawListCulled gets levels 0: the patch is discarded before
// evaluation and its levels are never computed (Niessner & Loop §5).
#include "patch_common.glsl"
#include "tess_levels.glsl"

layout(vertices = PATCH_POINTS) out;

layout(location = 0) in vec3 vPoint[];
layout(location = 1) flat in uint vPatch[];

layout(location = 0) out vec3 tcPoint[];
layout(location = 1) patch out uint tcPatch;
layout(location = 2) patch out vec4 tcLo;
layout(location = 3) patch out vec4 tcHi;
// The smallest fp32 depth z/w of the control points, or 0 (no clamp): patch.frag writes no
// fragment depth below it. Proof that this keeps the image and makes the Hi-Z bound hold
// (Niessner & Loop §4.1.1; docs/algorithms/occlusion.md, "Sub-pixel patches"):
// - the surface lies in the convex hull of its control points (Bezier and Gregory weights
//   are non-negative and sum to 1), and in clip space a point of the hull is
//   c = sum a_i c_i with a_i >= 0, so with every w_i > 0 its depth is
//   z/w = sum (a_i w_i / sum a_j w_j) (z_i / w_i), a convex combination of the points'
//   depths: the exact surface never lies in front of min z_i/w_i, so the clamp only moves
//   fragments that the rasterizer put in front of the patch (depth extrapolated past a
//   thin triangle: lavapipe decides coverage on vertices snapped to 1/256 pixel but
//   interpolates the plane of the float vertices; or fp32 rounding of the evaluation);
// - the cull's nearest depth (bound::hizScreenBox, hiz/occlusion.glsl) is min over points of
//   z/w minus err, err bounding the fp32 rounding of exactly this product and quotient, so
//   it never exceeds the value computed here; every fragment of a culled patch then has
//   depth >= nearest >= the farthest depth stored under its box and fails LESS.
// When some w <= 0 (the patch reaches the eye plane) the cull never tests the patch and the
// hull argument fails, so there is no clamp. The displaced draw moves points off the hull:
// no clamp either (its cull keeps the extrapolation estimate, HiZFragmentDepth::Extrapolated).
layout(location = 4) patch out float tcNearestDepth;

float nearestControlPointDepth(vec3 cp[PATCH_POINTS]) {
#if defined(PATCH_DISPLACED)
  return 0.0;
#else
  float nearest = 3.4028234e38;
  for (int i = 0; i < PATCH_POINTS; ++i) {
    vec4 c = pc.viewProjection * vec4(cp[i], 1.0);
    float z = c.z / c.w;
    if (!(c.w > 0.0) || isinf(c.w) || isnan(z) || isinf(z)) return 0.0;
    nearest = min(nearest, z);
  }
  return nearest;
#endif
}

void main() {
  tcPoint[gl_InvocationID] = vPoint[gl_InvocationID];
  if (gl_InvocationID == 0 && (vPatch[0] & kDrawListCulled) != 0u) {
    gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelOuter[3] = 0.0;
    gl_TessLevelInner[0] = gl_TessLevelInner[1] = 0.0;
    tcPatch = vPatch[0];
    tcLo = tcHi = vec4(0.0);
    tcNearestDepth = 0.0;
  } else if (gl_InvocationID == 0) {
    vec3 cp[PATCH_POINTS];
    for (int i = 0; i < PATCH_POINTS; ++i) cp[i] = vPoint[i];
    uint patchIndex = vPatch[0] & kDrawListPatchMask;
    vec4 lo, hi;
    edgeLevels(cp, transitionMask(patchIndex), lo, hi);
    vec4 outer = lo + hi;
    gl_TessLevelOuter[0] = outer[0];
    gl_TessLevelOuter[1] = outer[1];
    gl_TessLevelOuter[2] = outer[2];
    gl_TessLevelOuter[3] = outer[3];
    // As OsdComputeTessLevels: inner levels average the opposite outer levels.
    gl_TessLevelInner[0] = (outer[1] + outer[3]) * 0.5;
    gl_TessLevelInner[1] = (outer[0] + outer[2]) * 0.5;
    tcPatch = vPatch[0];
    tcLo = lo;
    tcHi = hi;
    tcNearestDepth = (pc.flags & kFlagNoDepthClamp) != 0u ? 0.0 : nearestControlPointDepth(cp);
  }
}
