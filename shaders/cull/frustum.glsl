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

#if CULL_PATCH_BOXES
// The frustum test of the patch's precomputed box (CULL_PATCH_BOXES: static points, no
// occlusion stage, so no NDC box is needed): the box contains the control points, so when
// its largest value of plane p's function is below -eps times a magnitude bound, every
// control point is certainly outside plane p, as the reference requires of a cull. For the
// plane q = r_a +- r_b of rows of viewProj (the six of bound::FrustumPlane) the largest
// value over the box is q . (c, 1) + |q.xyz| . e, and the magnitude |r_a| . (|c| + e, 1) +
// |r_b| . (|c| + e, 1) bounds every product of it and of each control point's own distance
// (|p| <= |c| + e componentwise), so a box cull is a cull of the point test with its
// margin (the fp32 error of the box values, including the rounding of c and e, is a few
// 2^-24 of that magnitude). The frustum code is the lowest plane the box is outside of.
PatchClipBounds patchClipBounds(uint patchIndex) {
  PatchClipBounds b = PatchClipBounds(0u, matrixIsFinite(), false, vec3(0.0), vec3(0.0));
  vec3 c, e;
  patchBox(patchIndex, c, e);
  b.finite = b.finite && isFiniteF(c) && isFiniteF(e);
  if (!b.finite) return b;
  const mat4 m = pc.viewProjection;
  const vec4 rx = vec4(m[0].x, m[1].x, m[2].x, m[3].x), ry = vec4(m[0].y, m[1].y, m[2].y, m[3].y);
  const vec4 rz = vec4(m[0].z, m[1].z, m[2].z, m[3].z), rw = vec4(m[0].w, m[1].w, m[2].w, m[3].w);
  const vec4 planes[6] = vec4[6](rw + rx, rw - rx, rw + ry, rw - ry, rz, rw - rz);
  const vec4 ca = vec4(abs(c) + e, 1.0);
  const float mx = dot(abs(rx), ca), my = dot(abs(ry), ca), mz = dot(abs(rz), ca),
              mw = dot(abs(rw), ca);
  const float mags[6] = float[6](mw + mx, mw + mx, mw + my, mw + my, mz, mw + mz);
  const float eps = kCullRelativeMargin;
  for (uint plane = 0u; plane < 6u; ++plane) {
    const vec4 q = planes[plane];
    const float top = dot(q.xyz, c) + q.w + dot(abs(q.xyz), e);
    if (top < -eps * mags[plane]) b.outsideAll |= 1u << plane;
  }
  return b;
}
#else
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
#endif

// The frustum field of the result code: the lowest plane every point is outside of
// (culled), kFrustumInside, or kFrustumNonFinite (kept).
uint frustumCode(PatchClipBounds b) {
  if (!b.finite) return kFrustumNonFinite;
  return b.outsideAll != 0u ? uint(findLSB(b.outsideAll)) : kFrustumInside;
}
#endif
