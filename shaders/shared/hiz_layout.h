// Constants and push-constant blocks of the Hi-Z pyramid builds (shaders/hiz/hiz_blocks.comp,
// hiz_tail.comp, hiz_reduce.comp, hiz_single_pass.comp) and of the Hi-Z occlusion test
// (shaders/hiz/occlusion.glsl), shared by C++ (osd_cull/bound/occlusion,
// osd_cull/frame/hiz_pyramid) and GLSL.
//
// Pyramid layout (Niessner & Loop §4.1; bound::HiZLayout computes it on the host): the depth
// image W x H is padded to P = max(bit_ceil(W), 2^s) x max(bit_ceil(H), 2^s), s = baseShift
// (1: the top level has half resolution as in the paper, 0: full resolution). Level l is
// max(1, P >> (l + s)) texels per axis; a texel holds the farthest (largest) depth of its
// footprint, [x 2^(l+s), (x+1) 2^(l+s)) clipped to the padded size. Pixels outside the image
// count as far (depth 1), so padding never makes a region look nearer.
#ifndef OSD_CULL_SHARED_HIZ_LAYOUT_H
#define OSD_CULL_SHARED_HIZ_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

OSD_CULL_CONST uint kHiZGroupSize = 8u;  // 8 x 8 texels per workgroup of the build

// HiZReduceConstants.mode
OSD_CULL_CONST uint kHiZCopy = 0u;       // dst = src texel (full-resolution top level)
OSD_CULL_CONST uint kHiZReduce2x2 = 1u;  // dst = max of the 2x2 src texels below it

// Depth of "nothing drawn": the clear value and the value of pixels outside the image.
OSD_CULL_CONST float kHiZFar = 1.0f;

// Margins of the occlusion test. The test decides whether the patch's rasterized fragments
// can pass the depth test (LESS) anywhere in its screen box; the rasterizer evaluates the
// patch in fp32, so the nearest depth and the box are widened:
// - per control point, by kHiZRelativeError (about 64 fp32 ulps) times the magnitudes its
//   clip coordinates are summed from (|viewProj| (|p|, 1)), divided by w;
// - the nearest depth by kHiZDepthBias more (16 ulps of depth 1: interpolation in the
//   rasterizer), the box by kHiZPixelMargin pixels (vertex snapping is 1/256 pixel).
// The GPU kernel computes in fp32 and uses twice these margins, so that it culls a subset of
// what the double-precision reference (bound::hizOcclusionTest) culls.
OSD_CULL_CONST float kHiZRelativeError = 3.814697265625e-6f;  // 2^-18
OSD_CULL_CONST float kHiZDepthBias = 9.5367431640625e-7f;     // 2^-20
OSD_CULL_CONST float kHiZPixelMargin = 0.015625f;             // 1/64
OSD_CULL_CONST float kHiZGpuMarginScale = 2.0f;
// Depth extrapolation of the rasterizer (docs/algorithms/occlusion.md, "Sub-pixel
// patches"): lavapipe interpolates depth over a plane through the triangle's float vertices
// but decides coverage on vertices snapped to 1/256 pixel, so a covered pixel centre can lie
// outside the triangle and get a depth in front of all three vertices (measured: 5.6 times
// the depth range of a 0.29 x 0.011 pixel patch). No margin bounds it; the patch draw
// clamps fragment depth to its nearest control point (displaced: to the nearest corner of
// the boxes around them, common/displaced_reach.glsl; patch.tesc), which makes the cull's
// bound exact.

// HiZParams.lookup: the level a box is looked up at. Paper (§4.1.1): ceil(log2(n)) for an
// n-pixel box, where 2x2 texels always cover it. Tight: one level finer when the box, as it
// happens to lie, still touches at most 2x2 texels there (no coarser level can be needed,
// so it never looks at more texels, and a finer texel's depth is never farther).
OSD_CULL_CONST uint kHiZLookupPaper = 0u;
OSD_CULL_CONST uint kHiZLookupTight = 1u;

// Push constants of one reduction step (one pyramid level).
struct HiZReduceConstants {
  uint srcWidth;  // source level (or depth image) size in texels
  uint srcHeight;
  uint dstWidth;  // level written
  uint dstHeight;
  uint mode;        // kHiZCopy or kHiZReduce2x2
  uint srcBounded;  // 1: source texels outside srcWidth x srcHeight read as kHiZFar (the
                    //    depth image); 0: reads clamp to the last texel (pyramid levels)
  uint pad0;
  uint pad1;
};

// The single-pass build (shaders/hiz/hiz_single_pass.comp): one workgroup of
// kHiZSinglePassThreads threads per kHiZTile x kHiZTile texels of level 0, at most
// kHiZMaxLevels levels (level 0 of 2^15 texels per axis).
OSD_CULL_CONST uint kHiZMaxLevels = 16u;
OSD_CULL_CONST uint kHiZTile = 32u;
OSD_CULL_CONST uint kHiZSinglePassThreads = 256u;

// Push constants of the single-pass build.
struct HiZSinglePassConstants {
  uint width;  // depth image size in pixels (pixels past it read kHiZFar)
  uint height;
  uint level0Width;  // level 0 in texels; level l is max(1, size >> l)
  uint level0Height;
  uint levelCount;
  uint baseShift;  // 0: level 0 copies the depth, 1: reduces 2x2 pixels
  float invWidth;  // 1 / width, 1 / height: normalized coordinates of the gathers
  float invHeight;
};

// The blocked build (shaders/hiz/hiz_blocks.comp): each dispatch writes up to
// kHiZBlockLevels levels, each invocation a kHiZBlock x kHiZBlock block of the first of
// them, kHiZBlockGroup x kHiZBlockGroup invocations a workgroup.
OSD_CULL_CONST uint kHiZBlockLevels = 3u;
OSD_CULL_CONST uint kHiZBlock = 4u;
OSD_CULL_CONST uint kHiZBlockGroup = 8u;
// The tail (shaders/hiz/hiz_tail.comp): one workgroup of kHiZTailThreads threads writes
// the last levels, at most kHiZTailLevels, when the first of them has at most
// kHiZTailTexels texels.
OSD_CULL_CONST uint kHiZTailLevels = 8u;
OSD_CULL_CONST uint kHiZTailThreads = 64u;
OSD_CULL_CONST uint kHiZTailTexels = 16384u;

// Push constants of one dispatch of the blocked build.
struct HiZBlockConstants {
  uint firstLevel;   // the first level written
  uint levels;       // levels written, 1 .. kHiZBlockLevels
  uint srcWidth;     // the source in texels: the depth image (firstLevel 0) or level
  uint srcHeight;    //   firstLevel - 1; depth pixels past it read kHiZFar. hiz_tail.comp:
                     //   the texels of the first level to write (its updated part)
  uint level0Width;  // level 0 in texels; level l is max(1, size >> l)
  uint level0Height;
  uint rowTexels;  // the depth rows buffer (HIZ_DEPTH_ROWS): RGBA32F texels per pixel row
  uint pad0;
};

// What the occlusion test needs to know about the pyramid (part of the cull constants).
struct HiZParams {
  uint width;  // depth image size in pixels (the screen the box is clamped to)
  uint height;
  uint baseShift;    // log2 of the pixels per top-level texel (1: half resolution)
  uint levelCount;   // mip levels of the pyramid image
  uint level0Width;  // size of level 0 in texels; level l is max(1, size >> l)
  uint level0Height;
  uint enabled;  // 0: no pyramid bound, never occlusion-culled
  uint lookup;   // kHiZLookupPaper or kHiZLookupTight
};

// The occlusion verdict of the cull kernel's result code (bits 16-23, shared/cull_layout.h):
// 0 culled as every stage's verdict, otherwise why the patch is kept; a visible verdict
// carries the pyramid level looked at in bits 4-7 of the field.
OSD_CULL_CONST uint kOcclusionVerdictOccluded = 0u;
OSD_CULL_CONST uint kOcclusionVerdictVisible = 1u;   // tested, something may be in front
OSD_CULL_CONST uint kOcclusionVerdictUntested = 2u;  // a point with w <= 0, NaN/Inf, or off screen
OSD_CULL_CONST uint kOcclusionVerdictLevelShift = 4u;

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::HiZReduceConstants) == 32);
static_assert(sizeof(osd_cull::shader::HiZParams) == 32);
static_assert(sizeof(osd_cull::shader::HiZSinglePassConstants) == 32);
static_assert(sizeof(osd_cull::shader::HiZBlockConstants) == 32);
#endif
#endif
