#version 450
// Evaluates a Bezier (16-point) or Gregory-basis (20-point) patch with OpenSubdiv's own
// basis functions (Osd_EvalBasisBezier / Osd_EvalBasisGregory), giving position and
// normal. Points on a shared edge are evaluated from that edge's boundary curve alone,
// in a direction both neighbours agree on, so neighbours produce bit-identical vertices.
#include "patch_common.glsl"
#include "edge_curves.glsl"
#include "osd/patch_basis.glsl"
#if defined(PATCH_DISPLACED)
#include "displace.glsl"
#endif

layout(quads, equal_spacing, ccw) in;

layout(location = 0) in vec3 tcPoint[];
layout(location = 1) patch in uint tcPatch;
layout(location = 2) patch in vec4 tcLo;
layout(location = 3) patch in vec4 tcHi;
layout(location = 4) patch in float tcNearestDepth;  // patch.tesc

layout(location = 0) out vec3 tePosition;
layout(location = 1) out vec3 teNormal;
layout(location = 2) flat out uint tePatch;
layout(location = 3) flat out float teNearestDepth;

// Equal-spacing form of OpenSubdiv's OsdGetTessTransitionSplit: the first `lo` segments
// of a transition edge cover [0, 1/2], the last `hi` cover [1/2, 1].
float transitionSplit(float t, float lo, float hi) {
  float ti = round(t * (lo + hi));
  return ti <= lo ? (ti / lo) * 0.5 : ((ti - lo) / hi) * 0.5 + 0.5;
}

vec3 bezierCurve(vec3 b0, vec3 b1, vec3 b2, vec3 b3, float t) {
  float s = 1.0 - t;
  return (s * s * s) * b0 + (3.0 * s * s * t) * b1 + (3.0 * s * t * t) * b2 + (t * t * t) * b3;
}

// Vertex i of `level` segments on edge e, evaluated in the agreed direction.
vec3 edgePoint(int e, float t, float level) {
  vec3 b0 = tcPoint[kEdgeCurve[4 * e + 0]];
  vec3 b1 = tcPoint[kEdgeCurve[4 * e + 1]];
  vec3 b2 = tcPoint[kEdgeCurve[4 * e + 2]];
  vec3 b3 = tcPoint[kEdgeCurve[4 * e + 3]];
  float i = round(t * level);
  bool reversed = (b0 == b3) ? lexLess(b2, b1) : lexLess(b3, b0);
  return reversed ? bezierCurve(b3, b2, b1, b0, (level - i) / level)
                  : bezierCurve(b0, b1, b2, b3, i / level);
}

void evalPatch(vec2 uv, out vec3 P, out vec3 dPu, out vec3 dPv) {
  float wP[PATCH_POINTS], wDs[PATCH_POINTS], wDt[PATCH_POINTS];
  float wDss[PATCH_POINTS], wDst[PATCH_POINTS], wDtt[PATCH_POINTS];
#if PATCH_POINTS == 16
  Osd_EvalBasisBezier(uv.x, uv.y, wP, wDs, wDt, wDss, wDst, wDtt);
#else
  Osd_EvalBasisGregory(uv.x, uv.y, wP, wDs, wDt, wDss, wDst, wDtt);
#endif
  P = vec3(0.0);
  dPu = vec3(0.0);
  dPv = vec3(0.0);
  for (int i = 0; i < PATCH_POINTS; ++i) {
    P += wP[i] * tcPoint[i];
    dPu += wDs[i] * tcPoint[i];
    dPv += wDt[i] * tcPoint[i];
  }
}

void main() {
  vec2 p = gl_TessCoord.xy;
  // OsdGetTessParameterization: remap the parameter along transition edges.
  vec2 uv = p;
  if (p.x == 0.0 && tcHi[0] > 0.0) uv.y = transitionSplit(p.y, tcLo[0], tcHi[0]);
  else if (p.y == 0.0 && tcHi[1] > 0.0) uv.x = transitionSplit(p.x, tcLo[1], tcHi[1]);
  else if (p.x == 1.0 && tcHi[2] > 0.0) uv.y = transitionSplit(p.y, tcLo[2], tcHi[2]);
  else if (p.y == 1.0 && tcHi[3] > 0.0) uv.x = transitionSplit(p.x, tcLo[3], tcHi[3]);

  vec3 P, dPu, dPv;
  evalPatch(uv, P, dPu, dPv);
  vec3 n = cross(dPu, dPv);
  if (!(dot(n, n) > 1e-24 * max(dot(dPu, dPu) * dot(dPv, dPv), 1e-30))) {
    // Collapsed edge or corner (e.g. the teapot lid): take the normal slightly inside.
    vec3 Q, qu, qv;
    evalPatch(clamp(uv, vec2(1e-3), vec2(1.0 - 1e-3)), Q, qu, qv);
    n = cross(qu, qv);
  }

  // Shared edges: exact boundary-curve vertices (not on transition edges, whose halves
  // meet finer patches and cannot be bit-identical anyway).
  if (p.x == 0.0 && tcHi[0] == 0.0) P = edgePoint(0, p.y, tcLo[0]);
  else if (p.y == 0.0 && tcHi[1] == 0.0) P = edgePoint(1, p.x, tcLo[1]);
  else if (p.x == 1.0 && tcHi[2] == 0.0) P = edgePoint(2, p.y, tcLo[2]);
  else if (p.y == 1.0 && tcHi[3] == 0.0) P = edgePoint(3, p.x, tcLo[3]);

#if defined(PATCH_DISPLACED)
  n = displace(tcPatch & kDrawListPatchMask, uv, P, n, dPu, dPv);
#endif
  tePosition = P;
  teNormal = n;
  tePatch = tcPatch;
  teNearestDepth = tcNearestDepth;
  if ((pc.flags & kFlagPatchTypeColors) != 0u) {
    // The status field carries the patch type to the fragment stage: 0 regular, 1 one
    // boundary edge, 2 corner, 3 Gregory (OsdGetPatchBoundaryMask: bits 7..10 of field 1).
    uint patchIndex = tcPatch & kDrawListPatchMask;
    uint boundary = bitCount((params[2u * patchIndex + 1u] >> 7u) & 0xFu);
    uint type = PATCH_POINTS == 20 ? 3u : min(uint(boundary), 2u);
    tePatch = patchIndex | (type << kDrawListStatusShift);
  }
  gl_Position = pc.viewProjection * vec4(P, 1.0);
}
