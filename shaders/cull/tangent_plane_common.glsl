// Shared parts of the parametric tangent-plane test (Loop, Niessner, Eisenacher, "Effective
// Back-Patch Culling for Hardware Tessellation"): cross4Z of Appendix A, its magnitude bound,
// and the DVis classification of section 4.2 with the Pcnt rule of section 7. fp32 mirror of
// bound/tangent_plane.h. The index and weight table (bound::tangentPlaneTerms, derived from
// the definition) is in the table buffer, kTangentPlaneTermCount entries; the kernel source
// is preceded by the generated declaration of that count.
#ifndef OSD_CULL_CULL_TANGENT_PLANE_COMMON_GLSL
#define OSD_CULL_CULL_TANGENT_PLANE_COMMON_GLSL
#include "cone_of_normals.glsl"

// Term k of the table: (target, j, k, l) and the weight.
uvec4 tangentPlaneTerm(uint k) {
  uint v = table[k].x;
  return uvec4(v & 0xFFu, (v >> 8u) & 0xFFu, (v >> 16u) & 0xFFu, v >> 24u);
}
float tangentPlaneWeight(uint k) { return uintBitsToFloat(table[k].y); }

// det of the x, y, w rows of [a b c]: the z component of cross4(a, b, c).
float cross4Z(vec4 a, vec4 b, vec4 c) {
  return a.x * (b.y * c.w - b.w * c.y) - b.x * (a.y * c.w - a.w * c.y) +
         c.x * (a.y * b.w - a.w * b.y);
}

// The permanent of the absolute x, y, w rows (bound::cross4ZBound): with a, b, c the
// absClipPoint() values it bounds every product summed in cross4Z of the clip points.
float cross4ZBound(vec4 p, vec4 q, vec4 r) {
  return p.x * (q.y * r.w + q.w * r.y) + q.x * (p.y * r.w + p.w * r.y) +
         r.x * (p.y * q.w + p.w * q.y);
}

// Counts of one control plane z (times sigma) with its bound: may it be positive, negative?
// A sign counts only beyond kCullRelativeMargin * bound, so rounding never decides.
uvec2 planeSignCounts(float z, float bound) {
  float s = pc.eye.w * z, margin = kCullRelativeMargin * bound;
  return uvec2(s + margin > 0.0 ? 1u : 0u, s - margin < 0.0 ? 1u : 0u);
}

// Section 4.2 DVis with section 7's Pcnt rule from the counts over all 64 planes.
uint classifyTangentPlane(bool finite, uint pcnt, uint ncnt) {
  if (!finite) return kVerdictNonFinite;
  if (pcnt == 0u) return kVerdictBackFacing;
  if (ncnt == 0u) return kVerdictFrontFacing;
  return kVerdictSilhouette;
}
#endif
