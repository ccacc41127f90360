#version 450
// The whole Hi-Z pyramid (Niessner & Loop §4.1) in one dispatch, a single-pass downsampler
// in the manner of AMD FidelityFX SPD: each workgroup reduces one 64 x 64 tile of level 0
// (read straight from the depth attachment) down to one texel of level 6, through
// registers and shared memory; the last workgroup to finish (an atomic counter) reduces
// level 6 to the top of the pyramid.
//
// Same values as the per-level build (hiz_reduce.comp) and bound::buildHiZPyramid(): each
// texel is the farthest depth of its footprint; depth pixels outside the image read far
// (kHiZFar), so the power-of-two padding never looks nearer than it is. Level sizes are
// max(1, level0 >> l): once an axis is one texel wide, a texel's source column (or row)
// pair is clamped to that one texel, so the maximum runs over the sources inside the level
// only (the clamped duplicate is one of them).
#include <shared/hiz_layout.h>

layout(local_size_x = 256) in;  // kHiZSinglePassThreads: 16 x 16 threads, 4 x 4 texels each

layout(push_constant) uniform Push { HiZSinglePassConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D depthImage;  // texelFetch only
// Every mip of the pyramid; entries past levelCount repeat the last level (never written).
layout(set = 0, binding = 1, r32f) uniform coherent image2D levels[kHiZMaxLevels];
layout(set = 0, binding = 2) coherent buffer Counter { uint finishedGroups; };

shared float tile[16][16];
shared uint isLastGroup;

ivec2 levelSize(uint l) {
  return ivec2(max(uvec2(1u), uvec2(pc.level0Width, pc.level0Height) >> l));
}

// A constant index per case: no dynamic indexing of the image array is needed.
#define LEVEL_CASE(k)                                   \
  case k:                                               \
    if (load) return imageLoad(levels[k], p).r;         \
    imageStore(levels[k], p, vec4(v));                  \
    return v;
float levelAccess(uint l, ivec2 p, float v, bool load) {
  switch (l) {
    LEVEL_CASE(0) LEVEL_CASE(1) LEVEL_CASE(2) LEVEL_CASE(3) LEVEL_CASE(4) LEVEL_CASE(5)
    LEVEL_CASE(6) LEVEL_CASE(7) LEVEL_CASE(8) LEVEL_CASE(9) LEVEL_CASE(10) LEVEL_CASE(11)
    LEVEL_CASE(12) LEVEL_CASE(13) LEVEL_CASE(14) LEVEL_CASE(15)
  }
  return v;
}

// Stores texel p of level l when both exist.
void store(uint l, ivec2 p, float v) {
  if (l < pc.levelCount && all(lessThan(p, levelSize(l)))) levelAccess(l, p, v, false);
}

float depthAt(ivec2 p) {
  if (p.x >= int(pc.width) || p.y >= int(pc.height)) return kHiZFar;
  return texelFetch(depthImage, p, 0).r;
}

// Level-0 texel t: a depth pixel (full resolution) or the farthest of 2 x 2.
float level0(ivec2 t) {
  if (pc.baseShift == 0u) return depthAt(t);
  const ivec2 s = 2 * t;
  return max(max(depthAt(s), depthAt(s + ivec2(1, 0))),
             max(depthAt(s + ivec2(0, 1)), depthAt(s + ivec2(1, 1))));
}

// The farthest of the (up to) four values below texel t of level l + 1 that lie inside
// level l; v[dy][dx] is the value of source 2t + (dx, dy).
float reduce(uint l, ivec2 t, float v00, float v10, float v01, float v11) {
  const ivec2 size = levelSize(l);
  const bool x1 = 2 * t.x + 1 < size.x, y1 = 2 * t.y + 1 < size.y;
  float m = v00;
  if (x1) m = max(m, v10);
  if (y1) m = max(m, v01);
  if (x1 && y1) m = max(m, v11);
  return m;
}

void main() {
  const uint index = gl_LocalInvocationIndex;
  const ivec2 local = ivec2(index % 16u, index / 16u);
  const ivec2 group = ivec2(gl_WorkGroupID.xy);

  // Levels 0-2 in registers: 4 x 4 texels of level 0, 2 x 2 of level 1, one of level 2.
  const ivec2 base0 = group * 64 + local * 4;
  float l0[4][4];
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      l0[y][x] = level0(base0 + ivec2(x, y));
      store(0u, base0 + ivec2(x, y), l0[y][x]);
    }
  float l1[2][2];
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const ivec2 t = group * 32 + local * 2 + ivec2(x, y);
      l1[y][x] = reduce(0u, t, l0[2 * y][2 * x], l0[2 * y][2 * x + 1], l0[2 * y + 1][2 * x],
                        l0[2 * y + 1][2 * x + 1]);
      store(1u, t, l1[y][x]);
    }
  const ivec2 t2 = group * 16 + local;
  float v = reduce(1u, t2, l1[0][0], l1[0][1], l1[1][0], l1[1][1]);
  store(2u, t2, v);
  tile[local.y][local.x] = v;
  barrier();

  // Levels 3-6 through shared memory: 8 x 8, 4 x 4, 2 x 2, 1 texel of this tile.
  for (uint l = 3u, n = 8u; l <= 6u; ++l, n /= 2u) {
    const bool inTile = index < n * n;
    const ivec2 p = ivec2(index % n, index / n);
    const ivec2 t = group * int(n) + p;
    float r = 0.0;
    if (inTile) {
      const ivec2 s = 2 * p;
      r = reduce(l - 1u, t, tile[s.y][s.x], tile[s.y][s.x + 1], tile[s.y + 1][s.x],
                 tile[s.y + 1][s.x + 1]);
      store(l, t, r);
    }
    barrier();
    if (inTile) tile[p.y][p.x] = r;
    barrier();
  }
  if (pc.levelCount <= 7u) return;

  // The last workgroup to get here sees every tile's level 6 and builds the rest.
  memoryBarrierImage();
  barrier();
  if (index == 0u) {
    const uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    isLastGroup = atomicAdd(finishedGroups, 1u) == groups - 1u ? 1u : 0u;
  }
  barrier();
  if (isLastGroup == 0u) return;
  memoryBarrierImage();
  for (uint l = 7u; l < pc.levelCount; ++l) {
    const ivec2 size = levelSize(l), below = levelSize(l - 1u);
    for (uint i = index; i < uint(size.x * size.y); i += 256u) {
      const ivec2 t = ivec2(i % uint(size.x), i / uint(size.x));
      const ivec2 s = 2 * t, s1 = min(s + 1, below - 1);
      const float r = max(max(levelAccess(l - 1u, s, 0.0, true),
                              levelAccess(l - 1u, ivec2(s1.x, s.y), 0.0, true)),
                          max(levelAccess(l - 1u, ivec2(s.x, s1.y), 0.0, true),
                              levelAccess(l - 1u, s1, 0.0, true)));
      levelAccess(l, t, r, false);
    }
    memoryBarrierImage();
    barrier();
  }
}
