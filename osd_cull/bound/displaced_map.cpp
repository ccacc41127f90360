#include "osd_cull/bound/displaced_map.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace osd_cull::bound {
namespace {

// Relative margin of Dmin/Dmax over the texel extremes: covers the fp32 filter weights and
// the fp32 evaluation of scale * (v - midlevel) and of the unit normal in the draw (each
// below 1e-6 relative), see docs/algorithms/displacement.md.
constexpr double kFilterMargin = 1e-5;

int64_t wrapIndex(int64_t i, int64_t n) { return ((i % n) + n) % n; }

// Splits an inclusive index range of a repeating axis of n texels into at most two ranges
// inside [0, n).
int splitWrapped(int64_t a, int64_t b, int64_t n, int64_t out[4]) {
  if (b - a + 1 >= n) {
    out[0] = 0;
    out[1] = n - 1;
    return 1;
  }
  const int64_t wa = wrapIndex(a, n), wb = wrapIndex(b, n);
  if (wa <= wb) {
    out[0] = wa;
    out[1] = wb;
    return 1;
  }
  out[0] = wa;
  out[1] = n - 1;
  out[2] = 0;
  out[3] = wb;
  return 2;
}

}  // namespace

DisplacementMap::DisplacementMap(std::string name, uint32_t width, uint32_t height,
                                 std::vector<float> texels, double scale, double midlevel,
                                 uint32_t maxLod)
    : name_(std::move(name)),
      width_(width),
      height_(height),
      scale_(scale),
      midlevel_(midlevel),
      maxLod_(maxLod) {
  const std::string where = "displacement map " + (name_.empty() ? std::string("?") : name_);
  if (width == 0 || height == 0) throw Error(where + ": the map is empty (0 texels)");
  if (texels.size() != static_cast<size_t>(width) * height)
    throw Error(where + ": " + std::to_string(texels.size()) + " texels for a " +
                std::to_string(width) + " x " + std::to_string(height) + " map");
  for (size_t i = 0; i < texels.size(); ++i)
    if (!std::isfinite(texels[i]))
      throw Error(where + ": texel " + std::to_string(i % width) + ", " +
                  std::to_string(i / width) + " is NaN or Inf");
  if (!std::isfinite(scale)) throw Error(where + ": the displacement scale is NaN or Inf");
  if (!std::isfinite(midlevel)) throw Error(where + ": the displacement midlevel is NaN or Inf");

  levels_.push_back(std::move(texels));
  const bool powerOfTwo = std::has_single_bit(width) && std::has_single_bit(height);
  if (powerOfTwo) {
    // Box filter: each texel of level L is the mean of a 2x2 block of level L-1 (a 2x1 or
    // 1x2 block once one side is 1 texel).
    for (uint32_t l = 1; (width >> (l - 1)) > 1 || (height >> (l - 1)) > 1; ++l) {
      const uint32_t pw = levelWidth(l - 1), ph = levelHeight(l - 1);
      const uint32_t w = std::max(1u, pw / 2), h = std::max(1u, ph / 2);
      const std::vector<float>& prev = levels_.back();
      std::vector<float> next(static_cast<size_t>(w) * h);
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
          const uint32_t x0 = pw > 1 ? 2 * x : x, x1 = pw > 1 ? 2 * x + 1 : x;
          const uint32_t y0 = ph > 1 ? 2 * y : y, y1 = ph > 1 ? 2 * y + 1 : y;
          const double sum = double(prev[y0 * pw + x0]) + prev[y0 * pw + x1] + prev[y1 * pw + x0] +
                             prev[y1 * pw + x1];
          next[y * w + x] = static_cast<float>(sum * 0.25);
        }
      levels_.push_back(std::move(next));
    }
  }
  if (maxLod_ >= levelCount())
    throw Error(where + ": maximum level of detail " + std::to_string(maxLod_) +
                " but the map has " + std::to_string(levelCount()) + " mip level(s)" +
                (powerOfTwo ? "" : " (maps whose sides are not powers of two are not mip-mapped)"));

  // Min/max pyramid over 2^k x 2^k blocks of level 0 (the last block of a row or column
  // may be smaller), until one block covers the map.
  minLevels_.push_back(levels_.front());
  maxLevels_.push_back(levels_.front());
  pyramidWidths_.push_back(width);
  pyramidHeights_.push_back(height);
  while (pyramidWidths_.back() > 1 || pyramidHeights_.back() > 1) {
    const uint32_t pw = pyramidWidths_.back(), ph = pyramidHeights_.back();
    const uint32_t w = (pw + 1) / 2, h = (ph + 1) / 2;
    std::vector<float> lo(static_cast<size_t>(w) * h), hi(lo.size());
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        float a = 3.0e38f, b = -3.0e38f;
        for (uint32_t yy = 2 * y; yy < std::min(2 * y + 2, ph); ++yy)
          for (uint32_t xx = 2 * x; xx < std::min(2 * x + 2, pw); ++xx) {
            a = std::min(a, minLevels_.back()[yy * pw + xx]);
            b = std::max(b, maxLevels_.back()[yy * pw + xx]);
          }
        lo[y * w + x] = a;
        hi[y * w + x] = b;
      }
    minLevels_.push_back(std::move(lo));
    maxLevels_.push_back(std::move(hi));
    pyramidWidths_.push_back(w);
    pyramidHeights_.push_back(h);
  }
}

uint32_t DisplacementMap::levelWidth(uint32_t level) const { return std::max(1u, width_ >> level); }
uint32_t DisplacementMap::levelHeight(uint32_t level) const {
  return std::max(1u, height_ >> level);
}

double DisplacementMap::sample(glm::dvec2 st, double lod) const {
  lod = std::clamp(lod, 0.0, static_cast<double>(maxLod_));
  const auto bilinear = [&](uint32_t l) {
    const int64_t w = levelWidth(l), h = levelHeight(l);
    const double x = st.x * static_cast<double>(w) - 0.5, y = st.y * static_cast<double>(h) - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    const auto ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
    const std::vector<float>& t = levels_[l];
    const auto at = [&](int64_t i, int64_t j) {
      return static_cast<double>(t[static_cast<size_t>(wrapIndex(j, h) * w + wrapIndex(i, w))]);
    };
    return (1 - ay) * ((1 - ax) * at(ix, iy) + ax * at(ix + 1, iy)) +
           ay * ((1 - ax) * at(ix, iy + 1) + ax * at(ix + 1, iy + 1));
  };
  const auto l0 = static_cast<uint32_t>(std::floor(lod));
  const double f = lod - l0;
  const uint32_t l1 = std::min(l0 + 1, maxLod_);
  return f > 0.0 ? (1 - f) * bilinear(l0) + f * bilinear(l1) : bilinear(l0);
}

TexelRange DisplacementMap::rangeOver(const UvRegion& region) const {
  const int64_t w = width_, h = height_;
  if (!std::isfinite(region.lo.x) || !std::isfinite(region.lo.y) || !std::isfinite(region.hi.x) ||
      !std::isfinite(region.hi.y) || std::max(std::abs(region.lo.x), std::abs(region.hi.x)) > 1e9 ||
      std::max(std::abs(region.lo.y), std::abs(region.hi.y)) > 1e9)
    return texelRange(0, w - 1, 0, h - 1);
  // Bilinear taps at level L read level-L texels whose centres are within one level-L texel
  // of the sample point; each covers 2^L level-0 texels: 1.5 * 2^L level-0 texels around
  // the point, plus one for the sampler's fixed-point texel snapping.
  const double reach = 1.5 * std::ldexp(1.0, static_cast<int>(maxLod_)) + 1.0;
  const auto x0 = static_cast<int64_t>(std::floor(region.lo.x * w - reach));
  const auto x1 = static_cast<int64_t>(std::floor(region.hi.x * w + reach));
  const auto y0 = static_cast<int64_t>(std::floor(region.lo.y * h - reach));
  const auto y1 = static_cast<int64_t>(std::floor(region.hi.y * h + reach));
  return texelRange(x0, x1, y0, y1);
}

TexelRange DisplacementMap::texelRange(int64_t x0, int64_t x1, int64_t y0, int64_t y1) const {
  int64_t xs[4], ys[4];
  const int nx = splitWrapped(x0, x1, width_, xs);
  const int ny = splitWrapped(y0, y1, height_, ys);
  TexelRange r{3.0e38, -3.0e38};
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const TexelRange p =
          pyramidRange(static_cast<uint32_t>(xs[2 * i]), static_cast<uint32_t>(xs[2 * i + 1]),
                       static_cast<uint32_t>(ys[2 * j]), static_cast<uint32_t>(ys[2 * j + 1]));
      r.lo = std::min(r.lo, p.lo);
      r.hi = std::max(r.hi, p.hi);
    }
  return r;
}

// The extremes over the blocks of pyramid level k that cover the inclusive texel range;
// k is chosen so that at most 5 x 5 blocks are read (a superset of the range: looser, never
// smaller).
TexelRange DisplacementMap::pyramidRange(uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1) const {
  const uint32_t extent = std::max(x1 - x0, y1 - y0) + 1;
  const uint32_t k = std::min<uint32_t>(static_cast<uint32_t>(std::bit_width(extent)) > 2
                                            ? static_cast<uint32_t>(std::bit_width(extent)) - 2
                                            : 0u,
                                        static_cast<uint32_t>(minLevels_.size()) - 1);
  const uint32_t pw = pyramidWidths_[k];
  TexelRange r{3.0e38, -3.0e38};
  for (uint32_t by = y0 >> k; by <= (y1 >> k); ++by)
    for (uint32_t bx = x0 >> k; bx <= (x1 >> k); ++bx) {
      r.lo = std::min(r.lo, static_cast<double>(minLevels_[k][by * pw + bx]));
      r.hi = std::max(r.hi, static_cast<double>(maxLevels_[k][by * pw + bx]));
    }
  return r;
}

DisplacementRange DisplacementMap::toDisplacement(TexelRange range) const {
  const double a = displacement(range.lo), b = displacement(range.hi);
  const double margin = kFilterMargin * std::abs(scale_) *
                        (std::max(std::abs(range.lo), std::abs(range.hi)) + std::abs(midlevel_));
  return {std::min({a, b, 0.0}) - margin, std::max({a, b, 0.0}) + margin};
}

DisplacementRange DisplacementMap::displacementOver(const UvRegion& region) const {
  return toDisplacement(rangeOver(region));
}

DisplacementRange DisplacementMap::displacementRange() const {
  return toDisplacement(texelRange(0, width_ - 1, 0, height_ - 1));
}

double DisplacementMap::variationAlong(glm::dvec2 a, glm::dvec2 b) const {
  const int64_t w = levelWidth(maxLod_), h = levelHeight(maxLod_);
  const std::vector<float>& texels = levels_[maxLod_];
  const auto at = [&](int64_t i, int64_t j) {
    return static_cast<double>(texels[static_cast<size_t>(wrapIndex(j, h) * w + wrapIndex(i, w))]);
  };
  const double absScale = std::abs(scale_);
  const auto wholeMap = [&](double cells) {
    const TexelRange r = texelRange(0, width_ - 1, 0, height_ - 1);
    return absScale * 2.0 * (r.hi - r.lo) * cells;
  };
  const bool finite = std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(b.x) &&
                      std::isfinite(b.y) &&
                      std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y)}) < 1e6;
  if (!finite) return wholeMap(static_cast<double>(std::max(w, h)));
  // The same walk from either end: start at the lexicographically smaller one.
  if (b.x < a.x || (b.x == a.x && b.y < a.y)) std::swap(a, b);
  // Texel-centre grid of the level: cell (i, j) spans centres i..i+1, j..j+1.
  const glm::dvec2 p(a.x * static_cast<double>(w) - 0.5, a.y * static_cast<double>(h) - 0.5);
  const glm::dvec2 q(b.x * static_cast<double>(w) - 0.5, b.y * static_cast<double>(h) - 0.5);
  const glm::dvec2 d = q - p;
  auto ix = static_cast<int64_t>(std::floor(p.x)), iy = static_cast<int64_t>(std::floor(p.y));
  const auto ex = static_cast<int64_t>(std::floor(q.x)), ey = static_cast<int64_t>(std::floor(q.y));
  const int64_t cells = std::abs(ex - ix) + std::abs(ey - iy) + 1;
  if (cells > (int64_t{1} << 22)) return wholeMap(static_cast<double>(cells));
  const int64_t sx = ex >= ix ? 1 : -1, sy = ey >= iy ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  // Segment parameter of the next cell boundary crossed in x and in y.
  double tx = d.x != 0.0 ? (static_cast<double>(sx > 0 ? ix + 1 : ix) - p.x) / d.x : inf;
  double ty = d.y != 0.0 ? (static_cast<double>(sy > 0 ? iy + 1 : iy) - p.y) / d.y : inf;
  const double dtx = d.x != 0.0 ? static_cast<double>(sx) / d.x : inf;
  const double dty = d.y != 0.0 ? static_cast<double>(sy) / d.y : inf;
  double t0 = 0.0, total = 0.0;
  for (int64_t c = 0; c < cells; ++c) {
    const bool last = c + 1 == cells;
    const bool stepX = iy == ey || (ix != ex && tx < ty);
    const double t1 = last ? 1.0 : std::clamp(stepX ? tx : ty, t0, 1.0);
    // Bilinear in the cell: f = c00 + gx ax + gy ay + k ax ay; along the segment a
    // quadratic in t whose variation is read at its ends and its extremum.
    const double c00 = at(ix, iy), c10 = at(ix + 1, iy), c01 = at(ix, iy + 1),
                 c11 = at(ix + 1, iy + 1);
    const double gx = c10 - c00, gy = c01 - c00, k = c00 - c10 - c01 + c11;
    const auto f = [&](double t) {
      const double ax = std::clamp(p.x + t * d.x - static_cast<double>(ix), 0.0, 1.0);
      const double ay = std::clamp(p.y + t * d.y - static_cast<double>(iy), 0.0, 1.0);
      return c00 + gx * ax + gy * ay + k * ax * ay;
    };
    const double quadratic = k * d.x * d.y;
    const double linear =
        gx * d.x + gy * d.y +
        k * ((p.x - static_cast<double>(ix)) * d.y + (p.y - static_cast<double>(iy)) * d.x);
    const double tm = quadratic != 0.0 ? -linear / (2.0 * quadratic) : inf;
    total += tm > t0 && tm < t1 ? std::abs(f(tm) - f(t0)) + std::abs(f(t1) - f(tm))
                                : std::abs(f(t1) - f(t0));
    if (last) break;
    t0 = t1;
    if (stepX) {
      ix += sx;
      tx += dtx;
    } else {
      iy += sy;
      ty += dty;
    }
  }
  return absScale * total;
}

}  // namespace osd_cull::bound
