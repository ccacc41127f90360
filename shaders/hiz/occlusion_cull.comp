#version 450
// Hi-Z occlusion test of every patch against a pyramid (Niessner & Loop §4.1.1), one
// invocation per patch, writing a result code per patch (shared/hiz_layout.h).
// The stand-alone form of the occlusion stage; the frame's cull kernel runs the same
// functions (occlusion.glsl) after its frustum and back-patch tests.
#include <shared/hiz_layout.h>
#include <shared/visibility_layout.h>
#include "occlusion.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform Push { OcclusionCullConstants pc; };
layout(std430, set = 0, binding = 0) readonly buffer Points { float points[]; };
layout(set = 0, binding = 1) uniform sampler2D pyramid;
layout(std430, set = 0, binding = 2) writeonly buffer Results { uint results[]; };

void main() {
  uint patchIndex = gl_GlobalInvocationID.x;
  if (patchIndex >= pc.patchCount) return;
  bool bezier = patchIndex < pc.bezierCount;
  uint first = bezier ? patchIndex * 16u : pc.bezierCount * 16u + (patchIndex - pc.bezierCount) * 20u;
  uint count = bezier ? 16u : 20u;
  mat4 absViewProj = mat4(abs(pc.viewProjection[0]), abs(pc.viewProjection[1]),
                          abs(pc.viewProjection[2]), abs(pc.viewProjection[3]));
  HiZBox box = hizBoxBegin();
  for (uint i = 0u; i < count; ++i) {
    uint base = pc.pointOffset + (first + i) * pc.pointStride;
    vec3 p = vec3(points[base], points[base + 1u], points[base + 2u]);
    hizBoxAdd(box, pc.viewProjection * vec4(p, 1.0), absViewProj * vec4(abs(p), 1.0));
  }
  int level;
  ivec2 t0, t1;
  uint result = kOcclusionVerdictUntested << kOcclusionVerdictShift;
  if (hizFootprint(box, pc.hiz, level, t0, t1)) {
    bool occluded = hizOccluded(box, pc.hiz, pyramid);
    result = (occluded ? kResultOcclusion : kResultSurvived) |
             ((occluded ? kOcclusionVerdictOccluded : kOcclusionVerdictVisible)
              << kOcclusionVerdictShift) |
             (uint(level) << kOcclusionLevelShift);
  }
  results[patchIndex] = result;
}
