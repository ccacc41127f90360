#version 450
// Indirect draw commands over the survivors the cull kernel appended (cull_main.glsl):
// per patch type, runs of at most drawChunk* slots (the batch limits of
// osd_cull/frame/draw_chunks.h, a lavapipe tessellation bug), and the number of commands.
// Bezier commands fill commands[0, maxBezier), Gregory commands follow. Workgroup row y
// serves instance y (its counters and commands at the offsets of shared/cull_layout.h
// CullInstance; firstVertex is relative to the instance's draw list).
#include <shared/cull_layout.h>

layout(local_size_x = kDrawsGroupSize) in;

layout(push_constant) uniform Push { CullConstants pc; };
layout(std430, set = 0, binding = kCullBindingCounters) buffer Counters { uint counters[]; };
layout(std430, set = 0, binding = kCullBindingCommands) writeonly buffer Commands {
  uvec4
      commands[];  // VkDrawIndirectCommand: vertexCount, instanceCount, firstVertex, firstInstance
};

uint ceilDiv(uint a, uint b) { return (a + b - 1u) / b; }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint c0 = gl_WorkGroupID.y * kCounterCount;
  const uint d0 = gl_WorkGroupID.y * (pc.patchCount + 2u);
  const uint gregoryCount = pc.patchCount - pc.bezierCount;
  const uint maxBezier = ceilDiv(pc.bezierCount, pc.drawChunkBezier);
  const uint maxGregory = ceilDiv(gregoryCount, pc.drawChunkGregory);
  const uint bezier = counters[c0 + kCounterSurvivorsBezier];
  const uint gregory = counters[c0 + kCounterSurvivorsGregory];
  if (i == 0u) {
    counters[c0 + kCounterDrawsBezier] = ceilDiv(bezier, pc.drawChunkBezier);
    counters[c0 + kCounterDrawsGregory] = ceilDiv(gregory, pc.drawChunkGregory);
  }
  if (i < maxBezier) {
    uint first = i * pc.drawChunkBezier;
    uint n = bezier > first ? min(pc.drawChunkBezier, bezier - first) : 0u;
    commands[d0 + i] = uvec4(n * 16u, 1u, first * 16u, 0u);
  } else if (i < maxBezier + maxGregory) {
    uint first = (i - maxBezier) * pc.drawChunkGregory;
    uint n = gregory > first ? min(pc.drawChunkGregory, gregory - first) : 0u;
    commands[d0 + i] = uvec4(n * 20u, 1u, (pc.bezierCount + first) * 20u, 0u);
  }
}
