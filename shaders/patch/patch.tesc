#version 450
// Passes the control points through and sets the tessellation levels (tess_levels.glsl).
// A draw-list entry flagged kDrawListCulled gets levels 0: the patch is discarded before
// evaluation and its levels are never computed (Niessner & Loop §5).
#include "patch_common.glsl"
#include "tess_levels.glsl"

layout(vertices = PATCH_POINTS) out;

layout(location = 0) in vec3 vPoint[];
layout(location = 1) flat in uint vPatch[];

layout(location = 0) out vec3 tcPoint[];
layout(location = 1) patch out uint tcPatch;
layout(location = 2) patch out vec4 tcLo;
layout(location = 3) patch out vec4 tcHi;

void main() {
  tcPoint[gl_InvocationID] = vPoint[gl_InvocationID];
  if (gl_InvocationID == 0 && (vPatch[0] & kDrawListCulled) != 0u) {
    gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelOuter[3] = 0.0;
    gl_TessLevelInner[0] = gl_TessLevelInner[1] = 0.0;
    tcPatch = vPatch[0];
    tcLo = tcHi = vec4(0.0);
  } else if (gl_InvocationID == 0) {
    vec3 cp[PATCH_POINTS];
    for (int i = 0; i < PATCH_POINTS; ++i) cp[i] = vPoint[i];
    uint patchIndex = vPatch[0] & kDrawListPatchMask;
    vec4 lo, hi;
    edgeLevels(cp, transitionMask(patchIndex), lo, hi);
    vec4 outer = lo + hi;
    gl_TessLevelOuter[0] = outer[0];
    gl_TessLevelOuter[1] = outer[1];
    gl_TessLevelOuter[2] = outer[2];
    gl_TessLevelOuter[3] = outer[3];
    // As OsdComputeTessLevels: inner levels average the opposite outer levels.
    gl_TessLevelInner[0] = (outer[1] + outer[3]) * 0.5;
    gl_TessLevelInner[1] = (outer[0] + outer[2]) * 0.5;
    tcPatch = vPatch[0];
    tcLo = lo;
    tcHi = hi;
  }
}
