#version 450
// Indirect draw commands over one compact draw list (visibility_update.comp): per patch
// type, runs of at most chunk* slots (the batch limits of osd_cull/frame/draw_chunks.h, a
// lavapipe tessellation bug), and the number of commands per type. Bezier commands fill
// commands[0, maxBezier), Gregory commands follow.
#include <shared/visibility_layout.h>

layout(local_size_x = 64) in;

layout(push_constant) uniform Push { VisibilityConstants pc; };
layout(std430, set = 0, binding = kDrawsBindingCounters) buffer Counters { uint counters[]; };
layout(std430, set = 0, binding = kDrawsBindingCommands) writeonly buffer Commands {
  uvec4 commands[];  // vertexCount, instanceCount, firstVertex, firstInstance
};

uint ceilDiv(uint a, uint b) { return (a + b - 1u) / b; }

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint gregoryCount = pc.patchCount - pc.bezierCount;
  uint maxBezier = ceilDiv(pc.bezierCount, pc.chunkBezier);
  uint maxGregory = ceilDiv(gregoryCount, pc.chunkGregory);
  uint bezier = counters[kListSurvivorsBezier];
  uint gregory = counters[kListSurvivorsGregory];
  if (i == 0u) {
    counters[kListDrawsBezier] = ceilDiv(bezier, pc.chunkBezier);
    counters[kListDrawsGregory] = ceilDiv(gregory, pc.chunkGregory);
  }
  if (i < maxBezier) {
    uint first = i * pc.chunkBezier;
    uint n = bezier > first ? min(pc.chunkBezier, bezier - first) : 0u;
    commands[i] = uvec4(n * 16u, 1u, first * 16u, 0u);
  } else if (i < maxBezier + maxGregory) {
    uint first = (i - maxBezier) * pc.chunkGregory;
    uint n = gregory > first ? min(pc.chunkGregory, gregory - first) : 0u;
    commands[i] = uvec4(n * 20u, 1u, (pc.bezierCount + first) * 20u, 0u);
  }
}
