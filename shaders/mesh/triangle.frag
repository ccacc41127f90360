#version 450
// Flat-shaded occluder; writes pc.itemBase (kItemOccluder) into the item buffer.
#include <shared/draw_layout.h>
#include "../common/shading.glsl"

layout(push_constant) uniform Push { DrawConstants pc; };

layout(location = 0) in vec3 vPosition;

layout(location = 0) out vec4 outColor;
// ITEM_BUFFER 0: a target without an item buffer (the application's color and depth).
#ifndef ITEM_BUFFER
#define ITEM_BUFFER 1
#endif
#if ITEM_BUFFER
layout(location = 1) out uint outItem;
#endif

void main() {
  vec3 n = cross(dFdx(vPosition), dFdy(vPosition));
  outColor = vec4(shade(vec3(0.55, 0.6, 0.7), vPosition, n, pc.eye.xyz), 1.0);
#if ITEM_BUFFER
  outItem = pc.itemBase;
#endif
}
