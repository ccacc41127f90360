#pragma once
/// \file displaced_map.h
/// \brief A scalar displacement map as the draw samples it, and the conservative range of
/// its values over a region of texture space (Sathe, "Pre-Processing Step": the maximum
/// displacement of a patch is the extreme of the map over the patch's texture region;
/// Nießner & Loop §4.2: Dmin <= 0 <= Dmax).
///
/// The displaced surface is P + N · D(s, t), D = scale · (texel(s, t) - midlevel), N the
/// unit normal. The map is a grid of float texels (row 0 at t = 0), sampled as Vulkan does
/// with `repeat` addressing, linear filtering between texels and, for power-of-two sizes,
/// linear filtering between mip levels (box-filtered, each texel of level L the mean of a
/// 2^L x 2^L block of level 0). Every filtered sample is a convex combination of level-0
/// texels near the sample point, so the extremes of those texels bound it: rangeOver()
/// widens the region by the filter footprint of the coarsest level the draw may read
/// (DisplacementMap::maxLod) and by a texel for the sampler's texel snapping, then reads a
/// min/max pyramid built once per map.

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace osd_cull::bound {

/// \brief An axis-aligned rectangle of texture space (s, t), in map periods (1 = the
/// whole map); may extend beyond [0, 1], where the map repeats.
struct UvRegion {
  glm::dvec2 lo{0.0};
  glm::dvec2 hi{0.0};
};

/// \brief The range of the map's texels over a region, before scale and midlevel.
struct TexelRange {
  double lo = 0.0;
  double hi = 0.0;
};

/// \brief The displacement of a patch: Dmin <= 0 <= Dmax (Nießner & Loop §4.2), in object
/// units, rounded outward.
struct DisplacementRange {
  double dmin = 0.0;
  double dmax = 0.0;
  /// max(|Dmin|, |Dmax|): the uniform extension of the Full bound.
  double maxAbs() const { return dmax > -dmin ? dmax : -dmin; }
};

/// \brief A displacement map with its mip chain and min/max pyramid (built once).
class DisplacementMap {
 public:
  /// \brief Takes level-0 texels (width * height floats, row-major, row 0 at t = 0).
  /// `scale` and `midlevel` map a texel value v to the displacement scale * (v - midlevel).
  /// `maxLod` is the coarsest mip level the draw may sample (the sampler clamps to it);
  /// power-of-two maps only, others must use 0.
  /// \throws osd_cull::Error naming `name` for an empty map, a size that does not match,
  /// NaN/Inf texels, a non-finite scale or midlevel, or a bad maxLod.
  DisplacementMap(std::string name, uint32_t width, uint32_t height, std::vector<float> texels,
                  double scale, double midlevel, uint32_t maxLod = 0);

  const std::string& name() const { return name_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  double scale() const { return scale_; }
  double midlevel() const { return midlevel_; }
  uint32_t maxLod() const { return maxLod_; }
  /// \brief Mip levels: 1 + log2(max(width, height)) for power-of-two maps, else 1.
  uint32_t levelCount() const { return static_cast<uint32_t>(levels_.size()); }
  uint32_t levelWidth(uint32_t level) const;
  uint32_t levelHeight(uint32_t level) const;
  /// \brief The texels of one mip level (row-major).
  const std::vector<float>& level(uint32_t level) const { return levels_.at(level); }

  /// \brief The displacement of a texel value: scale * (value - midlevel).
  double displacement(double value) const { return scale_ * (value - midlevel_); }

  /// \brief What the draw computes at (s, t) with level of detail `lod` (0 <= lod <=
  /// maxLod): trilinear filtering with repeat addressing, in double. Used by tests.
  double sample(glm::dvec2 st, double lod = 0.0) const;

  /// \brief Bounds of every filtered sample of the draw (any lod in [0, maxLod], texel
  /// snapping included) at points of `region`: the extremes of the level-0 texels within
  /// the filter footprint, read from the min/max pyramid. Non-finite region: the whole map.
  TexelRange rangeOver(const UvRegion& region) const;

  /// \brief rangeOver() in displacement units, widened to contain 0 (Dmin <= 0 <= Dmax)
  /// and by a relative margin that covers the fp32 filtering of the draw.
  DisplacementRange displacementOver(const UvRegion& region) const;

  /// \brief The extremes of the whole map in displacement units (as displacementOver()).
  DisplacementRange displacementRange() const;

  /// \brief The total variation, in displacement units (|scale| times texel values), of the
  /// draw's sample at level maxLod along the straight texture-space segment from `a` to `b`:
  /// the length of the path the displacement D travels while (s, t) runs along the segment.
  /// Exact for the bilinear interpolation of that level (per texel cell the restriction to
  /// a line is a quadratic: its ends and its extremum); the fixed-point texel snapping of
  /// the sampler is not modelled (a tessellation estimate, not a culling bound). Symmetric
  /// bit for bit: the segment is walked from its lexicographically smaller end, so the two
  /// patches sharing an edge get the same value (docs/algorithms/displacement.md,
  /// "Tessellation"). Non-finite ends: twice the map's range per texel of its larger side.
  double variationAlong(glm::dvec2 a, glm::dvec2 b) const;

 private:
  TexelRange texelRange(int64_t x0, int64_t x1, int64_t y0, int64_t y1) const;
  TexelRange pyramidRange(uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1) const;
  DisplacementRange toDisplacement(TexelRange range) const;

  std::string name_;
  uint32_t width_ = 0;
  uint32_t height_ = 0;
  double scale_ = 1.0;
  double midlevel_ = 0.0;
  uint32_t maxLod_ = 0;
  std::vector<std::vector<float>> levels_;     ///< mip chain, box filtered
  std::vector<std::vector<float>> minLevels_;  ///< min over 2^k x 2^k blocks of level 0
  std::vector<std::vector<float>> maxLevels_;
  std::vector<uint32_t> pyramidWidths_;
  std::vector<uint32_t> pyramidHeights_;
};

}  // namespace osd_cull::bound
