#version 450
// Shaded color (headlight, two-sided) and the item-buffer value of the patch.
#include <shared/draw_layout.h>
#include "../common/shading.glsl"

layout(push_constant) uniform Push { DrawConstants pc; };

layout(location = 0) in vec3 tePosition;
layout(location = 1) in vec3 teNormal;
layout(location = 2) flat in uint tePatch;
// Smallest depth of the patch's control points, 0 for none (patch.tesc says why).
layout(location = 3) flat in float teNearestDepth;

layout(location = 0) out vec4 outColor;
// ITEM_BUFFER 0: a target without an item buffer (the application's color and depth).
#ifndef ITEM_BUFFER
#define ITEM_BUFFER 1
#endif
#if ITEM_BUFFER
layout(location = 1) out uint outItem;
#endif
// Front faces win depth ties (kFlagFrontWinsTies, on by default): a back-facing fragment is pushed back by one pixel's worth of
// its depth slope (as depthBiasSlopeFactor 1 would) plus 2^-22 of its depth. On a closed
// surface seen from outside a ray meets a front face first, but where a front and a back
// face meet at a silhouette edge their depths at a pixel are equal up to vertex snapping and
// interpolation, which on grazing triangles is many depth ulps; without this the back face
// could win such pixels in the item buffer, and a back-patch-culled patch had pixels
// (catmark_cubes_infsharp). depth_greater keeps early depth rejection valid.
layout(depth_greater) out float gl_FragDepth;

// Debug-view colors of kDrawStatus* (index = status).
const vec3 kStatusColors[6] = vec3[6](vec3(0.80, 0.78, 0.72), vec3(0.35, 0.75, 0.35),
                                      vec3(0.95, 0.85, 0.25), vec3(0.35, 0.55, 0.95),
                                      vec3(0.70, 0.40, 0.90), vec3(0.95, 0.35, 0.30));

// Patch-type colors (kFlagPatchTypeColors): regular, boundary, corner, Gregory.
const vec3 kTypeColors[4] = vec3[4](vec3(0.80, 0.78, 0.72), vec3(0.40, 0.65, 0.95),
                                    vec3(0.95, 0.60, 0.25), vec3(0.85, 0.35, 0.65));

void main() {
  uint patchIndex = tePatch & kDrawListPatchMask;
  vec3 base = vec3(0.80, 0.78, 0.72);
  if ((pc.flags & kFlagDebugColors) != 0u) base = debugColor(patchIndex);
  if ((pc.flags & kFlagStatusColors) != 0u)
    base = kStatusColors[min((tePatch >> kDrawListStatusShift) & 7u, 5u)];
  if ((pc.flags & kFlagPatchTypeColors) != 0u)
    base = kTypeColors[(tePatch >> kDrawListStatusShift) & 3u];
  outColor = vec4(shade(base, tePosition, teNormal, pc.eye.xyz), 1.0);
#if ITEM_BUFFER
  outItem = pc.itemBase + patchIndex + 1u;
#endif
  float z = gl_FragCoord.z;
  float slope = max(abs(dFdx(z)), abs(dFdy(z)));
  // Never in front of the patch's control points (Niessner & Loop §4.1.1's bound made
  // exact for the rasterizer; proof in patch.tesc). Both only move depth back, so
  // depth_greater holds (clipping keeps z <= 1); depths stay at most 1, the far value no
  // stored depth exceeds, so a fragment clamped to 1 still fails LESS where it was culled.
  float clamped = min(max(z, teNearestDepth), 1.0);
  bool pushBack = !gl_FrontFacing && (pc.flags & kFlagFrontWinsTies) != 0u;
  gl_FragDepth =
      pushBack ? min(1.0, clamped + slope + clamped * (1.0 / 4194304.0) + 1.0e-30) : clamped;
}
