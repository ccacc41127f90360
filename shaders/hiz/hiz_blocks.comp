#version 450
// Up to kHiZBlockLevels levels of the Hi-Z pyramid (Niessner & Loop §4.1) in one dispatch,
// without shared memory or barriers: each invocation reduces the sources of a
// kHiZBlock x kHiZBlock block of the first level it writes, then that block to 2 x 2
// texels of the next level and to one of the level after (hiz_reduce.glsl). Dispatches
// follow one another until the rest fits hiz_tail.comp (at 720p and 1080p: levels 0-2 here,
// 3-10 in the tail).
//
// Why (docs/algorithms/occlusion.md, "Building the pyramid on lavapipe"): llvmpipe runs the
// invocations of a workgroup in 8-lane vectors; what costs is each texel a vector touches
// through the sampler (a gather from the D32 depth image costs about 3x a min/max-filtered
// fetch of an R32 level), each dispatch and barrier, and every branch, which it executes
// masked rather than skips. So the top level is read as four depth pixels per fetch
// (HIZ_DEPTH_ROWS: a copy of the depth in an RGBA32F texel buffer, rows of pc.rowTexels
// texels), the variants are compiled apart, one dispatch writes three levels, and the block
// lives in four vec4 rows, without loops (an indexed local array lives in memory).
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

// Texels t .. t + (3, 0) of the first level: one row of the block. No arrays and no loops:
// llvmpipe keeps an indexed local array in memory, one access per lane.
vec4 blockRow(ivec2 t) {
#if defined(HIZ_DEPTH_ROWS) && defined(HIZ_FULL_RESOLUTION)
  return depthRow(t.x, t.y);
#elif defined(HIZ_DEPTH_ROWS)
  // Texel (x, y) is the farthest of pixels 2 (x, y) + {0, 1}^2: two fetches per pixel row.
  const vec4 a = max(depthRow(2 * t.x, 2 * t.y), depthRow(2 * t.x, 2 * t.y + 1));
  const vec4 b = max(depthRow(2 * t.x + 4, 2 * t.y), depthRow(2 * t.x + 4, 2 * t.y + 1));
  return vec4(max(a.x, a.y), max(a.z, a.w), max(b.x, b.y), max(b.z, b.w));
#else
  return vec4(firstLevelTexel(t), firstLevelTexel(t + ivec2(1, 0)),
              firstLevelTexel(t + ivec2(2, 0)), firstLevelTexel(t + ivec2(3, 0)));
#endif
}

// Stores row r of texels t .. t + (3, 0) where they lie inside the level (size).
#define STORE_ROW(image, t, r, size)                                           \
  if (t.y < size.y) {                                                          \
    if (t.x < size.x) imageStore(image, t, vec4(r.x));                         \
    if (t.x + 1 < size.x) imageStore(image, t + ivec2(1, 0), vec4(r.y));       \
    if (t.x + 2 < size.x) imageStore(image, t + ivec2(2, 0), vec4(r.z));       \
    if (t.x + 3 < size.x) imageStore(image, t + ivec2(3, 0), vec4(r.w));       \
  }

void main() {
  const ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 t0 = int(kHiZBlock) * g;  // the block's first texel of the first level
  const uvec2 level0 = uvec2(pc.level0Width, pc.level0Height);
  const vec4 r0 = blockRow(t0), r1 = blockRow(t0 + ivec2(0, 1)), r2 = blockRow(t0 + ivec2(0, 2)),
             r3 = blockRow(t0 + ivec2(0, 3));
  const ivec2 size = hizLevelSize(level0, pc.firstLevel);
  STORE_ROW(dst0, t0, r0, size)
  STORE_ROW(dst0, (t0 + ivec2(0, 1)), r1, size)
  STORE_ROW(dst0, (t0 + ivec2(0, 2)), r2, size)
  STORE_ROW(dst0, (t0 + ivec2(0, 3)), r3, size)
  if (pc.levels < 2u) return;
  const ivec2 t1 = 2 * g;  // the 2 x 2 texels of the next level
  const vec2 w0 = vec2(hizReduce(size, t1, r0.x, r0.y, r1.x, r1.y),
                       hizReduce(size, t1 + ivec2(1, 0), r0.z, r0.w, r1.z, r1.w));
  const vec2 w1 = vec2(hizReduce(size, t1 + ivec2(0, 1), r2.x, r2.y, r3.x, r3.y),
                       hizReduce(size, t1 + 1, r2.z, r2.w, r3.z, r3.w));
  const ivec2 size1 = hizLevelSize(level0, pc.firstLevel + 1u);
  if (t1.y < size1.y) {
    if (t1.x < size1.x) imageStore(dst1, t1, vec4(w0.x));
    if (t1.x + 1 < size1.x) imageStore(dst1, t1 + ivec2(1, 0), vec4(w0.y));
  }
  if (t1.y + 1 < size1.y) {
    if (t1.x < size1.x) imageStore(dst1, t1 + ivec2(0, 1), vec4(w1.x));
    if (t1.x + 1 < size1.x) imageStore(dst1, t1 + 1, vec4(w1.y));
  }
  if (pc.levels < 3u) return;
  const float u = hizReduce(size1, g, w0.x, w0.y, w1.x, w1.y);
  if (all(lessThan(g, hizLevelSize(level0, pc.firstLevel + 2u)))) imageStore(dst2, g, vec4(u));
}
