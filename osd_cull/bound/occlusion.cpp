#include "osd_cull/bound/occlusion.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace osd_cull::bound {

namespace {

using shader::kHiZDepthBias;
using shader::kHiZFar;
using shader::kHiZPixelMargin;
using shader::kHiZRelativeError;

bool finite4(const glm::dvec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

}  // namespace

HiZLayout HiZLayout::make(uint32_t width, uint32_t height, bool fullResolution) {
  if (width == 0 || height == 0)
    throw Error("HiZLayout: depth image size " + std::to_string(width) + "x" +
                std::to_string(height) + " must be positive");
  HiZLayout l;
  l.width = width;
  l.height = height;
  l.baseShift = fullResolution ? 0 : 1;
  const uint32_t minPadded = 1u << l.baseShift;
  l.paddedWidth = std::max(std::bit_ceil(width), minPadded);
  l.paddedHeight = std::max(std::bit_ceil(height), minPadded);
  // Both padded sizes are at least 2^baseShift, so the top level has at least one texel.
  const uint32_t log2Max = std::bit_width(std::max(l.paddedWidth, l.paddedHeight)) - 1;
  l.levelCount = log2Max - l.baseShift + 1;
  return l;
}

uint32_t HiZLayout::levelWidth(uint32_t level) const {
  return std::max(1u, paddedWidth >> texelShift(level));
}

uint32_t HiZLayout::levelHeight(uint32_t level) const {
  return std::max(1u, paddedHeight >> texelShift(level));
}

HiZPyramid buildHiZPyramid(std::span<const float> depth, uint32_t width, uint32_t height,
                           bool fullResolution) {
  HiZPyramid p;
  p.layout = HiZLayout::make(width, height, fullResolution);
  if (depth.size() != size_t{width} * height)
    throw Error("buildHiZPyramid: " + std::to_string(depth.size()) + " depth values for a " +
                std::to_string(width) + "x" + std::to_string(height) + " image");
  const HiZLayout& l = p.layout;
  constexpr double lowest = -std::numeric_limits<double>::infinity();
  for (uint32_t level = 0; level < l.levelCount; ++level) {
    const uint32_t lw = l.levelWidth(level), lh = l.levelHeight(level);
    const uint32_t shift = l.texelShift(level);
    std::vector<double> texels(size_t{lw} * lh, lowest);
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width; ++x) {
        double& t =
            texels[size_t{std::min(y >> shift, lh - 1)} * lw + std::min(x >> shift, lw - 1)];
        t = std::max(t, double{depth[size_t{y} * width + x]});
      }
    // A footprint [x 2^shift, (x+1) 2^shift) clipped to the padded size that reaches past
    // the image holds pixels that do not exist: they count as far.
    const uint64_t f = uint64_t{1} << shift;
    for (uint32_t ty = 0; ty < lh; ++ty)
      for (uint32_t tx = 0; tx < lw; ++tx) {
        const uint64_t xEnd = std::min<uint64_t>((tx + 1) * f, l.paddedWidth);
        const uint64_t yEnd = std::min<uint64_t>((ty + 1) * f, l.paddedHeight);
        if (xEnd > width || yEnd > height) texels[size_t{ty} * lw + tx] = kHiZFar;
      }
    p.levels.push_back(std::move(texels));
  }
  return p;
}

std::vector<glm::dvec3> displacedReachCorners(std::span<const glm::dvec3> points, double radius) {
  std::vector<glm::dvec3> out;
  out.reserve(8 * points.size());
  for (const glm::dvec3& p : points)
    for (int k = 0; k < 8; ++k)
      out.push_back(p + glm::dvec3((k & 1) ? radius : -radius, (k & 2) ? radius : -radius,
                                   (k & 4) ? radius : -radius));
  return out;
}

namespace {

// The NDC box and depth range of `points`, each widened by its rounding margin; false when a
// point is at or behind the eye plane (w <= the margin) or not finite.
struct NdcBounds {
  glm::dvec2 lo{std::numeric_limits<double>::infinity()};
  glm::dvec2 hi{-std::numeric_limits<double>::infinity()};
  double nearest = std::numeric_limits<double>::infinity();
};

bool ndcBounds(std::span<const glm::dvec3> points, const glm::dmat4& viewProj, double rel,
               NdcBounds& out) {
  for (const glm::dvec3& p : points) {
    const glm::dvec4 c = clipPoint(p, viewProj);
    const glm::dvec4 m = absClipPoint(p, viewProj);  // magnitudes c is summed from
    if (!finite4(c) || !finite4(m)) return false;
    // At or behind the eye plane: the NDC box does not bound the patch.
    if (!(c.w > rel * m.w)) return false;
    const double w = c.w - rel * m.w;  // smallest w the rasterizer may have used
    const glm::dvec3 ndc = glm::dvec3(c) / c.w;
    const glm::dvec3 err = rel * (glm::dvec3(m) + glm::abs(ndc) * m.w) / w;
    out.lo = glm::min(out.lo, glm::dvec2(ndc) - glm::dvec2(err));
    out.hi = glm::max(out.hi, glm::dvec2(ndc) + glm::dvec2(err));
    out.nearest = std::min(out.nearest, ndc.z - err.z);
  }
  return true;
}

}  // namespace

HiZScreenBox hizScreenBox(std::span<const glm::dvec3> points, const glm::dmat4& viewProj,
                          uint32_t width, uint32_t height, double marginScale,
                          const HiZDepthPoints* depth) {
  HiZScreenBox box;
  if (points.empty() || width == 0 || height == 0 || !allFinite(viewProj)) return box;
  const double rel = double{kHiZRelativeError} * marginScale;
  NdcBounds b;
  if (!ndcBounds(points, viewProj, rel, b)) return box;
  const glm::dvec2 lo = b.lo, hi = b.hi;
  double nearest = b.nearest;
  if (depth) {
    NdcBounds d;
    if (depth->points.empty() || !allFinite(depth->viewProj) ||
        !ndcBounds(depth->points, depth->viewProj, rel, d))
      return box;
    nearest = d.nearest;
  }
  // Vulkan viewport: pixel x = (ndc.x + 1) / 2 * width, y likewise (the projection flips y).
  const double pad = double{kHiZPixelMargin} * marginScale;
  const double px0 = (lo.x * 0.5 + 0.5) * width - pad, px1 = (hi.x * 0.5 + 0.5) * width + pad;
  const double py0 = (lo.y * 0.5 + 0.5) * height - pad, py1 = (hi.y * 0.5 + 0.5) * height + pad;
  if (!std::isfinite(px0 + px1 + py0 + py1 + nearest)) return box;
  if (px1 < 0.0 || py1 < 0.0 || px0 > width || py0 > height) return box;
  auto pixel = [](double v, uint32_t size) {
    return static_cast<uint32_t>(std::clamp(std::floor(v), 0.0, double(size - 1)));
  };
  box.valid = true;
  box.x0 = pixel(px0, width);
  box.x1 = pixel(px1, width);
  box.y0 = pixel(py0, height);
  box.y1 = pixel(py1, height);
  // Niessner & Loop §4.1.1 with the fragment depth of the draw: it writes max(interpolated
  // depth, P) with P the smallest fp32 z/w of the control points (of the displaced reach
  // corners, `depth`; patch.tesc), and P >= min(ndc.z - err.z) because err bounds the fp32
  // rounding of each z/w (the same argument as for the box); so no fragment lies in front of
  // `nearest`, whatever the rasterizer's depth interpolation does
  // (docs/algorithms/occlusion.md, "Sub-pixel patches", "Displaced patches").
  box.nearestDepth = nearest - double{kHiZDepthBias} * marginScale;
  return box;
}

HiZFootprint hizFootprint(const HiZLayout& layout, const HiZScreenBox& box, HiZLookup lookup) {
  const uint32_t n = std::max(box.x1 - box.x0, box.y1 - box.y0) + 1;
  // ceil(log2(n)) in integers: n pixels starting anywhere touch at most two aligned runs
  // of 2^k >= n pixels.
  const uint32_t k = n <= 1 ? 0u : static_cast<uint32_t>(std::bit_width(n - 1));
  HiZFootprint f;
  f.level = std::min(k > layout.baseShift ? k - layout.baseShift : 0u, layout.levelCount - 1);
  if (lookup == HiZLookup::Tight && f.level > 0) {
    // Only the next finer level can do: there 2^(k-1) < n pixels per texel, and one more
    // level down the box would touch at least three.
    const uint32_t finer = layout.texelShift(f.level - 1);
    if ((box.x1 >> finer) - (box.x0 >> finer) <= 1 && (box.y1 >> finer) - (box.y0 >> finer) <= 1)
      --f.level;
  }
  const uint32_t shift = layout.texelShift(f.level);
  const uint32_t lw = layout.levelWidth(f.level), lh = layout.levelHeight(f.level);
  f.x0 = std::min(box.x0 >> shift, lw - 1);
  f.x1 = std::min(box.x1 >> shift, lw - 1);
  f.y0 = std::min(box.y0 >> shift, lh - 1);
  f.y1 = std::min(box.y1 >> shift, lh - 1);
  return f;
}

OcclusionResult hizOcclusionTest(std::span<const glm::dvec3> points, const glm::dmat4& viewProj,
                                 const HiZPyramid& pyramid, HiZLookup lookup,
                                 const HiZDepthPoints* depth) {
  OcclusionResult r;
  const HiZLayout& l = pyramid.layout;
  const HiZScreenBox box = hizScreenBox(points, viewProj, l.width, l.height, 1.0, depth);
  if (!box.valid) return r;
  r.tested = true;
  r.nearestDepth = box.nearestDepth;
  r.footprint = hizFootprint(l, box, lookup);
  const HiZFootprint& f = r.footprint;
  r.hizDepth =
      std::max(std::max(pyramid.texel(f.level, f.x0, f.y0), pyramid.texel(f.level, f.x1, f.y0)),
               std::max(pyramid.texel(f.level, f.x0, f.y1), pyramid.texel(f.level, f.x1, f.y1)));
  r.culled = r.nearestDepth >= r.hizDepth;
  return r;
}

}  // namespace osd_cull::bound
