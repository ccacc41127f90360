#include "osd_cull/bound/drawn_triangles.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace osd_cull::bound {
namespace {

// fp32 unit roundoff.
constexpr double kFloatEpsilon = 1.0 / 16777216.0;

// A quantity known to lie in [lo, hi].
struct Range {
  double lo = 0.0, hi = 0.0;
};

// The tessellator rounds equal-spacing levels up to integers, at least 1.
Range levelRange(double level, double slack) {
  const double l = std::max(1.0, std::ceil(level));
  return {std::max(1.0, l - slack), l + slack};
}

// Inner level from the two opposite outer levels (OsdComputeTessLevels), rounded up; an
// inner level of 1 becomes 2 (Vulkan, quads, equal spacing) unless every level is 1.
Range innerRange(Range a, Range b, bool allOnes) {
  Range r{std::ceil(0.5 * (a.lo + b.lo)), std::ceil(0.5 * (a.hi + b.hi))};
  if (!allOnes) r.lo = std::max(2.0, r.lo), r.hi = std::max(2.0, r.hi);
  return r;
}

// R of the file comment: the largest distance of a control point from the eye.
double maxDistance(std::span<const glm::dvec3> points, const glm::dvec3& eye) {
  double r = 0.0;
  for (const glm::dvec3& p : points) r = std::max(r, glm::length(eye - p));
  return r;
}

}  // namespace

TriangleShape triangleShape(const QuadTessLevels& levels, double slack) {
  for (int e = 0; e < 4; ++e)
    if (!(std::isfinite(levels.lo[e]) && std::isfinite(levels.hi[e]) && levels.lo[e] >= 0.0 &&
          levels.hi[e] >= 0.0))
      throw Error("triangleShape: tessellation levels must be finite and non-negative");
  bool allOnes = slack == 0.0;
  std::array<Range, 4> lo, hi, outer;
  std::array<bool, 4> split{};
  for (int e = 0; e < 4; ++e) {
    split[e] = levels.hi[e] > 0.0;
    lo[e] = levelRange(levels.lo[e], slack);
    hi[e] = split[e] ? levelRange(levels.hi[e], slack) : Range{0.0, 0.0};
    outer[e] = {lo[e].lo + hi[e].lo, lo[e].hi + hi[e].hi};
    allOnes = allOnes && !split[e] && outer[e].hi == 1.0;
  }
  TriangleShape s;
  if (slack == 0.0) {  // integer levels: drawn_triangle_set.h lists them up to 64
    s.exactLevels = true;
    for (int e = 0; e < 4; ++e) {
      s.levels.lo[e] = lo[e].lo, s.levels.hi[e] = hi[e].lo;
      s.exactLevels = s.exactLevels && outer[e].lo <= 64.0;
    }
  }
  if (allOnes) {  // the quad as two triangles
    s.phi = 2.0 * 1.01, s.psi = 1.01, s.minEdge = 0.9;
    return s;
  }
  // inner[0] subdivides u (from outer edges 1 and 3, parameter u), inner[1] subdivides v.
  const Range inner[2] = {innerRange(outer[1], outer[3], false),
                          innerRange(outer[0], outer[2], false)};
  const Range spacing[2] = {{1.0 / inner[0].hi, 1.0 / inner[0].lo},
                            {1.0 / inner[1].hi, 1.0 / inner[1].lo}};
  // Inner grid: right triangles with legs su, sv; take the corner at the right angle.
  s.phi = spacing[0].hi + spacing[1].hi;
  s.psi = spacing[0].hi * spacing[1].hi;
  s.minEdge = std::min(spacing[0].lo, spacing[1].lo);
  for (int e = 0; e < 4; ++e) {
    // Edges 0 and 2 (u = 0, 1) run along v: ring depth su, inner row spacing sv.
    const Range along = spacing[(e % 2 == 0) ? 1 : 0];
    const Range depth = spacing[(e % 2 == 0) ? 0 : 1];
    // Segments of the edge after the transition remap, and the remap's largest shift of
    // a vertex from where the tessellator put it: |hi - lo| / (2 (lo + hi)) at vertex lo.
    double segMax, segMin, shift = 0.0;
    if (split[e]) {
      segMax = std::max(0.5 / lo[e].lo, 0.5 / hi[e].lo);
      segMin = std::min(0.5 / lo[e].hi, 0.5 / hi[e].hi);
      const double diff = std::abs(levels.hi[e] - levels.lo[e]) + 2.0 * slack;
      shift = std::min(0.5, diff / (2.0 * outer[e].lo));
    } else {
      segMax = 1.0 / outer[e].lo;
      segMin = 1.0 / outer[e].hi;
    }
    s.minEdge = std::min(s.minEdge, segMin);
    // A ring triangle: base on one row, apex on the other row at distance `depth`. The
    // stitching (implementation-dependent in Vulkan) puts the apex at most
    //   min(1.1 (|n - i| m + |σ - s|), 0.8 (max(σ, s) + |n - i| m / 2)),  m = min(σ, s),
    // beyond the base's nearer end (σ = 1/n the edge's spacing, s = 1/i the inner row's),
    // plus the transition remap's shift: rows with equal counts line up, and extra segments
    // on one row shift the other by up to about half a spacing each. Measured on lavapipe
    // (Mesa's D3D11-style tessellator) for every reachable (n, i) up to 64: at most 0.94 of
    // the first bracket and 0.70 of the second; tests/test_drawn_triangles.cpp checks the
    // whole bound against the device's tessellator.
    const double base = std::max(segMax, along.hi);
    const double sigmaMax = 1.0 / outer[e].lo, sigmaMin = 1.0 / outer[e].hi;
    const double countDiff =
        std::max(std::abs(outer[e].lo - 1.0 / along.lo), std::abs(outer[e].hi - 1.0 / along.hi));
    const double spacingDiff =
        std::max(std::abs(sigmaMax - along.lo), std::abs(sigmaMin - along.hi));
    const double minSpacing = std::min(sigmaMax, along.hi);
    const double offset =
        std::min(1.1 * (countDiff * minSpacing + spacingDiff),
                 0.8 * (std::max(sigmaMax, along.hi) + 0.5 * countDiff * minSpacing)) +
        shift;
    const double kappa = 1.0 + offset / depth.lo;
    s.phi = std::max(s.phi, kappa * (base + offset + depth.hi));
    s.psi = std::max(s.psi, kappa * base * (offset + depth.hi));
  }
  // The tessellator's coordinates are fixed point (lavapipe: 16 fractional bits) or
  // fp32: allow their rounding.
  s.phi *= 1.01;
  s.psi *= 1.01;
  s.minEdge *= 0.9;  // measured: edges up to 2% shorter than the spacing (fixed point)
  return s;
}

DerivativeBounds bezierDerivativeBounds(std::span<const glm::dvec3> bezier) {
  if (bezier.size() != 16)
    throw Error(std::string(__FILE__) + ": a bicubic Bézier patch has 16 control points, got " +
                std::to_string(bezier.size()));
  DerivativeBounds d;
  auto b = [&](int i, int j) { return bezier[4 * j + i]; };
  for (const glm::dvec3& p : bezier)
    d.maxAbs = std::max({d.maxAbs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      d.g = std::max(d.g, 3.0 * glm::length(b(i + 1, j) - b(i, j)));
      d.g = std::max(d.g, 3.0 * glm::length(b(j, i + 1) - b(j, i)));
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 2; ++i) {
      d.h = std::max(d.h, 6.0 * glm::length(b(i + 2, j) - 2.0 * b(i + 1, j) + b(i, j)));
      d.h = std::max(d.h, 6.0 * glm::length(b(j, i + 2) - 2.0 * b(j, i + 1) + b(j, i)));
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      d.h = std::max(d.h, 9.0 * glm::length(b(i + 1, j + 1) - b(i, j + 1) - b(i + 1, j) + b(i, j)));
  // Rounding of the differences: relative to the coordinates.
  d.g += 16.0 * std::numeric_limits<double>::epsilon() * d.maxAbs;
  d.h += 64.0 * std::numeric_limits<double>::epsilon() * d.maxAbs;
  return d;
}

double drawnVertexError(double maxAbs, const glm::dvec3& eye, double maxDistance,
                        double snapPerDistance) {
  const double e = std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)});
  return 32.0 * kFloatEpsilon * (maxAbs + e) + maxDistance * snapPerDistance;
}

double snapPerDistance(const glm::dmat4& viewProj, double width, double height,
                       uint32_t subPixelBits) {
  // Rows x, y and w of the projection (glm: m[column][row]); for a perspective view with a
  // rigid view matrix, |row_x.xyz| / |row_w.xyz| is the x focal factor (P00), likewise y.
  auto rowLength = [&](int r) {
    return std::sqrt(viewProj[0][r] * viewProj[0][r] + viewProj[1][r] * viewProj[1][r] +
                     viewProj[2][r] * viewProj[2][r]);
  };
  const double w = rowLength(3);
  const double fx = rowLength(0) / w, fy = rowLength(1) / w;
  if (!(fx > 0.0 && fy > 0.0 && width > 0.0 && height > 0.0))
    return std::numeric_limits<double>::infinity();
  // One pixel at distance d spans 2 d / (width fx) (x), 2 d / (height fy) (y); the snap
  // moves a vertex by at most half a sub-pixel step in each of x and y.
  const double half = 0.5 * std::ldexp(1.0, -static_cast<int>(subPixelBits));
  const double sx = 2.0 / (width * fx), sy = 2.0 / (height * fy);
  return half * std::sqrt(sx * sx + sy * sy) * 1.01;
}

double normalDeviation(const DerivativeBounds& d, const TriangleShape& shape, double vertexError) {
  const double m = std::max(shape.minEdge, 1e-6);
  const double h = d.h + 4.0 * vertexError / (m * m);
  return 0.5 * d.g * h * shape.phi + 0.25 * h * h * shape.psi;
}

double tangentPlaneDrawnMargin(std::span<const glm::dvec3> bezier, const glm::dvec3& eye,
                               const TriangleShape& shape, double snap) {
  const DerivativeBounds d = bezierDerivativeBounds(bezier);
  const double r = maxDistance(bezier, eye);
  const double dv = drawnVertexError(d.maxAbs, eye, r, snap);
  const double mu = (r + dv) * normalDeviation(d, shape, dv) + dv * d.g * d.g;
  return mu * (1.0 + 1e-9);
}

ConeOfNormals widenCone(const ConeOfNormals& cone, std::span<const glm::dvec3> bezier,
                        const glm::dvec3& eye, const TriangleShape& shape, double snap) {
  if (!cone.valid) return cone;
  ConeOfNormals w = cone;
  w.valid = false;
  w.reason = BackPatchVerdict::DrawnTriangles;
  const DerivativeBounds d = bezierDerivativeBounds(bezier);
  const double r = maxDistance(bezier, eye);
  const double dv = drawnVertexError(d.maxAbs, eye, r, snap);
  const double deviation = normalDeviation(d, shape, dv) * (1.0 + 1e-9);
  if (!(cone.minNormal > deviation)) return w;
  const double gamma = cone.angle + std::asin(deviation / cone.minNormal) + kConeAngleMargin;
  if (!(gamma < 0.5 * std::numbers::pi)) return w;
  // withApex's t grows by at most maxRadius (tan γ' - tan γ); a drawn vertex off the
  // surface by dv moves h and ρ by at most dv.
  const double tanOld = std::tan(cone.angle), tanNew = std::tan(gamma);
  const double back = cone.maxRadius * (tanNew - tanOld) + dv * (1.0 + tanNew);
  w.apex = cone.apex - (back * (1.0 + 1e-9)) * cone.axis;
  w.angle = gamma;
  w.sinAngle = std::sin(gamma) * (1.0 + 1e-12);
  w.valid = std::isfinite(w.apex.x) && std::isfinite(w.apex.y) && std::isfinite(w.apex.z) &&
            w.sinAngle < 1.0;
  w.reason = w.valid ? BackPatchVerdict::BackFacing : BackPatchVerdict::DrawnTriangles;
  return w;
}

}  // namespace osd_cull::bound
