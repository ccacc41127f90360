#version 450
// Indexed triangle occluders: positions from a storage buffer (pointStride floats each).
#include <shared/draw_layout.h>

layout(push_constant) uniform Push { DrawConstants pc; };
layout(std430, set = 0, binding = 0) readonly buffer Points { float points[]; };

layout(location = 0) out vec3 vPosition;

void main() {
  uint base = pc.pointOffset + uint(gl_VertexIndex) * pc.pointStride;
  vPosition = vec3(points[base], points[base + 1u], points[base + 2u]);
  gl_Position = pc.viewProjection * vec4(vPosition, 1.0);
}
