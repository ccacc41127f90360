// The tightened drawn-triangle test: fp32 mirror of bound/drawn_triangle_set.h
// (docs/algorithms/drawn-triangles.md, "Enumerated triangles"). With uniform tessellation
// (or precomputed adaptive) levels are integers, so instead of bounding the worst chord triangle from the
// patch-wide derivative bounds, every triangle the tessellator can draw is evaluated from
// the control points and tested: both diagonals of each inner-grid cell, and per outer edge
// every ring triangle whose apex lies within ringApexOffset of its base. The patch is
// culled only if each one faces away with its corners moved by eps = the drawn-vertex error
// (fp32 evaluation in the draw shader, sub-pixel snapping), the tessellator's fixed-point
// coordinates (2 G bound::tessCoordError, the device's exact fixed-point rounding) and this
// kernel's own fp32 evaluation error; candidate windows are widened by 1e-4 so that the
// kernel lists every triangle the double reference lists. Needs no per-patch data: it serves
// deforming meshes. Gregory patches are evaluated as Osd_EvalBasisGregory does (the Bezier net
// frozen at (u, v), bound::gregoryDerivativeBound for G, bound::kGregoryEvalUlps for the draw
// shader's extra fp32 error). Included when CULL_DRAWN and CULL_DRAWN_ENUMERATE are 1.
#ifndef OSD_CULL_CULL_DRAWN_TRIANGLE_SET_GLSL
#define OSD_CULL_CULL_DRAWN_TRIANGLE_SET_GLSL
#include "drawn_triangles.glsl"

// The largest listed level plus one: rows of points live in memory per SIMD lane on
// lavapipe, so they are no longer than the listing needs (CULL_DRAWN_LIST_LEVEL: 2 by
// default, 64 with CullSettings::drawnEnumerate).
const int kDrawnRowPoints = CULL_DRAWN_LIST_LEVEL + 1;
vec3 gDrawnNet[16];  // the Bezier net of the patch being tested (Gregory: drawnPoint fills
                     // the interior points 5, 6, 10, 9 at each (u, v))
vec3 gDrawnFace[8];  // Gregory: Fp, Fm of corners (0,0), (1,0), (1,1), (0,1)
// The type this listed pass lists (CULL_DRAWN_LISTED_GREGORY): a constant, so that a pass
// evaluates one kind of surface (lavapipe runs both sides of a branch on the patch type).
const bool gDrawnGregory = CULL_DRAWN_LISTED_GREGORY != 0;
float gDrawnEps;  // the corner displacement the test allows

// Osd_EvalBasisGregory's interior multiplier of Fp: a / (a + b), 1 where a + b vanishes
// (only at its own corner, where the point's Bernstein weight is 0).
float drawnGregoryBlend(float a, float b) {
  float d = a + b;
  return a * (d <= 0.0 ? 1.0 : 1.0 / d);
}

vec3 drawnPoint(vec2 uv) {
  vec2 s = 1.0 - uv;
  if (gDrawnGregory) {  // the Bezier net frozen at uv (bound::gregoryBezierNet)
    vec4 g = vec4(drawnGregoryBlend(uv.x, uv.y), drawnGregoryBlend(uv.y, s.x),
                  drawnGregoryBlend(s.x, s.y), drawnGregoryBlend(s.y, uv.x));
    gDrawnNet[5] = g.x * gDrawnFace[0] + (1.0 - g.x) * gDrawnFace[1];
    gDrawnNet[6] = g.y * gDrawnFace[2] + (1.0 - g.y) * gDrawnFace[3];
    gDrawnNet[10] = g.z * gDrawnFace[4] + (1.0 - g.z) * gDrawnFace[5];
    gDrawnNet[9] = g.w * gDrawnFace[6] + (1.0 - g.w) * gDrawnFace[7];
  }
  vec4 bu =
      vec4(s.x * s.x * s.x, 3.0 * s.x * s.x * uv.x, 3.0 * s.x * uv.x * uv.x, uv.x * uv.x * uv.x);
  vec4 bv =
      vec4(s.y * s.y * s.y, 3.0 * s.y * s.y * uv.y, 3.0 * s.y * uv.y * uv.y, uv.y * uv.y * uv.y);
  vec3 p = vec3(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) p += (bu[i] * bv[j]) * gDrawnNet[4 * j + i];
  return p;
}

// Net position k of the Gregory patch with Fp (fm false) or Fm at the interior positions.
vec3 drawnGregoryNetChoice(int k, bool fm) {
  int corner = k == 5 ? 0 : k == 6 ? 1 : k == 10 ? 2 : k == 9 ? 3 : -1;
  return corner < 0 ? gDrawnNet[k] : gDrawnFace[2 * corner + (fm ? 1 : 0)];
}

// The largest distance between net positions p and q over the blends' choices.
float drawnGregoryWidest(int p, int q) {
  float w = 0.0;
  for (int c = 0; c < 4; ++c)
    w = max(
        w, length(drawnGregoryNetChoice(p, (c & 1) != 0) - drawnGregoryNetChoice(q, (c & 2) != 0)));
  return w;
}

// Loads the Gregory patch at `first` (gDrawnNet's boundary, gDrawnFace) and returns
// bound::gregoryDerivativeBound and the largest |coordinate| of its 20 points.
vec3 drawnLoadGregory(uint first) {
  const int kBoundary[16] = int[16](0, 1, 7, 5, 2, -1, -1, 6, 16, -1, -1, 12, 15, 17, 11, 10);
  const int kFace[8] = int[8](3, 4, 8, 9, 13, 14, 18, 19);
  // Each point loaded once: on lavapipe a load of a per-invocation address is a loop over
  // the SIMD lanes, and the loads dominated this test.
  vec3 p[20];
  float maxAbs = 0.0, maxDistance = 0.0;
  for (int k = 0; k < 20; ++k) {
    p[k] = controlPoint(first + uint(k));
    vec3 a = abs(p[k]);
    maxAbs = max(maxAbs, max(a.x, max(a.y, a.z)));
    maxDistance = max(maxDistance, length(pc.eye.xyz - p[k]));
  }
  for (int k = 0; k < 16; ++k)
    if (kBoundary[k] >= 0) gDrawnNet[k] = p[kBoundary[k]];
  for (int k = 0; k < 8; ++k) gDrawnFace[k] = p[kFace[k]];
  float hodograph = 0.0, rational = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i)
      hodograph = max(hodograph, max(drawnGregoryWidest(4 * j + i, 4 * j + i + 1),
                                     drawnGregoryWidest(4 * i + j, 4 * (i + 1) + j)));
  for (int c = 0; c < 4; ++c) rational += length(gDrawnFace[2 * c] - gDrawnFace[2 * c + 1]);
  // fp32 differences of the points: 8 ulps of the coordinates each, 3 + 4 4/3 of them.
  float g =
      (3.0 * hodograph + 4.0 / 3.0 * rational) * kDrawnSafety + 10.0 * 8.0 / 16777216.0 * maxAbs;
  return vec3(g, maxAbs, maxDistance * kDrawnSafety);
}

// bound::triangleFacesAway in fp32: the margin also covers rounding of the triple product.
bool drawnFacesAway(vec3 p0, vec3 p1, vec3 p2) {
  vec3 v = pc.eye.xyz - p0, a = p1 - p0, c = p2 - p0;
  float la = length(a), lc = length(c), lv = length(v), eps = gDrawnEps;
  float d = 2.0 * eps * (la + lc) + 4.0 * eps * eps;
  float margin = ((lv + eps) * d + eps * la * lc + 32.0 / 16777216.0 * lv * la * lc) * 1.01;
  return dot(v, cross(a, c)) + margin < 0.0;  // NaN: kept
}

// Both diagonals of the cell c00 c10 c11 c01 (counter-clockwise in the domain).
bool drawnCellFacesAway(vec3 c00, vec3 c10, vec3 c11, vec3 c01) {
  return drawnFacesAway(c00, c10, c11) && drawnFacesAway(c00, c11, c01) &&
         drawnFacesAway(c00, c10, c01) && drawnFacesAway(c10, c11, c01);
}

// A triangle of domain corners q (any order) with points p, tested counter-clockwise.
bool drawnRingFacesAway(vec2 q0, vec2 q1, vec2 q2, vec3 p0, vec3 p1, vec3 p2) {
  vec2 d1 = q1 - q0, d2 = q2 - q0;
  return d1.x * d2.y - d1.y * d2.x >= 0.0 ? drawnFacesAway(p0, p1, p2) : drawnFacesAway(p0, p2, p1);
}

// bound::ringApexOffset.
float drawnRingApexOffset(float n, float i) {
  float sigma = 1.0 / n, s = 1.0 / i, countDiff = abs(n - i), m = min(sigma, s);
  return min(1.1 * (countDiff * m + abs(sigma - s)), 0.8 * (max(sigma, s) + 0.5 * countDiff * m));
}

// Domain point of edge e's ring (bound::forEachDrawnTriangle's ringPoint).
vec2 drawnRingPoint(int e, float along, float depth) {
  if (e == 0) return vec2(depth, along);
  if (e == 1) return vec2(along, depth);
  if (e == 2) return vec2(1.0 - depth, along);
  return vec2(along, 1.0 - depth);
}

// Position of vertex j of an edge of lo + hi segments after the transition remap.
float drawnEdgePosition(float j, float lo, float hi) {
  if (hi == 0.0) return j / lo;
  return j <= lo ? 0.5 * j / lo : 0.5 * (j - lo) / hi + 0.5;
}

// The ring of edge e: n = lo + hi outer segments against the inner row of `along`
// segments at depth `depth`.
bool drawnRingFacesAway(int e, float lo, float hi, float along, float depth) {
  vec3 rowA[kDrawnRowPoints], rowB[kDrawnRowPoints];
  float n = lo + hi;
  float o = drawnRingApexOffset(n, along) + 1e-4;
  for (int j = 0; j <= int(n); ++j)
    rowA[j] = drawnPoint(drawnRingPoint(e, drawnEdgePosition(float(j), lo, hi), 0.0));
  for (int k = 1; k < int(along); ++k)
    rowB[k] = drawnPoint(drawnRingPoint(e, float(k) / along, depth));
  for (int j = 0; j < int(n); ++j)
    for (int k = 1; k < int(along); ++k) {
      float s = float(k) / along;
      if (s < float(j) / n - o || s > float(j + 1) / n + o) continue;
      if (!drawnRingFacesAway(drawnRingPoint(e, drawnEdgePosition(float(j), lo, hi), 0.0),
                              drawnRingPoint(e, drawnEdgePosition(float(j + 1), lo, hi), 0.0),
                              drawnRingPoint(e, s, depth), rowA[j], rowA[j + 1], rowB[k]))
        return false;
    }
  for (int k = 1; k + 1 < int(along); ++k)
    for (int j = 0; j <= int(n); ++j) {
      float t = float(j) / n;
      if (t < float(k) / along - o || t > float(k + 1) / along + o) continue;
      if (!drawnRingFacesAway(drawnRingPoint(e, float(k) / along, depth),
                              drawnRingPoint(e, float(k + 1) / along, depth),
                              drawnRingPoint(e, drawnEdgePosition(float(j), lo, hi), 0.0), rowB[k],
                              rowB[k + 1], rowA[j]))
        return false;
    }
  return true;
}

// bound::tessellatorPointError: floor(n / 2) |r_n - 1/n|, r_n = round(2^16 / n) 2^-16, from
// the exact integer |round(2^16 / n) n - 2^16| (one rounding, covered by kDrawnSafety).
float drawnTessellatorPointError(float level) {
  uint n = uint(level), r = (65536u + n / 2u) / n;
  int diff = int(r * n) - 65536;
  return float(n / 2u) * float(abs(diff)) / (65536.0 * level) * kDrawnSafety;
}

// Whether every triangle the tessellator can draw for this patch (Bezier or Gregory) faces
// away.
bool drawnTrianglesFaceAway(uint patchIndex) {
  float lo[4], hi[4], outer[4];
  bool allOnes;
  if (!drawnListedLevels(patchIndex, lo, hi, outer, allOnes)) return false;
  uint first = firstPoint(patchIndex);
  if (isBezier(patchIndex) == gDrawnGregory) return false;  // the other pass's type
  float g, maxAbs, maxDistance, evalUlps = 24.0;
  if (gDrawnGregory) {
    vec3 d = drawnLoadGregory(first);
    g = d.x;
    maxAbs = d.y;
    maxDistance = d.z;
    // bound::kGregoryEvalUlps for the draw shader, and as much again for this kernel's
    // blends (the same operations but the division, which is also one here).
    evalUlps += 2.0 * 16.0;
  } else {
    for (uint k = 0u; k < 16u; ++k) gDrawnNet[k] = controlPoint(first + k);
    vec3 d = drawnDerivativeBounds(gDrawnNet);
    g = d.x;
    maxAbs = d.z;
    maxDistance = drawnMaxDistance(gDrawnNet);
  }
  vec3 e3 = abs(pc.eye.xyz);
  float i0 = max(2.0, ceil(0.5 * (outer[1] + outer[3])));  // subdivides u
  float i1 = max(2.0, ceil(0.5 * (outer[0] + outer[2])));  // subdivides v
  float coordError = (allOnes ? 0.0
                              : max(drawnTessellatorPointError(i0),
                                    drawnTessellatorPointError(i1))) +
                     1.0 / 2097152.0;  // bound::tessCoordError
  // This kernel's own parameters (k / i, the transition remap) carry the same fp32 error.
  coordError += 1.0 / 2097152.0;
  // This kernel's own fp32 error: the 16-term Bernstein sum and the corner differences
  // (below 24 ulps of the largest coordinate; Gregory: evalUlps) and E - p0 (2 ulps of the
  // eye). The draw shader's Gregory evaluation: bound::kGregoryEvalUlps.
  gDrawnEps = drawnVertexError(maxAbs, maxDistance) +
              2.0 * g * coordError * kDrawnSafety +
              (evalUlps * maxAbs + 2.0 * max(e3.x, max(e3.y, e3.z))) / 16777216.0;
  if (!isFiniteF(gDrawnEps)) return false;
  if (allOnes)  // the corners: boundary points for Gregory patches too
    return drawnCellFacesAway(gDrawnNet[0], gDrawnNet[3], gDrawnNet[15], gDrawnNet[12]);
  for (int e = 0; e < 4; ++e) {
    bool alongV = e % 2 == 0;
    if (!drawnRingFacesAway(e, lo[e], hi[e], alongV ? i1 : i0, 1.0 / (alongV ? i0 : i1)))
      return false;
  }
  // Inner grid, row by row (rows[l & 1] holds row l).
  vec3 rows[2][kDrawnRowPoints];
  for (int l = 1; l < int(i1); ++l) {
    for (int k = 1; k < int(i0); ++k)
      rows[l & 1][k] = drawnPoint(vec2(float(k) / i0, float(l) / i1));
    if (l == 1) continue;
    for (int k = 1; k + 1 < int(i0); ++k)
      if (!drawnCellFacesAway(rows[(l - 1) & 1][k], rows[(l - 1) & 1][k + 1], rows[l & 1][k + 1],
                              rows[l & 1][k]))
        return false;
  }
  return true;
}
#endif
