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

// Debug-view colors of kDrawStatus* (index = status).
const vec3 kStatusColors[6] = vec3[6](vec3(0.80, 0.78, 0.72), vec3(0.35, 0.75, 0.35),
                                      vec3(0.95, 0.85, 0.25), vec3(0.35, 0.55, 0.95),
                                      vec3(0.70, 0.40, 0.90), vec3(0.95, 0.35, 0.30));

void main() {
  uint patchIndex = tePatch & kDrawListPatchMask;
  vec3 base = vec3(0.80, 0.78, 0.72);
  if ((pc.flags & kFlagDebugColors) != 0u) base = debugColor(patchIndex);
  if ((pc.flags & kFlagStatusColors) != 0u)
    base = kStatusColors[min((tePatch >> kDrawListStatusShift) & 7u, 5u)];
  outColor = vec4(shade(base, tePosition, teNormal, pc.eye.xyz), 1.0);
  outItem = pc.itemBase + patchIndex + 1u;
}
