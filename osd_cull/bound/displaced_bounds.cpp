#include "osd_cull/bound/displaced_bounds.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/error.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>

namespace osd_cull::bound {
namespace {

// Added to every δ: covers the rounding of the products below (relative 1e-16) with a wide
// margin.
constexpr double kDeltaMargin = 1e-9;

// The largest value of N·r̂ over the cone, for unit r̂ (§4.2: δ+ for r̂, δ- for -r̂):
// 1 when r̂ is inside the cone (θ <= α, θ the angle between axis and r̂), else
// cos(θ - α) = cos θ cos α + sin θ sin α, without inverse trigonometry (the GLSL mirror
// computes the same products).
double coneReach(const ConeOfNormals& cone, const glm::dvec3& unitDirection) {
  const double cosTheta = glm::dot(cone.axis, unitDirection);
  const double sinTheta = glm::length(glm::cross(cone.axis, unitDirection));
  const double cosAlpha = std::cos(cone.angle), sinAlpha = std::sin(cone.angle);
  if (cosTheta >= cosAlpha) return 1.0;
  return std::min(1.0, cosTheta * cosAlpha + sinTheta * sinAlpha + kDeltaMargin);
}

bool finiteVec(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double maxAbs(const glm::dvec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

glm::dvec3 row3(const glm::dmat4& m, int row) { return {m[0][row], m[1][row], m[2][row]}; }

std::array<glm::dvec3, 8> boxCorners(const glm::dvec3& lo, const glm::dvec3& hi) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[static_cast<size_t>(i)] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y,
                                 (i & 4) ? hi.z : lo.z};
  return c;
}

// The extensions of a patch along three directions (rows of a linear map).
struct Extensions {
  glm::dvec3 plus{0.0}, minus{0.0};
};
Extensions extensions(const DisplacedPatch& patch, DisplacedExtension extension,
                      const glm::dvec3 (&directions)[3]) {
  Extensions e;
  for (int i = 0; i < 3; ++i) {
    const AxisExtension a = axisExtension(patch, extension, directions[i]);
    e.plus[i] = a.plus;
    e.minus[i] = a.minus;
  }
  return e;
}

}  // namespace

const char* toString(DisplacedExtension extension) {
  switch (extension) {
    case DisplacedExtension::Full:
      return "full";
    case DisplacedExtension::ACoN:
      return "acon";
    case DisplacedExtension::CoN:
      return "con";
  }
  return "?";
}

const char* toString(DisplacedBox box) { return box == DisplacedBox::CAF ? "caf" : "oobb"; }

std::string displacedKernelName(DisplacedExtension extension, DisplacedBox box) {
  return std::string(toString(extension)) + "-" + toString(box);
}

UvRegion patchUvRegion(std::span<const glm::dvec2> corners) {
  UvRegion r{corners[0], corners[0]};
  for (const glm::dvec2& c : corners) {
    r.lo = glm::min(r.lo, c);
    r.hi = glm::max(r.hi, c);
  }
  return r;
}

ConeOfNormals displacementCone(const PatchSet& patches, uint32_t patch,
                               DisplacedExtension extension) {
  if (extension == DisplacedExtension::Full) return {};
  const auto points = patches.controlPoints(patch);
  if (patches.type(patch) == PatchType::Gregory) return buildGregoryConeFromTangentCones(points);
  return extension == DisplacedExtension::CoN ? buildConeOfNormals(points)
                                              : buildConeFromTangentCones(points);
}

std::vector<DisplacementRange> displacementRanges(const PatchSet& patches,
                                                  std::span<const glm::dvec2> uvCorners,
                                                  const DisplacementMap& map) {
  if (uvCorners.empty())
    throw Error((patches.source.empty() ? std::string("mesh") : patches.source) +
                ": the mesh has no texture coordinates (OBJ 'vt'); a displacement map needs "
                "them");
  if (uvCorners.size() != 4 * static_cast<size_t>(patches.patchCount()))
    throw Error("displaced bounds: " + std::to_string(uvCorners.size()) +
                " texture coordinates for " + std::to_string(patches.patchCount()) +
                " patches (4 per patch expected)");
  std::vector<DisplacementRange> out(patches.patchCount());
  for (uint32_t p = 0; p < patches.patchCount(); ++p)
    out[p] = map.displacementOver(patchUvRegion(uvCorners.subspan(4 * size_t{p}, 4)));
  return out;
}

std::vector<DisplacedPatch> buildDisplacedPatches(const PatchSet& patches,
                                                  std::span<const glm::dvec2> uvCorners,
                                                  const DisplacementMap& map,
                                                  DisplacedExtension extension) {
  const std::vector<DisplacementRange> ranges = displacementRanges(patches, uvCorners, map);
  std::vector<DisplacedPatch> out(patches.patchCount());
  for (uint32_t p = 0; p < patches.patchCount(); ++p) {
    out[p].range = ranges[p];
    out[p].cone = displacementCone(patches, p, extension);
  }
  return out;
}

AxisExtension axisExtension(const DisplacedPatch& patch, DisplacedExtension extension,
                            const glm::dvec3& direction) {
  const double length = glm::length(direction);
  const double dmax = patch.range.dmax, negMin = -patch.range.dmin;  // both >= 0
  if (!(length > 0.0)) return {0.0, 0.0};
  double up = 1.0, down = 1.0;  // δ+ and δ-: Full, or a cone that cannot be used
  if (extension != DisplacedExtension::Full && patch.cone.valid) {
    const glm::dvec3 unit = direction / length;
    up = coneReach(patch.cone, unit);
    down = coneReach(patch.cone, -unit);
  }
  // Relative rounding of the products below, toward larger extensions.
  const double round = 1.0 + 1e-12;
  AxisExtension a;
  a.plus = std::max({dmax * up, negMin * down, 0.0}) * length * round;
  a.minus = std::max({dmax * down, negMin * up, 0.0}) * length * round;
  return a;
}

bool isCameraAlignedPerspective(const glm::dmat4& p) {
  return p[0][3] == 0.0 && p[1][3] == 0.0 && p[2][3] == -1.0 && p[3][3] == 0.0 && p[1][0] == 0.0 &&
         p[3][0] == 0.0 && p[0][1] == 0.0 && p[3][1] == 0.0 && p[0][2] == 0.0 && p[1][2] == 0.0;
}

DisplacedBound displacedBound(std::span<const glm::dvec3> points, const DisplacedPatch& patch,
                              DisplacedExtension extension, DisplacedBox box,
                              const glm::dmat4& view, const glm::dmat4& projection) {
  DisplacedBound b;
  b.box = box;
  b.finite = allFinite(points) && allFinite(view) && allFinite(projection) &&
             std::isfinite(patch.range.dmin) && std::isfinite(patch.range.dmax);
  if (!b.finite) return b;

  if (box == DisplacedBox::OOBB) {
    glm::dvec3 lo(points[0]), hi(points[0]);
    for (const glm::dvec3& p : points) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const Extensions e = extensions(patch, extension, axes);
    const double margin =
        kRelativeMargin * (std::max(maxAbs(lo), maxAbs(hi)) + maxAbs(e.plus) + maxAbs(e.minus));
    b.lo = lo - e.minus - margin;
    b.hi = hi + e.plus + margin;
    b.corners = boxCorners(b.lo, b.hi);
    b.toClip = projection * view;
    b.finite = finiteVec(b.lo) && finiteVec(b.hi);
    return b;
  }

  // CAF: per-point boxes along the camera axes (rows of the view's linear part).
  const glm::dvec3 axes[3] = {row3(view, 0), row3(view, 1), row3(view, 2)};
  const Extensions e = extensions(patch, extension, axes);
  glm::dvec3 lo(3e300), hi(-3e300);
  double scale = maxAbs(e.plus) + maxAbs(e.minus);
  std::vector<glm::dvec3> camera(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    camera[i] = glm::dvec3(view * glm::dvec4(points[i], 1.0));
    scale = std::max(scale, maxAbs(camera[i]) + maxAbs(e.plus) + maxAbs(e.minus));
  }
  const double margin = 4.0 * kRelativeMargin * scale;
  for (const glm::dvec3& c : camera) {
    lo = glm::min(lo, c - e.minus - margin);
    hi = glm::max(hi, c + e.plus + margin);
  }
  b.lo = lo;
  b.hi = hi;
  b.toClip = projection;
  b.corners = boxCorners(lo, hi);
  b.finite = finiteVec(lo) && finiteVec(hi);
  // Depth = -z; every box must lie certainly in front of the eye.
  const double nearDepth = -hi.z, farDepth = -lo.z;
  if (!b.finite || !isCameraAlignedPerspective(projection) || !(nearDepth > margin)) return b;

  glm::dvec2 slopeLo(3e300), slopeHi(-3e300);
  for (const glm::dvec3& c : camera) {
    const glm::dvec3 l = c - e.minus - margin, h = c + e.plus + margin;
    const double d0 = -h.z, d1 = -l.z;  // the box's depth range, d0 > 0
    for (int k = 0; k < 2; ++k) {
      // Extremes of x/d over the box: the largest x over the nearest depth when x >= 0.
      slopeHi[k] = std::max(slopeHi[k], h[k] >= 0.0 ? h[k] / d0 : h[k] / d1);
      slopeLo[k] = std::min(slopeLo[k], l[k] <= 0.0 ? l[k] / d0 : l[k] / d1);
    }
  }
  // Division rounding (relative 1e-16) widened to the common margin.
  slopeLo -= kRelativeMargin * (glm::abs(slopeLo) + glm::dvec2(1.0));
  slopeHi += kRelativeMargin * (glm::abs(slopeHi) + glm::dvec2(1.0));
  b.slopeLo = slopeLo;
  b.slopeHi = slopeHi;
  b.nearDepth = nearDepth;
  b.farDepth = farDepth;
  for (int i = 0; i < 8; ++i) {
    const double d = (i & 4) ? farDepth : nearDepth;
    b.corners[static_cast<size_t>(i)] = {((i & 1) ? slopeHi.x : slopeLo.x) * d,
                                         ((i & 2) ? slopeHi.y : slopeLo.y) * d, -d};
  }
  b.frustum = true;
  return b;
}

bool boundContains(const DisplacedBound& bound, const glm::dvec3& point, const glm::dmat4& view,
                   double tolerance) {
  if (!bound.finite) return true;
  const glm::dvec3 q =
      bound.box == DisplacedBox::OOBB ? point : glm::dvec3(view * glm::dvec4(point, 1.0));
  const double slack =
      tolerance * std::max({maxAbs(bound.lo), maxAbs(bound.hi), maxAbs(q), 1e-300});
  if (!bound.frustum)
    return glm::all(glm::greaterThanEqual(q, bound.lo - slack)) &&
           glm::all(glm::lessThanEqual(q, bound.hi + slack));
  const double d = -q.z;
  if (d < bound.nearDepth - slack || d > bound.farDepth + slack || !(d > 0.0)) return false;
  const glm::dvec2 slope = glm::dvec2(q.x, q.y) / d;
  const double s = tolerance * (1.0 + glm::length(slope));
  return glm::all(glm::greaterThanEqual(slope, bound.slopeLo - s)) &&
         glm::all(glm::lessThanEqual(slope, bound.slopeHi + s));
}

}  // namespace osd_cull::bound
