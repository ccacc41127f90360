// The Hi-Z occlusion stage of the cull kernel (cull_main.glsl's occlusion hook): Niessner &
// Loop §4.1.1 with the functions of hiz/occlusion.glsl, against the pyramid of the frame's
// first pass. Resources (descriptor set 1, frame/hiz_cull_stage.h): the pyramid (all
// levels, read with texelFetch) and its HiZParams.
#ifndef OSD_CULL_CULL_OCCLUSION_HIZ_GLSL
#define OSD_CULL_CULL_OCCLUSION_HIZ_GLSL
#include "cull_common.glsl"
#include "hiz/occlusion.glsl"

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
  // Undisplaced draws clamp fragment depth to the control points' nearest (patch.frag);
  // the displaced draw does not, and keeps the extrapolation estimate.
#if CULL_DISPLACED
  const bool extrapolated = true;
#else
  const bool extrapolated = false;
#endif
  if (hizOccluded(box, hizParams, hizPyramid, extrapolated)) return kOcclusionVerdictOccluded;
  return kOcclusionVerdictVisible | (uint(level) << kOcclusionVerdictLevelShift);
}
#endif
