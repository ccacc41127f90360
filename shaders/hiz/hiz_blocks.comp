#version 450
// Up to kHiZBlockLevels levels of the Hi-Z pyramid (Niessner & Loop §4.1) in one dispatch,
// without shared memory or barriers: each invocation reduces the sources of a
// kHiZBlock x kHiZBlock block of the first level it writes, then that block to 2 x 2
// texels of the next level and to one of the level after (hiz_reduce.glsl). A build is
// ceil(levels / 3) dispatches (11 levels at 720p and 1080p: 4).
//
// Why (docs/algorithms/occlusion.md, "Building the pyramid on lavapipe"): llvmpipe runs the
// invocations of a workgroup in 8-lane vectors; what costs is each texel a vector touches
// through the sampler (a gather from the D32 depth image costs about 3x a min/max-filtered
// fetch of an R32 level), each dispatch and barrier, and every branch, which it executes
// masked rather than skips. So the top level is read as four depth pixels per fetch
// (HIZ_DEPTH_ROWS: a copy of the depth in an RGBA32F texel buffer, rows of pc.rowTexels
// texels), the variants are compiled apart, and one dispatch writes three levels.
//
// Sources (the first level, pc.firstLevel):
//   HIZ_DEPTH_ROWS   level 0 from the depth rows buffer (pixels past the image read far);
//   HIZ_DEPTH_GATHER level 0 from the depth image, one textureGather() per texel (nearest,
//                    opaque white border: pixels past the image read 1, far);
//   HIZ_DEPTH_FETCH  level 0 from the depth image, one texelFetch() per texel;
//   HIZ_SAMPLER      level pc.firstLevel - 1 with a MAX-reduction linear sampler
//                    (unnormalized coordinates at the corner shared by the 2 x 2 texels,
//                    clamp to edge: a read past the level repeats its last texel);
//   otherwise        level pc.firstLevel - 1, four clamped texelFetch() and max().
// HIZ_FULL_RESOLUTION: level 0 has the depth's resolution (baseShift 0), else half.
#include "hiz_reduce.glsl"

layout(local_size_x = 8, local_size_y = 8) in;  // kHiZBlockGroup

layout(push_constant) uniform Push { HiZBlockConstants pc; };
#if defined(HIZ_DEPTH_ROWS)
layout(set = 0, binding = 0) uniform samplerBuffer src;
#else
layout(set = 0, binding = 0) uniform sampler2D src;
#endif
// Levels firstLevel, + 1, + 2; those past pc.levels repeat a written one and are not written.
layout(set = 0, binding = 1, r32f) uniform writeonly image2D dst0;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D dst1;
layout(set = 0, binding = 3, r32f) uniform writeonly image2D dst2;

#if defined(HIZ_DEPTH_ROWS)
// Depth pixels (x, y) .. (x + 3, y), x a multiple of 4; pixels past the image read far.
vec4 depthRow(int x, int y) {
  const int row = min(y, int(pc.srcHeight) - 1);
  const vec4 v = texelFetch(src, row * int(pc.rowTexels) + min(x >> 2, int(pc.rowTexels) - 1));
  const bvec4 inside = lessThan(ivec4(x) + ivec4(0, 1, 2, 3), ivec4(int(pc.srcWidth)));
  return y < int(pc.srcHeight) ? mix(vec4(kHiZFar), v, inside) : vec4(kHiZFar);
}
#endif

// The value of texel t of the first level (not used by HIZ_DEPTH_ROWS).
float firstLevelTexel(ivec2 t) {
#if defined(HIZ_DEPTH_GATHER)
  const vec4 g = textureGather(src, vec2(2 * t + 1) / vec2(pc.srcWidth, pc.srcHeight));
  return max(max(g.x, g.y), max(g.z, g.w));
#elif defined(HIZ_DEPTH_FETCH)
  const ivec2 size = ivec2(pc.srcWidth, pc.srcHeight);
  const float d = texelFetch(src, min(t, size - 1), 0).r;
  return all(lessThan(t, size)) ? d : kHiZFar;
#elif defined(HIZ_SAMPLER)
  return textureLod(src, vec2(2 * t + 1), 0.0).r;
#elif !defined(HIZ_DEPTH_ROWS)
  const ivec2 last = ivec2(pc.srcWidth, pc.srcHeight) - 1, s = 2 * t;
  return max(max(texelFetch(src, min(s, last), 0).r, texelFetch(src, min(s + ivec2(1, 0), last), 0).r),
             max(texelFetch(src, min(s + ivec2(0, 1), last), 0).r, texelFetch(src, min(s + 1, last), 0).r));
#else
  return kHiZFar;
#endif
}

void main() {
  const ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 t0 = int(kHiZBlock) * g;  // the block's first texel of the first level
  const uvec2 level0 = uvec2(pc.level0Width, pc.level0Height);
  float v[4][4];  // v[y][x]: the block
#if defined(HIZ_DEPTH_ROWS) && defined(HIZ_FULL_RESOLUTION)
  for (int y = 0; y < 4; ++y) {
    const vec4 r = depthRow(t0.x, t0.y + y);
    v[y][0] = r.x;
    v[y][1] = r.y;
    v[y][2] = r.z;
    v[y][3] = r.w;
  }
#elif defined(HIZ_DEPTH_ROWS)
  // Texel (x, y) is the farthest of pixels 2 (x, y) + {0, 1}^2: 8 x 8 pixels, two fetches
  // per pixel row.
  for (int y = 0; y < 4; ++y) {
    const int py = 2 * (t0.y + y);
    const vec4 a = max(depthRow(2 * t0.x, py), depthRow(2 * t0.x, py + 1));
    const vec4 b = max(depthRow(2 * t0.x + 4, py), depthRow(2 * t0.x + 4, py + 1));
    v[y][0] = max(a.x, a.y);
    v[y][1] = max(a.z, a.w);
    v[y][2] = max(b.x, b.y);
    v[y][3] = max(b.z, b.w);
  }
#else
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) v[y][x] = firstLevelTexel(t0 + ivec2(x, y));
#endif
  ivec2 size = hizLevelSize(level0, pc.firstLevel);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const ivec2 t = t0 + ivec2(x, y);
      if (all(lessThan(t, size))) imageStore(dst0, t, vec4(v[y][x]));
    }
  if (pc.levels < 2u) return;
  float w[2][2];
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const ivec2 t = 2 * g + ivec2(x, y);
      w[y][x] = hizReduce(size, t, v[2 * y][2 * x], v[2 * y][2 * x + 1], v[2 * y + 1][2 * x],
                          v[2 * y + 1][2 * x + 1]);
    }
  const ivec2 size1 = hizLevelSize(level0, pc.firstLevel + 1u);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const ivec2 t = 2 * g + ivec2(x, y);
      if (all(lessThan(t, size1))) imageStore(dst1, t, vec4(w[y][x]));
    }
  if (pc.levels < 3u) return;
  const float u = hizReduce(size1, g, w[0][0], w[0][1], w[1][0], w[1][1]);
  if (all(lessThan(g, hizLevelSize(level0, pc.firstLevel + 2u)))) imageStore(dst2, g, vec4(u));
}
