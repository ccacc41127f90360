#version 450
// The small levels of the Hi-Z pyramid (Niessner & Loop §4.1) in one workgroup: level
// pc.firstLevel from level pc.firstLevel - 1 (the blocked build's last level written,
// hiz_blocks.comp), then each level from the one below it, up to kHiZTailLevels levels,
// with a workgroup barrier between levels. At 720p and 1080p it writes levels 3-10 (80 x 45
// covered texels and less): one dispatch instead of three, where each dispatch and barrier
// costs llvmpipe a wake-up of its threads (docs/algorithms/occlusion.md). The levels are
// constant-indexed bindings: llvmpipe would execute every case of a switch over them.
//
// HIZ_SAMPLER: level pc.firstLevel - 1 is read with a MAX-reduction linear sampler (as in
// hiz_blocks.comp), otherwise with four clamped texelFetch(). The levels above it are read
// back with imageLoad() after memoryBarrierImage() and barrier(); a source texel past a
// level one texel wide or high is clamped to it (hiz_reduce.glsl: the same maximum).
#include "hiz_reduce.glsl"

layout(local_size_x = 64) in;  // kHiZTailThreads

layout(push_constant) uniform Push { HiZBlockConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, r32f) uniform coherent image2D level0;
layout(set = 0, binding = 2, r32f) uniform coherent image2D level1;
layout(set = 0, binding = 3, r32f) uniform coherent image2D level2;
layout(set = 0, binding = 4, r32f) uniform coherent image2D level3;
layout(set = 0, binding = 5, r32f) uniform coherent image2D level4;
layout(set = 0, binding = 6, r32f) uniform coherent image2D level5;
layout(set = 0, binding = 7, r32f) uniform coherent image2D level6;
layout(set = 0, binding = 8, r32f) uniform coherent image2D level7;

ivec2 tailLevelSize(uint k) {
  return hizLevelSize(uvec2(pc.level0Width, pc.level0Height), pc.firstLevel + k);
}

// Level k of the tail (k >= 1) from level k - 1, `below` and `here` their images.
#define TAIL_STEP(k, below, here)                                                        \
  if (k < pc.levels) {                                                                  \
    const ivec2 size = tailLevelSize(k), last = tailLevelSize(k - 1u) - 1;              \
    for (uint i = gl_LocalInvocationIndex; i < uint(size.x * size.y); i += 64u) {       \
      const ivec2 t = ivec2(i % uint(size.x), i / uint(size.x)), s = 2 * t;             \
      const ivec2 s1 = min(s + 1, last);                                                \
      const float r = max(max(imageLoad(below, s).r, imageLoad(below, ivec2(s1.x, s.y)).r), \
                          max(imageLoad(below, ivec2(s.x, s1.y)).r, imageLoad(below, s1).r)); \
      imageStore(here, t, vec4(r));                                                     \
    }                                                                                   \
    memoryBarrierImage();                                                               \
    barrier();                                                                          \
  }

void main() {
  // The first level: its updated part (pc.srcWidth x pc.srcHeight texels, see HiZBlockConstants).
  const ivec2 extent = ivec2(pc.srcWidth, pc.srcHeight);
  for (uint i = gl_LocalInvocationIndex; i < uint(extent.x * extent.y); i += 64u) {
    const ivec2 t = ivec2(i % uint(extent.x), i / uint(extent.x));
#if defined(HIZ_SAMPLER)
    const float r = textureLod(src, vec2(2 * t + 1), 0.0).r;
#else
    const ivec2 s = 2 * t, last = textureSize(src, 0) - 1;
    const float r = max(max(texelFetch(src, min(s, last), 0).r, texelFetch(src, min(s + ivec2(1, 0), last), 0).r),
                        max(texelFetch(src, min(s + ivec2(0, 1), last), 0).r, texelFetch(src, min(s + 1, last), 0).r));
#endif
    imageStore(level0, t, vec4(r));
  }
  memoryBarrierImage();
  barrier();
  TAIL_STEP(1u, level0, level1)
  TAIL_STEP(2u, level1, level2)
  TAIL_STEP(3u, level2, level3)
  TAIL_STEP(4u, level3, level4)
  TAIL_STEP(5u, level4, level5)
  TAIL_STEP(6u, level5, level6)
  TAIL_STEP(7u, level6, level7)
}
