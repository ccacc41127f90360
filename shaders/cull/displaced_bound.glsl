// Displaced-patch bounds of the cull kernel (CULL_DISPLACED): fp32 mirror of
// bound::displacedBound (osd_cull/bound/displaced_bounds.h; Niessner & Loop §4.2, Fig. 5;
// Sathe, run-time step). The frustum test and the occlusion stage read the bound through
// boundPointCount() / boundPoint() / boundClipPoint() / boundAbsClipPoint(): 8 corners of
// the OOBB (world space, DISPLACED_BOX 0) or of the camera-aligned frustum (camera space,
// DISPLACED_BOX 1), computed once per patch by prepareBound().
// Per patch (cones[], shared/cull_layout.h kConeVec4s, filled by the host for a static
// displaced mesh, by the bounds pass, shaders/bounds/, for a deforming one): cones[4p] = (Dmin, Dmax rounded outward, cos α, sin α), cones[4p + 1] =
// (axis.xyz, 1 with a cone, 0 without: Full, or a cone that could not be built).
#ifndef OSD_CULL_CULL_DISPLACED_BOUND_GLSL
#define OSD_CULL_CULL_DISPLACED_BOUND_GLSL
#include "cull_common.glsl"

layout(std430, set = 0, binding = kCullBindingDisplacedView) readonly buffer DisplacedViewBuffer {
  DisplacedView dviews[];  // one per instance (shared/cull_layout.h CullInstance)
};
DisplacedView dview;  // the invocation's instance, set by cull_main.glsl

// fp32 slack of every δ (products of rounded unit vectors and cos/sin of α: < 1e-6).
const float kDeltaSlack = 1e-5;

vec3 gBoundCorners[8];
bool gBoundFinite;

// max of N·r̂ over the cone, r̂ unit (§4.2 δ+).
float coneReach(vec4 cone, vec4 axis, vec3 r) {
  if (axis.w == 0.0) return 1.0;
  float c = dot(axis.xyz, r);
  float s = length(cross(axis.xyz, r));
  if (c >= cone.z - kDeltaSlack) return 1.0;
  return min(1.0, c * cone.z + s * cone.w + kDeltaSlack);
}

// Extensions (plus, minus) of N·D along direction r (any length).
vec2 axisExtension(vec4 cone, vec4 axis, vec3 r) {
  float len = length(r);
  if (!(len > 0.0)) return vec2(0.0);
  vec3 u = r / len;
  float up = coneReach(cone, axis, u), down = coneReach(cone, axis, -u);
  float dmax = cone.y, negMin = -cone.x;
  return vec2(max(max(dmax * up, negMin * down), 0.0), max(max(dmax * down, negMin * up), 0.0)) *
         len * (1.0 + kCullRelativeMargin);
}

float maxAbs3(vec3 v) { return max(max(abs(v.x), abs(v.y)), abs(v.z)); }

void setBoxCorners(vec3 lo, vec3 hi) {
  for (int i = 0; i < 8; ++i)
    gBoundCorners[i] =
        vec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z);
}

void prepareBound(uint patchIndex) {
  vec4 cone = cones[kConeVec4s * patchIndex];
  vec4 axis = cones[kConeVec4s * patchIndex + 1u];
  uint first = firstPoint(patchIndex), n = pointCount(patchIndex);
  gBoundFinite = isFiniteF(cone) && isFiniteF(axis);
#if DISPLACED_BOX == 0
  // OOBB: the world box of the points, extended along the world axes.
  vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
  for (uint k = 0u; k < n; ++k) {
    vec3 p = controlPoint(first + k);
    gBoundFinite = gBoundFinite && isFiniteF(p);
    lo = min(lo, p);
    hi = max(hi, p);
  }
  vec2 ex = axisExtension(cone, axis, vec3(1, 0, 0));
  vec2 ey = axisExtension(cone, axis, vec3(0, 1, 0));
  vec2 ez = axisExtension(cone, axis, vec3(0, 0, 1));
  vec3 plus = vec3(ex.x, ey.x, ez.x), minus = vec3(ex.y, ey.y, ez.y);
  float margin =
      kCullRelativeMargin * (max(maxAbs3(lo), maxAbs3(hi)) + maxAbs3(plus) + maxAbs3(minus));
  setBoxCorners(lo - minus - margin, hi + plus + margin);
#else
  // CAF: per-point boxes along the camera axes (rows of the view's linear part).
  mat4 v = dview.view;
  vec2 ex = axisExtension(cone, axis, vec3(v[0][0], v[1][0], v[2][0]));
  vec2 ey = axisExtension(cone, axis, vec3(v[0][1], v[1][1], v[2][1]));
  vec2 ez = axisExtension(cone, axis, vec3(v[0][2], v[1][2], v[2][2]));
  vec3 plus = vec3(ex.x, ey.x, ez.x), minus = vec3(ex.y, ey.y, ez.y);
  float scale = maxAbs3(plus) + maxAbs3(minus);
  vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
  for (uint k = 0u; k < n; ++k) {
    vec3 p = controlPoint(first + k);
    vec3 c = (v * vec4(p, 1.0)).xyz;
    vec3 m = (mat4(abs(v[0]), abs(v[1]), abs(v[2]), abs(v[3])) * vec4(abs(p), 1.0)).xyz;
    gBoundFinite = gBoundFinite && isFiniteF(p) && isFiniteF(c);
    scale = max(scale, maxAbs3(m) + maxAbs3(plus) + maxAbs3(minus));
    lo = min(lo, c - minus);
    hi = max(hi, c + plus);
  }
  float margin = 4.0 * kCullRelativeMargin * scale;
  lo -= margin;
  hi += margin;
  setBoxCorners(lo, hi);
  float nearDepth = -hi.z, farDepth = -lo.z;
  if (!gBoundFinite || dview.perspective == 0u || !(nearDepth > margin)) return;
  vec2 slopeLo = vec2(3.0e38), slopeHi = vec2(-3.0e38);
  for (uint k = 0u; k < n; ++k) {
    vec3 c = (v * vec4(controlPoint(first + k), 1.0)).xyz;
    vec3 l = c - minus - margin, h = c + plus + margin;
    float d0 = -h.z, d1 = -l.z;
    for (int a = 0; a < 2; ++a) {
      slopeHi[a] = max(slopeHi[a], h[a] >= 0.0 ? h[a] / d0 : h[a] / d1);
      slopeLo[a] = min(slopeLo[a], l[a] <= 0.0 ? l[a] / d0 : l[a] / d1);
    }
  }
  slopeLo -= kCullRelativeMargin * (abs(slopeLo) + vec2(1.0));
  slopeHi += kCullRelativeMargin * (abs(slopeHi) + vec2(1.0));
  for (int i = 0; i < 8; ++i) {
    float d = (i & 4) != 0 ? farDepth : nearDepth;
    gBoundCorners[i] = vec3(((i & 1) != 0 ? slopeHi.x : slopeLo.x) * d,
                            ((i & 2) != 0 ? slopeHi.y : slopeLo.y) * d, -d);
  }
#endif
}

uint boundPointCount(uint patchIndex) { return 8u; }
vec3 boundPoint(uint patchIndex, uint k) { return gBoundCorners[k]; }
#if DISPLACED_BOX == 0
vec4 boundClipPoint(vec3 p) { return clipPoint(p); }
vec4 boundAbsClipPoint(vec3 p) { return absClipPoint(p); }
#else
vec4 boundClipPoint(vec3 p) { return dview.projection * vec4(p, 1.0); }
vec4 boundAbsClipPoint(vec3 p) {
  mat4 a = mat4(abs(dview.projection[0]), abs(dview.projection[1]), abs(dview.projection[2]),
                abs(dview.projection[3]));
  return a * vec4(abs(p), 1.0);
}
#endif
#endif
