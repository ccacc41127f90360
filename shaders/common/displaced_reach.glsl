// The region a displaced patch can reach, shared by the displaced draw's depth clamp
// (shaders/patch/patch.tesc, PATCH_DISPLACED) and the Hi-Z stage of the displaced cull
// kernel (shaders/cull/occlusion_hiz.glsl, CULL_DISPLACED), so that both see the same fp32
// corners; the double reference is bound::displacedReachCorners (osd_cull/bound/occlusion.h).
//
// Niessner & Loop §4.2 (Fig. 5) with the uniform extension ("Full", Sathe): a displaced
// patch is S = P + N D with P in the convex hull of the control points p_i, |N| = 1 and
// Dmin <= D <= Dmax, so |N D| <= R = max(Dmax, -Dmin) and, writing P = sum a_i p_i
// (a_i >= 0, sum 1), S = sum a_i (p_i + N D): every point of S lies in the convex hull of
// the boxes p_i ± R (each axis). reachCorner(p, r, k) is corner k (0..7) of such a box;
// r = displacedReach(p, R) adds kReachRelativeMargin of |p| + R, more than the fp32 rounding
// of p ± r (half an ulp), so the fp32 corners still enclose the exact boxes.
#ifndef OSD_CULL_COMMON_DISPLACED_REACH_GLSL
#define OSD_CULL_COMMON_DISPLACED_REACH_GLSL

const float kReachRelativeMargin = 1e-5;

// R = max(Dmax, -Dmin) of a patch from its (Dmin, Dmax).
float displacedReachRadius(vec2 range) { return max(range.y, -range.x); }

float displacedReach(vec3 p, float radius) {
  return radius + kReachRelativeMargin * (max(max(abs(p.x), abs(p.y)), abs(p.z)) + radius);
}

vec3 reachCorner(vec3 p, float r, int k) {
  return p + vec3((k & 1) != 0 ? r : -r, (k & 2) != 0 ? r : -r, (k & 4) != 0 ? r : -r);
}
#endif
