#version 450
// The whole Hi-Z pyramid (Niessner & Loop §4.1) in one dispatch, a single-pass downsampler
// in the manner of AMD FidelityFX SPD: each workgroup reduces one 32 x 32 tile of level 0
// (read straight from the depth attachment) down to one texel of level 5, through
// registers and shared memory; the last workgroup to finish (an atomic counter) reduces
// level 5 to the top of the pyramid.
//
// Same values as the per-level build (hiz_reduce.comp) and bound::buildHiZPyramid(): each
// texel is the farthest depth of its footprint; depth pixels outside the image read far
// (kHiZFar), so the power-of-two padding never looks nearer than it is. Level sizes are
// max(1, level0 >> l): once an axis is one texel wide, a texel's source column (or row)
// pair is clamped to that one texel, so the maximum runs over the sources inside the level
// only (the clamped duplicate is one of them).
#include "hiz_reduce.glsl"

layout(local_size_x = 256) in;  // kHiZSinglePassThreads: 16 x 16 threads, 2 x 2 texels each

layout(push_constant) uniform Push { HiZSinglePassConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D depthImage;  // nearest, white border
// Every mip of the pyramid; entries past levelCount repeat the last level (never written).
layout(set = 0, binding = 1, r32f) uniform coherent image2D levels[kHiZMaxLevels];
layout(set = 0, binding = 2) coherent buffer Counter { uint finishedGroups; };

shared float tile[16][16];
shared uint isLastGroup;

ivec2 levelSize(uint l) {
  return ivec2(max(uvec2(1u), uvec2(pc.level0Width, pc.level0Height) >> l));
}

// Constant indices in the cases: no dynamic indexing of the image array is needed (a
// constant level folds the switch away).
#define STORE_CASE(k) \
  case k:             \
    imageStore(levels[k], p, vec4(v)); \
    break;
#define LOAD_CASE(k) \
  case k:            \
    return imageLoad(levels[k], p).r;
void levelStore(uint l, ivec2 p, float v) {
  switch (l) {
    STORE_CASE(0) STORE_CASE(1) STORE_CASE(2) STORE_CASE(3) STORE_CASE(4) STORE_CASE(5)
    STORE_CASE(6) STORE_CASE(7) STORE_CASE(8) STORE_CASE(9) STORE_CASE(10) STORE_CASE(11)
    STORE_CASE(12) STORE_CASE(13) STORE_CASE(14) STORE_CASE(15)
  }
}
float levelLoad(uint l, ivec2 p) {
  switch (l) {
    LOAD_CASE(0) LOAD_CASE(1) LOAD_CASE(2) LOAD_CASE(3) LOAD_CASE(4) LOAD_CASE(5)
    LOAD_CASE(6) LOAD_CASE(7) LOAD_CASE(8) LOAD_CASE(9) LOAD_CASE(10) LOAD_CASE(11)
    LOAD_CASE(12) LOAD_CASE(13) LOAD_CASE(14) LOAD_CASE(15)
  }
  return kHiZFar;
}

// Stores texel p of level L (a constant) when both exist.
#define STORE(L, p, v) \
  if (L < pc.levelCount && all(lessThan(p, levelSize(L)))) imageStore(levels[L], p, vec4(v))

float depthAt(ivec2 p) {
  if (p.x >= int(pc.width) || p.y >= int(pc.height)) return kHiZFar;
  return texelFetch(depthImage, p, 0).r;
}

// Level-0 texel t: a depth pixel (full resolution) or the farthest of 2 x 2, fetched with
// one textureGather() at their shared corner (nearest sampler, clamp to an opaque white
// border: pixels past the image read 1, far; the corner lies half a texel from any other
// texel boundary, so rounding cannot shift the footprint).
float level0(ivec2 t) {
  if (pc.baseShift == 0u) return depthAt(t);
  const vec4 g = textureGather(depthImage, vec2(2 * t + 1) * vec2(pc.invWidth, pc.invHeight));
  return max(max(g.x, g.y), max(g.z, g.w));
}

// The farthest of the (up to) four values below texel t of level l + 1 that lie inside
// level l (hiz_reduce.glsl).
float reduce(uint l, ivec2 t, float v00, float v10, float v01, float v11) {
  return hizReduce(levelSize(l), t, v00, v10, v01, v11);
}

// Level L of this tile, n x n texels, from level L - 1 in `tile` (written back to it).
#define LEVEL_STEP(L, n)                                                                    \
  {                                                                                         \
    const bool inTile = index < n * n;                                                      \
    const ivec2 p = ivec2(index % n, index / n);                                            \
    const ivec2 t = group * int(n) + p;                                                     \
    float r = 0.0;                                                                          \
    if (inTile) {                                                                           \
      const ivec2 s = 2 * p;                                                                \
      r = reduce(L - 1u, t, tile[s.y][s.x], tile[s.y][s.x + 1], tile[s.y + 1][s.x],         \
                 tile[s.y + 1][s.x + 1]);                                                   \
      STORE(L, t, r);                                                                       \
    }                                                                                       \
    barrier();                                                                              \
    if (inTile) tile[p.y][p.x] = r;                                                         \
    barrier();                                                                              \
  }

void main() {
  const uint index = gl_LocalInvocationIndex;
  const ivec2 local = ivec2(index % 16u, index / 16u);
  const ivec2 group = ivec2(gl_WorkGroupID.xy);

  // Levels 0 and 1 in registers: 2 x 2 texels of level 0, one of level 1.
  const ivec2 t1 = group * 16 + local;
  float l0[4];
  for (int i = 0; i < 4; ++i) {
    const ivec2 t = 2 * t1 + ivec2(i & 1, i >> 1);
    l0[i] = level0(t);
    STORE(0u, t, l0[i]);
  }
  const float v = reduce(0u, t1, l0[0], l0[1], l0[2], l0[3]);
  STORE(1u, t1, v);
  tile[local.y][local.x] = v;
  barrier();

  // Levels 2-5 through shared memory: 8 x 8, 4 x 4, 2 x 2, 1 texel of this tile.
  LEVEL_STEP(2u, 8u);
  LEVEL_STEP(3u, 4u);
  LEVEL_STEP(4u, 2u);
  LEVEL_STEP(5u, 1u);
  if (pc.levelCount <= 6u) return;

  // The last workgroup to get here sees every tile's level 5 and builds the rest.
  memoryBarrierImage();
  barrier();
  if (index == 0u) {
    const uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    isLastGroup = atomicAdd(finishedGroups, 1u) == groups - 1u ? 1u : 0u;
  }
  barrier();
  if (isLastGroup == 0u) return;
  memoryBarrierImage();
  for (uint l = 6u; l < pc.levelCount; ++l) {
    const ivec2 size = levelSize(l), below = levelSize(l - 1u);
    for (uint i = index; i < uint(size.x * size.y); i += 256u) {
      const ivec2 t = ivec2(i % uint(size.x), i / uint(size.x));
      const ivec2 s = 2 * t, s1 = min(s + 1, below - 1);
      const float r = max(max(levelLoad(l - 1u, s), levelLoad(l - 1u, ivec2(s1.x, s.y))),
                          max(levelLoad(l - 1u, ivec2(s.x, s1.y)), levelLoad(l - 1u, s1)));
      levelStore(l, t, r);
    }
    memoryBarrierImage();
    barrier();
  }
}
