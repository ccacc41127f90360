// Resources and helpers shared by every stage of the cull kernel (cull_main.glsl).
// Mirrors osd_cull/bound/clip_space.h in fp32; see docs/algorithms/cull-kernel.md.
#ifndef OSD_CULL_CULL_COMMON_GLSL
#define OSD_CULL_CULL_COMMON_GLSL
#include <shared/cull_layout.h>

// The view-wide constants; the instance's (view · model, eye, snap) replace the push
// constants' in `pc` at the start of main (loadInstance), so every stage reads its own
// instance through pc.
layout(push_constant) uniform Push { CullConstants pcView; };
layout(std430, set = 0, binding = kCullBindingInstances) readonly buffer Instances {
  uvec4 instanceHeader;  // x: instances in the dispatch
  CullInstance instances[];
};
CullConstants pc;
uint gLevelBase;     // its first entry in tessLevels[]

// Copies the view's constants and the values of instance `i` into pc.
void loadInstance(uint i) {
  pc = pcView;
  pc.viewProjection = instances[i].viewProjection;
  pc.eye = instances[i].eye;
  pc.snapPerDistance = instances[i].snapPerDistance;
  gLevelBase = instances[i].levelSlot * pcView.patchCount;
}

#define POINTS_BINDING kCullBindingPoints  // read by common/control_points.glsl
layout(std430, set = 0, binding = kCullBindingCones) readonly buffer Cones { vec4 cones[]; };
#if CULL_DRAWN_LISTED  // the listed-triangle pass reads the codes the cull kernel wrote
layout(std430, set = 0, binding = kCullBindingResults) buffer Results { uint results[]; };
#else
layout(std430, set = 0, binding = kCullBindingResults) writeonly buffer Results { uint results[]; };
#endif
layout(std430, set = 0, binding = kCullBindingDrawList) writeonly buffer DrawList {
  uint drawList[];
};
layout(std430, set = 0, binding = kCullBindingCounters) buffer Counters { uint counters[]; };
layout(std430, set = 0, binding = kCullBindingTable) readonly buffer Table { uvec2 table[]; };
layout(std430, set = 0, binding = kCullBindingBoxes) readonly buffer Boxes { float boxes[]; };

#if CULL_PATCH_BOXES
// The precomputed box of a patch's control points (CullSettings::staticPoints): its centre
// and half extent, in fp32 (their rounding is far below kCullRelativeMargin of the
// magnitudes the tests compare with). Six loads instead of the 48 of 16 control points:
// on lavapipe every load of a per-invocation address is a loop over the SIMD lanes, and the
// loads dominated the frustum kernel (docs/results/cull-kernel-floor.md).
void patchBox(uint patchIndex, out vec3 centre, out vec3 halfExtent) {
  const uint n = pcView.patchCount;
  vec3 lo = vec3(boxes[patchIndex], boxes[n + patchIndex], boxes[2u * n + patchIndex]);
  vec3 hi = vec3(boxes[3u * n + patchIndex], boxes[4u * n + patchIndex],
                 boxes[5u * n + patchIndex]);
  centre = 0.5 * (lo + hi);
  halfExtent = 0.5 * (hi - lo);
}
#endif

#include "../common/patch_points.glsl"

// c = viewProj * (p, 1) and m = |viewProj| * (|p|, 1): m bounds every product summed in c
// (bound::clipPoint, bound::absClipPoint).
vec4 clipPoint(vec3 p) { return pc.viewProjection * vec4(p, 1.0); }
vec4 absClipPoint(vec3 p) {
  mat4 a = mat4(abs(pc.viewProjection[0]), abs(pc.viewProjection[1]), abs(pc.viewProjection[2]),
                abs(pc.viewProjection[3]));
  return a * vec4(abs(p), 1.0);
}

bool matrixIsFinite() {
  return isFiniteF(pc.viewProjection[0]) && isFiniteF(pc.viewProjection[1]) &&
         isFiniteF(pc.viewProjection[2]) && isFiniteF(pc.viewProjection[3]);
}

// Result-code fields (shared/cull_layout.h).
uint resultStage(uint r) { return r & 0xFu; }
uint withStage(uint r, uint stage) { return (r & ~0xFu) | stage; }
uint withField(uint r, uint shift, uint width, uint value) {
  uint mask = ((1u << width) - 1u) << shift;
  return (r & ~mask) | ((value << shift) & mask);
}
#endif
