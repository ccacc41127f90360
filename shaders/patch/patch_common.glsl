// Resources shared by the patch draw stages. PATCH_POINTS is 16 (Bezier) or 20 (Gregory).
#ifndef OSD_CULL_PATCH_COMMON_GLSL
#define OSD_CULL_PATCH_COMMON_GLSL
#include <shared/draw_layout.h>

#if !defined(PATCH_POINTS)
#error "define PATCH_POINTS (16: Bezier, 20: Gregory)"
#endif

layout(push_constant) uniform Push { DrawConstants pc; };

// Parameters of tess_levels.glsl.
mat4 tessViewProjection() { return pc.viewProjection; }
vec2 tessViewportSize() { return pc.viewport.xy; }
float tessPixelsPerSegment() { return pc.eye.w; }
float tessUniformLevel() { return pc.viewport.z; }
float tessMaxLevel() { return pc.viewport.w; }
uint tessMode() { return pc.mode; }

#define POINTS_BINDING 0
#include "../common/control_points.glsl"
layout(std430, set = 0, binding = 1) readonly buffer Params { uint params[]; };
layout(std430, set = 0, binding = 2) readonly buffer DrawList { uint drawList[]; };
layout(std430, set = 0, binding = kBindingTessLevels) readonly buffer TessLevels {
  uvec2 tessLevels[];
};

// Index of the first control point of a patch (PatchSet layout: Bezier first, then Gregory).
uint firstPoint(uint patchIndex) {
  return patchIndex < pc.bezierCount
             ? patchIndex * 16u
             : pc.bezierCount * 16u + (patchIndex - pc.bezierCount) * 20u;
}

// Far::PatchParam transition mask: bit k set when edge k (0: v=0, 1: u=1, 2: v=1, 3: u=0)
// borders two patches of the next refinement level.
uint transitionMask(uint patchIndex) { return params[2u * patchIndex] >> 28u; }
#endif
