// Scalar displacement along the normal, P + N * scale * (D(s, t) - midlevel), for the
// displaced variant of the patch evaluation stage (PATCH_DISPLACED; patch.tese). Only that
// variant includes this file: undisplaced patches run no displacement code.
// Texture coordinates are bilinear over the patch (osd_cull/patch/face_varying_uv.h); the
// map is sampled at the fixed level of detail the bounds assume (bound/displaced_map.h).
#ifndef OSD_CULL_PATCH_DISPLACE_GLSL
#define OSD_CULL_PATCH_DISPLACE_GLSL
#include <shared/displacement_layout.h>

layout(set = kDisplaceSet, binding = kDisplaceBindingMap) uniform sampler2D displacementMap;
layout(std430, set = kDisplaceSet, binding = kDisplaceBindingUVs) readonly buffer PatchUVs {
  vec4 patchUVs[];
};
layout(std430, set = kDisplaceSet, binding = kDisplaceBindingParams) readonly buffer
    DisplacementParamsBuffer {
  DisplacementParams displacement;
};

// Texture coordinates at (u, v) of a patch and their derivatives along u and v.
vec2 patchTexCoord(uint patchIndex, vec2 uv, out vec2 dU, out vec2 dV) {
  vec4 c01 = patchUVs[2u * patchIndex];
  vec4 c23 = patchUVs[2u * patchIndex + 1u];
  vec2 c0 = c01.xy, c1 = c01.zw, c2 = c23.xy, c3 = c23.zw;
  vec2 bottom = mix(c0, c1, uv.x), top = mix(c3, c2, uv.x);
  dU = mix(c1 - c0, c2 - c3, uv.y);
  dV = top - bottom;
  return mix(bottom, top, uv.y);
}

float displacementAt(vec2 st) {
  float v = textureLod(displacementMap, st, displacement.map.z).r;
  return displacement.map.x * (v - displacement.map.y);
}

// Displaces P along the unit normal of n and returns the normal of the displaced surface,
// approximated as cross(dPu + N dD/du, dPv + N dD/dv) (the curvature term dN/du D is
// left out: shading only; the bounds use the true surface).
vec3 displace(uint patchIndex, vec2 uv, inout vec3 P, vec3 n, vec3 dPu, vec3 dPv) {
  vec2 dU, dV;
  vec2 st = patchTexCoord(patchIndex, uv, dU, dV);
  float len = length(n);
  vec3 N = len > 0.0 ? n / len : vec3(0.0);
  P += N * displacementAt(st);
  // Central differences of D over one texel in s and t, chained with ds/du, dt/du.
  vec2 texel = vec2(displacement.map.w, displacement.size.x);
  float ds = (displacementAt(st + vec2(texel.x, 0.0)) - displacementAt(st - vec2(texel.x, 0.0))) /
             (2.0 * texel.x);
  float dt = (displacementAt(st + vec2(0.0, texel.y)) - displacementAt(st - vec2(0.0, texel.y))) /
             (2.0 * texel.y);
  vec3 tu = dPu + N * (ds * dU.x + dt * dU.y);
  vec3 tv = dPv + N * (ds * dV.x + dt * dV.y);
  vec3 m = cross(tu, tv);
  return dot(m, m) > 0.0 ? m : n;
}
#endif
