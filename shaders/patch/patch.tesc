#version 450
// Passes the control points through and sets the tessellation levels (tess_levels.glsl).
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
  if (gl_InvocationID == 0) {
    vec3 cp[PATCH_POINTS];
    for (int i = 0; i < PATCH_POINTS; ++i) cp[i] = vPoint[i];
    uint patchIndex = vPatch[0];
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
    tcPatch = patchIndex;
    tcLo = lo;
    tcHi = hi;
  }
}
