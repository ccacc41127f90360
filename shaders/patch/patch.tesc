#version 450
// Passes the control points through and sets the tessellation levels (tess_levels.glsl), or
// with kFlagTessLevelsFromBuffer the levels the levels pass wrote for this view
// (tess_levels.comp: the same function of each edge's curve, computed once per patch and
// read by the draws and the cull kernel alike).
// A draw-list entry flagged kDrawListCulled gets levels 0: the patch is discarded before
// evaluation and its levels are never computed (Niessner & Loop §5).
// The displaced variant (PATCH_DISPLACED) adds the displacement's variation along each
// edge to its adaptive level (docs/algorithms/displacement.md, "Tessellation").
#include "patch_common.glsl"
#include "tess_levels.glsl"
#if defined(PATCH_DISPLACED)
#include <shared/displacement_layout.h>
layout(std430, set = kDisplaceSet, binding = kDisplaceBindingEdges) readonly buffer
    EdgeDisplacementBuffer {
  vec4 edgeDisplacement[];
};
layout(std430, set = kDisplaceSet, binding = kDisplaceBindingRanges) readonly buffer
    DisplacementRangeBuffer {
  vec2 displacementRanges[];  // (Dmin, Dmax) per patch
};
#include "../common/displaced_reach.glsl"

// The displacement length each edge (Lo and Hi halves) adds, as frame::edgeDisplacementTerms.
void displacementOffsets(uint patchIndex, uint transition, out vec4 offsetLo, out vec4 offsetHi) {
  offsetLo = offsetHi = vec4(0.0);
  if ((pc.flags & kFlagTessIgnoreDisplacement) != 0u) return;
  vec4 whole = edgeDisplacement[3u * patchIndex];
  if ((pc.flags & kFlagTessPerPatchDisplacement) != 0u) {
    offsetLo = offsetHi = vec4(max(max(whole.x, whole.y), max(whole.z, whole.w)));
    return;
  }
  vec4 first = edgeDisplacement[3u * patchIndex + 1u];
  vec4 second = edgeDisplacement[3u * patchIndex + 2u];
  for (int e = 0; e < 4; ++e) {
    bool split = (transition & kEdgeTransitionBit[e]) != 0u;
    offsetLo[e] = split ? first[e] : whole[e];
    offsetHi[e] = split ? second[e] : 0.0;
  }
}
#endif

layout(vertices = PATCH_POINTS) out;

layout(location = 0) in vec3 vPoint[];
layout(location = 1) flat in uint vPatch[];

layout(location = 0) out vec3 tcPoint[];
layout(location = 1) patch out uint tcPatch;
layout(location = 2) patch out vec4 tcLo;
layout(location = 3) patch out vec4 tcHi;
// The smallest fp32 depth z/w of the control points (of the region a displaced patch can
// reach, PATCH_DISPLACED), or 0 (no clamp): patch.frag writes no fragment depth below it.
// Proof that this keeps the image and makes the Hi-Z bound hold (Niessner & Loop §4.1.1;
// docs/algorithms/occlusion.md, "Sub-pixel patches" and "Displaced patches"):
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
// Displaced patches (S = P + N D, Niessner & Loop §4.2, Fig. 5, uniform extension): the
// same argument with the points replaced by the 8 corners of the box p_i ± r_i around every
// control point (common/displaced_reach.glsl: S lies in the convex hull of those boxes,
// r_i >= max(Dmax, -Dmin) of the patch, rounded outward as the kernel's cones[] hold it).
// The displaced cull kernel (cull/occlusion_hiz.glsl) takes its nearest depth from the very
// same fp32 corners (same include, same per-patch floats) minus its margins, and
// bound::displacedFragmentDepth in double, so again nearest <= this value: a proof for
// every displaced kernel, whatever cone or box (OOBB, CAF) gives its screen rectangle.
// When some w <= 0 (the patch reaches the eye plane) the cull never tests the patch (it
// requires w > 2^-17 |w| terms, beyond any rounding difference) and the hull argument
// fails, so there is no clamp.
layout(location = 4) patch out float tcNearestDepth;

// Folds point p into the running minimum of z/w; false when w <= 0 or NaN/Inf (no clamp).
bool addDepth(inout float nearest, vec3 p) {
  vec4 c = pc.viewProjection * vec4(p, 1.0);
  float z = c.z / c.w;
  if (!(c.w > 0.0) || isinf(c.w) || isnan(z) || isinf(z)) return false;
  nearest = min(nearest, z);
  return true;
}

float nearestControlPointDepth(uint patchIndex, vec3 cp[PATCH_POINTS]) {
  float nearest = 3.4028234e38;
#if defined(PATCH_DISPLACED)
  float radius = displacedReachRadius(displacementRanges[patchIndex]);
  for (int i = 0; i < PATCH_POINTS; ++i) {
    float r = displacedReach(cp[i], radius);
    for (int k = 0; k < 8; ++k)
      if (!addDepth(nearest, reachCorner(cp[i], r, k))) return 0.0;
  }
#else
  for (int i = 0; i < PATCH_POINTS; ++i)
    if (!addDepth(nearest, cp[i])) return 0.0;
#endif
  return nearest;
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
    uint transition = transitionMask(patchIndex);
    vec4 offsetLo = vec4(0.0), offsetHi = vec4(0.0);
#if defined(PATCH_DISPLACED)
    if (tessMode() == kTessAdaptive)
      displacementOffsets(patchIndex, transition, offsetLo, offsetHi);
#endif
    vec4 lo, hi;
    if ((pc.flags & kFlagTessLevelsFromBuffer) != 0u)
      unpackTessLevels(tessLevels[pc.levelBase + patchIndex], lo, hi);
    else
      edgeLevels(cp, transition, offsetLo, offsetHi, lo, hi);
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
    tcNearestDepth = (pc.flags & kFlagNoDepthClamp) != 0u ? 0.0 : nearestControlPointDepth(patchIndex, cp);
  }
}
