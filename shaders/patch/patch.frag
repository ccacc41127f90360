#version 450
// Shaded color (headlight, two-sided) and the item-buffer value of the patch.
#include <shared/draw_layout.h>
#include "../common/shading.glsl"

layout(push_constant) uniform Push { DrawConstants pc; };

layout(location = 0) in vec3 tePosition;
layout(location = 1) in vec3 teNormal;
layout(location = 2) flat in uint tePatch;

layout(location = 0) out vec4 outColor;
layout(location = 1) out uint outItem;

void main() {
  vec3 base = (pc.flags & kFlagDebugColors) != 0u ? debugColor(tePatch) : vec3(0.80, 0.78, 0.72);
  outColor = vec4(shade(base, tePosition, teNormal, pc.eye.xyz), 1.0);
  outItem = pc.itemBase + tePatch + 1u;
}
