#version 450
// The levels pass: the adaptive tessellation levels of every patch of a set for one view
// (tess_levels.glsl, the per-edge rule of the control shader: each edge's level is a
// function of that edge's boundary curve alone, so neighbours agree), packed into
// tessLevels[levelBase + patch]. Every adaptive draw of an undisplaced set that sets
// kFlagTessLevelsFromBuffer reads them (patch.tesc), and the cull kernel's drawn-triangle
// test reads the same entries (cull/drawn_triangles.glsl): the unculled frame, the culled
// frame and the item-buffer oracle draw the very integers the back-patch test checked, so
// it needs no slack for fp32 differences between a kernel and a draw shader
// (docs/algorithms/drawn-triangles.md, "Exact adaptive levels"). Nießner and Loop compute
// the tessellation factors in compute as well (§5). Push constants: DrawConstants of the
// draw (frame::TessLevelsPass), levelCount patches.
#include <shared/draw_layout.h>

layout(local_size_x = 64) in;
layout(push_constant) uniform Push { DrawConstants pc; };

mat4 tessViewProjection() { return pc.viewProjection; }
vec2 tessViewportSize() { return pc.viewport.xy; }
float tessPixelsPerSegment() { return pc.eye.w; }
float tessUniformLevel() { return pc.viewport.z; }
float tessMaxLevel() { return pc.viewport.w; }
uint tessMode() { return pc.mode; }
#include "tess_levels.glsl"

#define POINTS_BINDING kBindingPoints
#include "../common/control_points.glsl"
layout(std430, set = 0, binding = kBindingParams) readonly buffer Params { uint params[]; };
layout(std430, set = 0, binding = kBindingTessLevels) writeonly buffer TessLevels {
  uvec2 tessLevels[];
};

void main() {
  uint p = gl_GlobalInvocationID.x;
  if (p >= pc.levelCount) return;
  bool bezier = p < pc.bezierCount;
  uint first = bezier ? p * 16u : pc.bezierCount * 16u + (p - pc.bezierCount) * 20u;
  vec3 curves[16];
  for (int k = 0; k < 16; ++k)
    curves[k] = controlPoint(first + uint(bezier ? kEdgeCurveBezier[k] : kEdgeCurveGregory[k]));
  vec4 lo, hi;
  curveEdgeLevels(curves, params[2u * p] >> 28u, lo, hi);
  tessLevels[pc.levelBase + p] = packTessLevels(lo, hi);
}
