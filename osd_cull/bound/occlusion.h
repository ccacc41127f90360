#pragma once
/// \file occlusion.h
/// \brief Hi-Z occlusion culling of patches (Niessner & Loop, "Patch-Based Occlusion
/// Culling for Hardware Tessellation", §4.1 and §4.1.1): the double-precision CPU reference
/// of the pyramid build (shaders/hiz/hiz_reduce.comp) and of the occlusion test
/// (shaders/hiz/occlusion.glsl).
///
/// Depth convention (camera.h, render_target.h): Vulkan depth in [0, 1], 0 near, 1 far,
/// cleared to 1, compare LESS. The pyramid therefore keeps the largest depth of a footprint.
///
/// The test: the patch lies in the convex hull of its control points (Gregory: its 20
/// points), so the clip-space box of the points, divided by w, bounds the patch on screen
/// and in depth when every w is positive. The box is clamped to the screen; the pyramid
/// level is ceil(log2(n)) for a box n pixels wide or high (in pixels of the full
/// resolution), where a texel covers 2^level pixels, so at most 2 x 2 texels cover it
/// (with floor() a box could need 3 x 3). The patch is occluded when its nearest depth is
/// not nearer than the farthest depth of those texels: none of its fragments can pass the
/// depth test. Points with w <= 0 (behind the eye) keep the patch.

#include <osd_cull/shared/hiz_layout.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace osd_cull::bound {

/// \brief Sizes of a Hi-Z pyramid over a width x height depth image (shared/hiz_layout.h).
struct HiZLayout {
  uint32_t width = 0;  ///< depth image, pixels
  uint32_t height = 0;
  uint32_t baseShift = 1;    ///< a level-0 texel covers 2^baseShift pixels per axis
  uint32_t paddedWidth = 0;  ///< max(bit_ceil(width), 2^baseShift)
  uint32_t paddedHeight = 0;
  uint32_t levelCount = 0;

  /// \brief Layout for a depth image; fullResolution puts level 0 at the image's resolution
  /// (baseShift 0), otherwise level 0 has half resolution (baseShift 1, as in §4.1).
  /// \throws osd_cull::Error for a zero size.
  static HiZLayout make(uint32_t width, uint32_t height, bool fullResolution);

  uint32_t levelWidth(uint32_t level) const;
  uint32_t levelHeight(uint32_t level) const;
  /// \brief log2 of the pixels a texel of `level` covers per axis: level + baseShift.
  uint32_t texelShift(uint32_t level) const { return level + baseShift; }
};

/// \brief A pyramid on the host: levels[l][y * levelWidth(l) + x].
struct HiZPyramid {
  HiZLayout layout;
  std::vector<std::vector<double>> levels;
  double texel(uint32_t level, uint32_t x, uint32_t y) const {
    return levels[level][size_t{y} * layout.levelWidth(level) + x];
  }
};

/// \brief Builds the pyramid from its definition: every texel is the maximum depth over its
/// footprint, pixels outside the image counting as far (1). `depth` holds width x height
/// values, rows top to bottom (RenderTarget::readDepth()).
/// \throws osd_cull::Error when the depth array has the wrong size.
HiZPyramid buildHiZPyramid(std::span<const float> depth, uint32_t width, uint32_t height,
                           bool fullResolution);

/// \brief Points whose nearest depth bounds a patch's fragments when they are not the points
/// of its screen box (docs/algorithms/occlusion.md, "Displaced patches"): the displaced
/// draw clamps fragment depth to the nearest depth of displacedReachCorners(), while the
/// screen rectangle comes from the kernel's displaced bound (OOBB or CAF corners).
struct HiZDepthPoints {
  std::span<const glm::dvec3> points;
  glm::dmat4 viewProj{1.0};
};

/// \brief The 8 corners of the box p ± radius (every axis) around every point, in order
/// (point i: corners 8i .. 8i + 7): a displaced patch P + N D with |D| <= radius lies in
/// their convex hull (Niessner & Loop §4.2, uniform extension). The double mirror of
/// shaders/common/displaced_reach.glsl (which widens the radius by its fp32 margin).
std::vector<glm::dvec3> displacedReachCorners(std::span<const glm::dvec3> points, double radius);

/// \brief The screen box of a patch: inclusive pixel ranges and the nearest depth.
struct HiZScreenBox {
  bool valid = false;  ///< false: a point with w <= 0, non-finite input, or off screen
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< pixels [x0, x1] x [y0, y1], clamped
  /// Lower bound of the patch's rasterized depth: the smallest z/w of the points (of the
  /// depth points when given), each widened by its rounding margin, minus kHiZDepthBias
  /// (times the margin scale). The draw clamps every fragment's depth to at least the
  /// smallest fp32 z/w of the same points (patch.tesc), which this never exceeds.
  double nearestDepth = 0.0;
};

/// \brief The patch's pixel box and nearest depth with the margins of shared/hiz_layout.h
/// scaled by `marginScale` (1 for the reference). Invalid when some point has w <= the
/// margin (at or behind the eye plane), on NaN/Inf, or when the box misses the screen; with
/// `depth`, also when one of its points is.
HiZScreenBox hizScreenBox(std::span<const glm::dvec3> points, const glm::dmat4& viewProj,
                          uint32_t width, uint32_t height, double marginScale = 1.0,
                          const HiZDepthPoints* depth = nullptr);

/// \brief Which level a box is looked up at (shared/hiz_layout.h kHiZLookup*).
enum class HiZLookup {
  Paper,  ///< ceil(log2(n)) for an n-pixel box (§4.1.1)
  Tight,  ///< one level finer when the box touches at most 2x2 texels there
};

/// \brief The texels that cover a pixel box: level and inclusive texel ranges (at most
/// two per axis).
struct HiZFootprint {
  uint32_t level = 0;
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// \brief The level ceil(log2(max(box width, box height))) - baseShift (at least 0; with
/// HiZLookup::Tight one less when the box touches at most 2x2 texels there) and the texels
/// under the box at that level.
HiZFootprint hizFootprint(const HiZLayout& layout, const HiZScreenBox& box,
                          HiZLookup lookup = HiZLookup::Paper);

/// \brief Result of the occlusion test.
struct OcclusionResult {
  bool tested = false;  ///< the screen box was valid (see HiZScreenBox)
  bool culled = false;  ///< tested and nearestDepth >= hizDepth
  double nearestDepth = 0.0;
  double hizDepth = 0.0;  ///< farthest depth of the footprint's texels
  HiZFootprint footprint;
};

/// \brief The Hi-Z occlusion test of §4.1.1 for one patch's control points (16 Bézier or
/// 20 Gregory). Culled iff every fragment the patch can produce in its box would fail a
/// LESS depth test against the depths the pyramid was built from.
OcclusionResult hizOcclusionTest(std::span<const glm::dvec3> points, const glm::dmat4& viewProj,
                                 const HiZPyramid& pyramid, HiZLookup lookup = HiZLookup::Paper,
                                 const HiZDepthPoints* depth = nullptr);

}  // namespace osd_cull::bound
