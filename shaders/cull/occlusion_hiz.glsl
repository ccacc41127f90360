// The Hi-Z occlusion stage of the cull kernel (cull_main.glsl's occlusion hook): Niessner &
// Loop §4.1.1 with the functions of hiz/occlusion.glsl, against the pyramid of the frame's
// first pass. Resources (descriptor set 1, frame/hiz_cull_stage.h): the pyramid (all
// levels, read with texelFetch) and its HiZParams.
#ifndef OSD_CULL_CULL_OCCLUSION_HIZ_GLSL
#define OSD_CULL_CULL_OCCLUSION_HIZ_GLSL
#include "cull_common.glsl"
#include "hiz/occlusion.glsl"
#if CULL_DISPLACED
#include "../common/displaced_reach.glsl"
#endif

layout(set = 1, binding = 0) uniform sampler2D hizPyramid;
layout(std140, set = 1, binding = 1) uniform HiZUniform { HiZParams hizParams; };

// 0 (kOcclusionVerdictOccluded) when occluded; otherwise kOcclusionVerdictUntested (a point
// at or behind the eye, NaN/Inf, off screen) or kOcclusionVerdictVisible with the pyramid
// level looked at in bits 4-7.
uint occlusionVerdict(uint patchIndex, PatchClipBounds bounds) {
  if (!bounds.finite) return kOcclusionVerdictUntested;
  HiZBox box = hizBoxBegin();
  // The points patchClipBounds() used (control points, or the displaced bound's corners).
  uint n = boundPointCount(patchIndex);
  for (uint k = 0u; k < n; ++k) {
    vec3 p = boundPoint(patchIndex, k);
    hizBoxAdd(box, boundClipPoint(p), boundAbsClipPoint(p));
  }
  int level;
  ivec2 t0, t1;
  if (!hizFootprint(box, hizParams, level, t0, t1)) return kOcclusionVerdictUntested;
#if CULL_DISPLACED
  // The displaced draw clamps fragment depth to the nearest fp32 depth of the boxes
  // p_i ± r_i around the control points (patch.tesc, common/displaced_reach.glsl; the same
  // floats: cones[].xy is (Dmin, Dmax) rounded as the draw's copy): that, minus the
  // margins, is the nearest depth of every fragment, whatever bound gave the rectangle.
  // Not tested when a corner is at or behind the eye plane (the draw does not clamp then).
  HiZBox reach = hizBoxBegin();
  vec4 range = cones[kConeVec4s * patchIndex];
  float radius = displacedReachRadius(range.xy);
  uint first = firstPoint(patchIndex), points = pointCount(patchIndex);
  for (uint i = 0u; i < points; ++i) {
    vec3 p = controlPoint(first + i);
    float r = displacedReach(p, radius);
    for (int k = 0; k < 8; ++k) {
      vec3 q = reachCorner(p, r, k);
      hizBoxAdd(reach, clipPoint(q), absClipPoint(q));
    }
  }
  if (!reach.valid || !isFiniteF(range)) return kOcclusionVerdictUntested;
  box.nearest = reach.nearest;
#endif
  if (hizOccluded(box, hizParams, hizPyramid)) return kOcclusionVerdictOccluded;
  return kOcclusionVerdictVisible | (uint(level) << kOcclusionVerdictLevelShift);
}
#endif
