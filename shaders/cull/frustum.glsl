// Clip-space bounds of a patch's control points and the view-frustum test: fp32 mirror of
// bound::clipBounds / bound::frustumTest (Sathe, "View Frustum Culling of Catmull-Clark
// Patches in DirectX 11", Run-Time Step: the patch lies in the convex hull of its control
// points). The test is done in homogeneous clip space, so it stays valid for points behind
// the eye; the NDC box is only built when every w is certainly positive. Gregory patches use
// their 20 points (non-negative basis functions summing to one).
#ifndef OSD_CULL_CULL_FRUSTUM_GLSL
#define OSD_CULL_CULL_FRUSTUM_GLSL
#include "cull_common.glsl"

// The points whose convex hull bounds the patch: its control points, or with CULL_DISPLACED
// the 8 corners of the displaced bound (displaced_bound.glsl). prepareBound() runs first.
#if CULL_DISPLACED
#include "displaced_bound.glsl"
#else
void prepareBound(uint patchIndex) {}
uint boundPointCount(uint patchIndex) { return pointCount(patchIndex); }
vec3 boundPoint(uint patchIndex, uint k) { return controlPoint(firstPoint(patchIndex) + k); }
vec4 boundClipPoint(vec3 p) { return clipPoint(p); }
vec4 boundAbsClipPoint(vec3 p) { return absClipPoint(p); }
#endif

// What the frustum test and the occlusion stage know about a patch's control points.
struct PatchClipBounds {
  uint outsideAll;  // bit p: every point is certainly outside plane p (bound::FrustumPlane)
  bool finite;      // every point and clip coordinate is finite
  bool hasNdcBox;   // finite and every w certainly positive: ndcMin/ndcMax are valid
  vec3 ndcMin;      // NDC box widened by the fp32 rounding bound
  vec3 ndcMax;
};

PatchClipBounds patchClipBounds(uint patchIndex) {
  PatchClipBounds b;
  b.outsideAll = 0x3Fu;
  b.finite = matrixIsFinite();
  b.hasNdcBox = true;
  b.ndcMin = vec3(3.0e38);
  b.ndcMax = vec3(-3.0e38);
  const float eps = kCullRelativeMargin;
  prepareBound(patchIndex);
#if CULL_DISPLACED
  b.finite = b.finite && gBoundFinite;
#endif
  uint n = boundPointCount(patchIndex);
  for (uint k = 0u; k < n && b.finite; ++k) {
    vec3 p = boundPoint(patchIndex, k);
    vec4 c = boundClipPoint(p);
    vec4 m = boundAbsClipPoint(p);
    if (!isFiniteF(p) || !isFiniteF(c) || !isFiniteF(m)) {
      b.finite = false;
      break;
    }
    // Signed distances to the six planes (inside >= 0) and the magnitudes behind them; a
    // point is outside only when the distance is below -eps times its magnitude.
    float dist[6] = float[6](c.x + c.w, c.w - c.x, c.y + c.w, c.w - c.y, c.z, c.w - c.z);
    float mag[6] = float[6](m.x + m.w, m.w + m.x, m.y + m.w, m.w + m.y, m.z, m.w + m.z);
    uint outside = 0u;
    for (uint plane = 0u; plane < 6u; ++plane)
      if (dist[plane] < -eps * mag[plane]) outside |= 1u << plane;
    b.outsideAll &= outside;
    if (!(c.w > eps * m.w)) {
      b.hasNdcBox = false;  // behind or on the eye plane: x/w is meaningless
      continue;
    }
    vec3 ndc = c.xyz / c.w;
    vec3 err = eps * (m.xyz + abs(ndc) * m.w) / (c.w - eps * m.w);
    b.ndcMin = min(b.ndcMin, ndc - err);
    b.ndcMax = max(b.ndcMax, ndc + err);
  }
  if (!b.finite) b.outsideAll = 0u;
  b.hasNdcBox = b.hasNdcBox && b.finite;
  return b;
}

// The frustum field of the result code: the lowest plane every point is outside of
// (culled), kFrustumInside, or kFrustumNonFinite (kept).
uint frustumCode(PatchClipBounds b) {
  if (!b.finite) return kFrustumNonFinite;
  return b.outsideAll != 0u ? uint(findLSB(b.outsideAll)) : kFrustumInside;
}
#endif
