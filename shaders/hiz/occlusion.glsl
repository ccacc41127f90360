// Hi-Z occlusion test of one patch (Niessner & Loop §4.1.1), the fp32 mirror of
// bound::hizScreenBox / hizFootprint / hizOcclusionTest (osd_cull/bound/occlusion.h).
//
// Usage: HiZBox b = hizBoxBegin(); for every control point p (16 Bezier, 20 Gregory):
// hizBoxAdd(b, viewProj * vec4(p, 1), absViewProj * vec4(abs(p), 1)); then
// hizOccluded(b, params, pyramid). The margins are kHiZGpuMarginScale times the
// reference's, so fp32 rounding can only make this cull less than the reference.
#ifndef OSD_CULL_HIZ_OCCLUSION_GLSL
#define OSD_CULL_HIZ_OCCLUSION_GLSL
#include <shared/hiz_layout.h>

const float kHiZInf = 3.4028234e38;  // largest float: start of min() / max()

struct HiZBox {
  vec2 lo;        // NDC x, y box, widened by the rounding margins
  vec2 hi;
  float nearest;  // smallest z/w minus margins
  float farthest; // largest z/w plus margins
  bool valid;     // false: a point at or behind the eye plane, or NaN/Inf
};

HiZBox hizBoxBegin() { return HiZBox(vec2(kHiZInf), vec2(-kHiZInf), kHiZInf, -kHiZInf, true); }

// Adds one control point: c = viewProj * (p, 1), m = |viewProj| * (|p|, 1).
void hizBoxAdd(inout HiZBox b, vec4 c, vec4 m) {
  const float rel = kHiZRelativeError * kHiZGpuMarginScale;
  if (any(isnan(c)) || any(isinf(c)) || any(isinf(m)) || !(c.w > rel * m.w)) {
    b.valid = false;
    return;
  }
  float w = c.w - rel * m.w;
  vec3 ndc = c.xyz / c.w;
  vec3 err = rel * (m.xyz + abs(ndc) * m.w) / w;
  b.lo = min(b.lo, ndc.xy - err.xy);
  b.hi = max(b.hi, ndc.xy + err.xy);
  b.nearest = min(b.nearest, ndc.z - err.z);
  b.farthest = max(b.farthest, ndc.z + err.z);
}

// The footprint of the box: level ceil(log2(n)) - baseShift for an n-pixel box (one finer
// with kHiZLookupTight when the box allows), and up to 2 x 2 texels there (ceil, not floor:
// floor could need 3 x 3). Returns false when the box
// misses the screen or is invalid.
bool hizFootprint(HiZBox b, HiZParams hiz, out int level, out ivec2 t0, out ivec2 t1) {
  level = 0;
  t0 = t1 = ivec2(0);
  if (!b.valid) return false;
  const float pad = kHiZPixelMargin * kHiZGpuMarginScale;
  vec2 size = vec2(hiz.width, hiz.height);
  vec2 p0 = (b.lo * 0.5 + 0.5) * size - pad;
  vec2 p1 = (b.hi * 0.5 + 0.5) * size + pad;
  if (any(isnan(p0)) || any(isnan(p1)) || any(isinf(p0)) || any(isinf(p1))) return false;
  if (p1.x < 0.0 || p1.y < 0.0 || p0.x > size.x || p0.y > size.y) return false;
  ivec2 last = ivec2(hiz.width, hiz.height) - 1;
  ivec2 x0 = clamp(ivec2(floor(max(p0, vec2(0.0)))), ivec2(0), last);
  ivec2 x1 = clamp(ivec2(floor(min(p1, size))), ivec2(0), last);
  int n = max(x1.x - x0.x, x1.y - x0.y) + 1;
  int k = n <= 1 ? 0 : findMSB(n - 1) + 1;
  level = clamp(k - int(hiz.baseShift), 0, int(hiz.levelCount) - 1);
  if (hiz.lookup == kHiZLookupTight && level > 0) {
    int finer = level - 1 + int(hiz.baseShift);
    ivec2 span = (x1 >> finer) - (x0 >> finer);
    if (span.x <= 1 && span.y <= 1) level -= 1;
  }
  int shift = level + int(hiz.baseShift);
  ivec2 levelLast = max(ivec2(hiz.level0Width, hiz.level0Height) >> level, ivec2(1)) - 1;
  t0 = min(x0 >> shift, levelLast);
  t1 = min(x1 >> shift, levelLast);
  return true;
}

// True when no fragment of the patch can pass a LESS depth test against the depths the
// pyramid was built from: its nearest depth is not nearer than the farthest of the texels.
// The draw clamps each fragment's depth to at least the nearest fp32 control-point depth
// (patch.tesc, patch.frag; bound::hizScreenBox), or for displaced
// patches the nearest depth of the boxes around them (common/displaced_reach.glsl, which the
// displaced kernel puts into b.nearest), which b.nearest (2x the reference's margins) never
// exceeds.
bool hizOccluded(HiZBox b, HiZParams hiz, sampler2D pyramid) {
  if (hiz.enabled == 0u) return false;
  int level;
  ivec2 t0, t1;
  if (!hizFootprint(b, hiz, level, t0, t1)) return false;
  float far = max(max(texelFetch(pyramid, t0, level).r, texelFetch(pyramid, ivec2(t1.x, t0.y), level).r),
                  max(texelFetch(pyramid, ivec2(t0.x, t1.y), level).r, texelFetch(pyramid, t1, level).r));
  float nearest = b.nearest - kHiZDepthBias * kHiZGpuMarginScale;
  return nearest >= far;
}
#endif
