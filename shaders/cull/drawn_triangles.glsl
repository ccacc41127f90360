// The drawn-triangle bound of the back-patch stage: fp32 mirror of bound/drawn_triangles.h
// (docs/algorithms/drawn-triangles.md). The back-patch tests are exact for the surface; a
// patch is culled only if every chord triangle the tessellator draws faces away too. The
// kernel computes each patch's tessellation levels with the draw shaders' own code
// (patch/tess_levels.glsl), bounds the shape of the worst triangle, and from the patch's
// derivative bounds G and H the largest deviation of a triangle normal from a surface normal.
// Every quantity is rounded up by kDrawnSafety, far more than its fp32 error. Adaptive levels
// precomputed by the levels pass (CULL_LEVELS 2: patch/tess_levels.comp, read by the draws too)
// are the drawn integers themselves; computed here instead, they get a slack of 2 (the draw
// shader's fp32 levels may differ from these by one; the double reference allows one). So
// every GPU cull is a cull of the reference.
// Included when CULL_DRAWN is 1.
#ifndef OSD_CULL_CULL_DRAWN_TRIANGLES_GLSL
#define OSD_CULL_CULL_DRAWN_TRIANGLES_GLSL
#include "cull_common.glsl"
#include <shared/draw_layout.h>

layout(std430, set = 0, binding = kCullBindingParams) readonly buffer Params { uint params[]; };

// Parameters of tess_levels.glsl from CullConstants.
mat4 tessViewProjection() { return pc.viewProjection; }
vec2 tessViewportSize() { return pc.viewport.xy; }
float tessPixelsPerSegment() { return pc.tessPixelsPerSegment; }
float tessUniformLevel() { return pc.viewport.z; }
float tessMaxLevel() { return pc.viewport.w; }
// Where the levels come from is fixed when the kernel is composed (CULL_LEVELS, chosen per
// record by CullPass::levelSource): llvmpipe runs every branch of a kernel under a mask
// whether or not a lane takes it, so a run-time choice between the three sources paid for
// all three in every invocation, the 16 curve loads and 32 projections of the computed
// levels included (twice in the deferring kernel), even where the levels were uniform or
// read from the levels pass (docs/results/cull-kernel-floor.md, "Branches cost").
#if CULL_LEVELS == 1  // uniform levels: integers the kernel knows
uint tessMode() { return kTessUniform; }
#elif CULL_LEVELS == 2 || CULL_LEVELS == 3  // adaptive: the levels pass's, or computed here
uint tessMode() { return kTessAdaptive; }
#else
#error "CULL_LEVELS must be 1 (uniform), 2 (exact adaptive) or 3 (adaptive from the curves)"
#endif
#include "patch/tess_levels.glsl"

layout(std430, set = 0, binding = kCullBindingTessLevels) readonly buffer TessLevels {
  uvec2 tessLevels[];
};

// Whether the levels below are the drawn integers: uniform, or precomputed for the draws.
bool drawnLevelsExact() { return CULL_LEVELS != 3; }

const float kDrawnSafety = 1.001;

vec2 drawnLevelRange(float level, float slack) {
  float l = max(1.0, ceil(level));
  return vec2(max(1.0, l - slack), l + slack);
}

vec2 drawnInnerRange(vec2 a, vec2 b) {
  return max(vec2(2.0), vec2(ceil(0.5 * (a.x + b.x)), ceil(0.5 * (a.y + b.y))));
}

// The Lo and Hi outer levels the draw shaders set for a patch (Bezier or Gregory) in this
// view.
void drawnEdgeLevels(uint patchIndex, out vec4 levelLo, out vec4 levelHi) {
#if CULL_LEVELS == 2
  unpackTessLevels(tessLevels[gLevelBase + patchIndex], levelLo, levelHi);
#elif CULL_LEVELS == 1  // no curve loads: on lavapipe they dominate the kernel
  uniformEdgeLevels(params[2u * patchIndex] >> 28u, levelLo, levelHi);
#else
  uint first = firstPoint(patchIndex);
  bool bezier = isBezier(patchIndex);
  vec3 curves[16];
  for (int k = 0; k < 16; ++k)
    curves[k] = controlPoint(first + uint(bezier ? kEdgeCurveBezier[k] : kEdgeCurveGregory[k]));
  curveEdgeLevels(curves, params[2u * patchIndex] >> 28u, levelLo, levelHi);
#endif
}

#ifdef CULL_DRAWN_LIST_LEVEL
// The outer levels the tessellator draws for this view (each half of a split edge rounded up
// to a whole count, at least 1: lo, hi, outer = lo + hi) and whether the listed-triangle test
// (drawn_triangle_set.glsl drawnTrianglesFaceAway) can decide the patch: exact levels, a
// finite eye and every outer level at most CULL_DRAWN_LIST_LEVEL (64 with
// CullSettings::drawnEnumerate, else bound::kDrawnListLowLevel: where the listing is cheap and
// the bound loose). `allOnes`: every edge is one segment.
bool drawnListedLevels(uint patchIndex, out float lo[4], out float hi[4], out float outer[4],
                       out bool allOnes) {
  allOnes = true;
  for (int e = 0; e < 4; ++e) lo[e] = hi[e] = outer[e] = 0.0;
  if (!drawnLevelsExact() || pc.eye.w == 0.0) return false;
  vec4 levelLo, levelHi;
  drawnEdgeLevels(patchIndex, levelLo, levelHi);
  for (int e = 0; e < 4; ++e) {
    lo[e] = max(1.0, ceil(levelLo[e]));
    hi[e] = levelHi[e] > 0.0 ? max(1.0, ceil(levelHi[e])) : 0.0;
    outer[e] = lo[e] + hi[e];
    if (!(outer[e] <= float(CULL_DRAWN_LIST_LEVEL))) return false;
    allOnes = allOnes && outer[e] == 1.0;
  }
  return true;
}

// Whether the listed-triangle test can decide the patch (drawnListedLevels).
bool drawnListable(uint patchIndex) {
  float lo[4], hi[4], outer[4];
  bool allOnes;
  return drawnListedLevels(patchIndex, lo, hi, outer, allOnes);
}
#endif

// bound::triangleShape of a Bezier patch for this view: (phi, psi, minEdge).
vec3 drawnShape(uint patchIndex) {
  vec4 levelLo, levelHi;
  drawnEdgeLevels(patchIndex, levelLo, levelHi);
  const float slack = drawnLevelsExact() ? 0.0 : 2.0;
  vec2 lo[4], hi[4], outer[4];
  bool allOnes = slack == 0.0;
  for (int e = 0; e < 4; ++e) {
    bool split = levelHi[e] > 0.0;
    lo[e] = drawnLevelRange(levelLo[e], slack);
    hi[e] = split ? drawnLevelRange(levelHi[e], slack) : vec2(0.0);
    outer[e] = lo[e] + hi[e];
    allOnes = allOnes && !split && outer[e].y == 1.0;
  }
  if (allOnes) return vec3(2.02 * kDrawnSafety, 1.01 * kDrawnSafety, 0.89);
  vec2 inner0 = drawnInnerRange(outer[1], outer[3]);  // subdivides u
  vec2 inner1 = drawnInnerRange(outer[0], outer[2]);  // subdivides v
  vec2 su = vec2(1.0 / inner0.y, 1.0 / inner0.x), sv = vec2(1.0 / inner1.y, 1.0 / inner1.x);
  float phi = su.y + sv.y, psi = su.y * sv.y, minEdge = min(su.x, sv.x);
  for (int e = 0; e < 4; ++e) {
    vec2 along = (e % 2 == 0) ? sv : su;
    vec2 depth = (e % 2 == 0) ? su : sv;
    float segMax, segMin, shift = 0.0;
    if (levelHi[e] > 0.0) {
      segMax = max(0.5 / lo[e].x, 0.5 / hi[e].x);
      segMin = min(0.5 / lo[e].y, 0.5 / hi[e].y);
      float diff = abs(levelHi[e] - levelLo[e]) + 2.0 * slack;
      shift = min(0.5, diff / (2.0 * outer[e].x));
    } else {
      segMax = 1.0 / outer[e].x;
      segMin = 1.0 / outer[e].y;
    }
    minEdge = min(minEdge, segMin);
    float base = max(segMax, along.y);
    // Apex offset of the stitching: bound::triangleShape says why.
    float sigmaMax = 1.0 / outer[e].x, sigmaMin = 1.0 / outer[e].y;
    float countDiff = max(abs(outer[e].x - 1.0 / along.x), abs(outer[e].y - 1.0 / along.y));
    float spacingDiff = max(abs(sigmaMax - along.x), abs(sigmaMin - along.y));
    float minSpacing = min(sigmaMax, along.y);
    float offset = min(1.1 * (countDiff * minSpacing + spacingDiff),
                       0.8 * (max(sigmaMax, along.y) + 0.5 * countDiff * minSpacing)) +
                   shift;
    float kappa = 1.0 + offset / depth.x;
    phi = max(phi, kappa * (base + offset + depth.y));
    psi = max(psi, kappa * base * (offset + depth.y));
  }
  return vec3(phi * 1.01 * kDrawnSafety, psi * 1.01 * kDrawnSafety,
              minEdge * 0.89);
}

// bound::drawnVertexError; maxDistance bounds the distance of the patch from the eye.
float drawnVertexError(float maxAbs, float maxDistance) {
  vec3 e = abs(pc.eye.xyz);
  return (32.0 / 16777216.0 * (maxAbs + max(e.x, max(e.y, e.z))) +
          maxDistance * pc.snapPerDistance) * kDrawnSafety;
}

// The largest distance of the 16 points `b` from the eye.
float drawnMaxDistance(vec3 b[16]) {
  float r = 0.0;
  for (int k = 0; k < 16; ++k) r = max(r, length(pc.eye.xyz - b[k]));
  return r * kDrawnSafety;
}

// The same of the 16 points at `first`.
float drawnMaxDistance(uint first) {
  vec3 b[16];
  for (uint k = 0u; k < 16u; ++k) b[k] = controlPoint(first + k);
  return drawnMaxDistance(b);
}

// bound::normalDeviation from (G, H) and the shape.
float drawnNormalDeviation(float g, float h, vec3 shape, float vertexError) {
  float m = max(shape.z, 1e-6);
  float hh = h + 4.0 * vertexError / (m * m);
  return (0.5 * g * hh * shape.x + 0.25 * hh * hh * shape.y) * kDrawnSafety;
}

// bound::bezierDerivativeBounds of the Bezier net b: (G, H, max |coordinate|).
vec3 drawnDerivativeBounds(vec3 b[16]) {
  float maxAbs = 0.0;
  for (int k = 0; k < 16; ++k) {
    vec3 a = abs(b[k]);
    maxAbs = max(maxAbs, max(a.x, max(a.y, a.z)));
  }
  float g = 0.0, h = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      g = max(g, 3.0 * length(b[4 * j + i + 1] - b[4 * j + i]));
      g = max(g, 3.0 * length(b[4 * (i + 1) + j] - b[4 * i + j]));
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 2; ++i) {
      h = max(h, 6.0 * length(b[4 * j + i + 2] - 2.0 * b[4 * j + i + 1] + b[4 * j + i]));
      h = max(h, 6.0 * length(b[4 * (i + 2) + j] - 2.0 * b[4 * (i + 1) + j] + b[4 * i + j]));
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      h = max(h, 9.0 * length(b[4 * (j + 1) + i + 1] - b[4 * (j + 1) + i] - b[4 * j + i + 1] +
                              b[4 * j + i]));
  // fp32 differences of the points: relative to the coordinates.
  float round = 8.0 / 16777216.0 * maxAbs;
  return vec3(g * kDrawnSafety + 6.0 * round, h * kDrawnSafety + 36.0 * round, maxAbs);
}

// The same of the 16 points at `first`.
vec3 drawnDerivativeBounds(uint first) {
  vec3 b[16];
  for (uint k = 0u; k < 16u; ++k) b[k] = controlPoint(first + k);
  return drawnDerivativeBounds(b);
}
#endif
