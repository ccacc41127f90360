// Tessellation levels per edge, from the edge's own boundary curve only, so the two
// patches sharing an edge compute the same level (no cracks). Transition edges (Far
// PatchParam transition bits) are split at their midpoint into a Lo and a Hi half, each
// levelled like the neighbouring finer patch's edge, as OpenSubdiv's
// OsdEvalPatchBezierTessLevels / OsdComputeTessLevels do for equal spacing.
// The includer defines the parameters (the draw shaders from DrawConstants, the cull kernel
// from CullConstants, which computes the same levels for its drawn-triangle bound):
//   mat4 tessViewProjection(); vec2 tessViewportSize(); float tessPixelsPerSegment();
//   float tessUniformLevel(); float tessMaxLevel(); uint tessMode();
#ifndef OSD_CULL_TESS_LEVELS_GLSL
#define OSD_CULL_TESS_LEVELS_GLSL
#include "edge_curves.glsl"

// Pixel position of a world point; w <= 0 reports false.
bool toPixels(vec3 p, out vec2 pixel) {
  vec4 c = tessViewProjection() * vec4(p, 1.0);
  pixel = c.xy / c.w * 0.5 * tessViewportSize();
  return c.w > 1e-6;
}

// Pixels per world unit of a short vector at p in any direction, to first order: the
// projection's Jacobian 0.5 v (r_i - (c_i / w) r_3) / w bounded by the norms of the rows
// r_i of its linear part (host mirror: tess_levels.cpp). Only called with w > 1e-6.
float pixelScale(vec3 p) {
  mat4 m = tessViewProjection();
  vec4 c = m * vec4(p, 1.0);
  vec2 v = tessViewportSize();
  float r0 = length(vec3(m[0][0], m[1][0], m[2][0]));
  float r1 = length(vec3(m[0][1], m[1][1], m[2][1]));
  float r3 = length(vec3(m[0][3], m[1][3], m[2][3]));
  return 0.5 * max(v.x * (r0 + abs(c.x / c.w) * r3), v.y * (r1 + abs(c.y / c.w) * r3)) / c.w;
}

// Segments for one cubic curve: its screen-space control-polygon length over the target
// segment length, rounded up, in [1, maxLevel]. The sum is ordered so that the reversed
// curve gives the bit-identical result (neighbours traverse shared edges oppositely).
// A curve reaching behind the eye gets maxLevel. `offset` (world units, >= 0): the
// displacement's variation along the curve (displaced draws, docs/algorithms/
// displacement.md "Tessellation"), added at the curve's largest pixel scale; max is
// order-free, so the reversed curve still gives the same level.
float curveLevel(vec3 b0, vec3 b1, vec3 b2, vec3 b3, float offset, float maxLevel) {
  vec2 s0, s1, s2, s3;
  bool ok = toPixels(b0, s0);
  ok = toPixels(b1, s1) && ok;
  ok = toPixels(b2, s2) && ok;
  ok = toPixels(b3, s3) && ok;
  if (!ok) return maxLevel;
  float len = (distance(s0, s1) + distance(s2, s3)) + distance(s1, s2);
  if (offset > 0.0)
    len += offset * max(max(pixelScale(b0), pixelScale(b1)), max(pixelScale(b2), pixelScale(b3)));
  float level = ceil(len / tessPixelsPerSegment());
  // NaN or Inf coordinates: keep the patch drawn at the finest level.
  if (!(level >= 1.0)) return level < 1.0 ? 1.0 : maxLevel;
  return min(level, maxLevel);
}

// Outer levels split into Lo and Hi halves (Hi is 0 on non-transition edges), from the
// four boundary curves (curves[4e + k]: point k of edge e's curve, see edge_curves.glsl)
// and the displacement's variation along each edge or half (offsetLo, offsetHi; zero for
// undisplaced patches).
// The uniform levels: they depend on the transition edges only, not on the curves.
void uniformEdgeLevels(uint transition, out vec4 lo, out vec4 hi) {
  float maxLevel = tessMaxLevel(), uniformLevel = tessUniformLevel();
  for (int e = 0; e < 4; ++e) {
    bool split = (transition & kEdgeTransitionBit[e]) != 0u;
    float level = split ? min(uniformLevel, floor(maxLevel * 0.5)) : min(uniformLevel, maxLevel);
    lo[e] = level;
    hi[e] = split ? level : 0.0;
  }
}

void curveEdgeLevels(vec3 curves[16], uint transition, vec4 offsetLo, vec4 offsetHi,
                     out vec4 lo, out vec4 hi) {
  if (tessMode() == kTessUniform) {
    uniformEdgeLevels(transition, lo, hi);
    return;
  }
  float maxLevel = tessMaxLevel();
  for (int e = 0; e < 4; ++e) {
    vec3 b0 = curves[4 * e + 0];
    vec3 b1 = curves[4 * e + 1];
    vec3 b2 = curves[4 * e + 2];
    vec3 b3 = curves[4 * e + 3];
    bool split = (transition & kEdgeTransitionBit[e]) != 0u;
    if (!split) {
      // Half the maximum, so that a neighbour's transition edge can hold two of these.
      lo[e] = curveLevel(b0, b1, b2, b3, offsetLo[e], floor(maxLevel * 0.5));
      hi[e] = 0.0;
    } else {
      // de Casteljau at 1/2: the halves are the finer neighbours' edges.
      vec3 b01 = 0.5 * (b0 + b1), b12 = 0.5 * (b1 + b2), b23 = 0.5 * (b2 + b3);
      vec3 b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23);
      vec3 m = 0.5 * (b012 + b123);
      lo[e] = curveLevel(b0, b01, b012, m, offsetLo[e], floor(maxLevel * 0.5));
      hi[e] = curveLevel(m, b123, b23, b3, offsetHi[e], floor(maxLevel * 0.5));
    }
  }
}

void curveEdgeLevels(vec3 curves[16], uint transition, out vec4 lo, out vec4 hi) {
  curveEdgeLevels(curves, transition, vec4(0.0), vec4(0.0), lo, hi);
}

// The levels as the levels pass stores them (tess_levels.comp): Lo and Hi of the four edges,
// one byte each (integers in [0, 64]: exact).
uvec2 packTessLevels(vec4 lo, vec4 hi) {
  uvec4 l = uvec4(lo), h = uvec4(hi);
  return uvec2(l.x | (l.y << 8u) | (l.z << 16u) | (l.w << 24u),
               h.x | (h.y << 8u) | (h.z << 16u) | (h.w << 24u));
}
void unpackTessLevels(uvec2 packed, out vec4 lo, out vec4 hi) {
  uvec4 shifts = uvec4(0u, 8u, 16u, 24u);
  lo = vec4((uvec4(packed.x) >> shifts) & 0xFFu);
  hi = vec4((uvec4(packed.y) >> shifts) & 0xFFu);
}

#if defined(PATCH_POINTS)
void edgeLevels(vec3 cp[PATCH_POINTS], uint transition, vec4 offsetLo, vec4 offsetHi,
                out vec4 lo, out vec4 hi) {
  vec3 curves[16];
  for (int k = 0; k < 16; ++k) curves[k] = cp[kEdgeCurve[k]];
  curveEdgeLevels(curves, transition, offsetLo, offsetHi, lo, hi);
}
#endif
#endif
