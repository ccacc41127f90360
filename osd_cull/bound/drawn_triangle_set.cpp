#include "osd_cull/bound/drawn_triangle_set.h"

#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace osd_cull::bound {
namespace {

// The largest level the draw shaders set (maxTessellationGenerationLevel on lavapipe).
constexpr double kMaxListedLevel = 64.0;

// Level `l` of a QuadTessLevels entry as an integer, or an error naming it.
double integerLevel(double l, const char* what, int edge) {
  if (!(std::isfinite(l) && l >= 0.0 && l <= kMaxListedLevel && l == std::floor(l)))
    throw Error("forEachDrawnTriangle: " + std::string(what) + " level of edge " +
                std::to_string(edge) + " must be an integer in [0, 64], got " + std::to_string(l));
  return l;
}

// Domain point of edge e's ring at position `along` (0..1 along the edge) and depth `depth`
// into the patch; edges in gl_TessLevelOuter order (0: u = 0, 1: v = 0, 2: u = 1, 3: v = 1).
glm::dvec2 ringPoint(int e, double along, double depth) {
  switch (e) {
    case 0:
      return {depth, along};
    case 1:
      return {along, depth};
    case 2:
      return {1.0 - depth, along};
    default:
      return {along, 1.0 - depth};
  }
}

// B(u, v) of a 16-point Bézier patch (point (i, j) at 4 j + i), position only.
glm::dvec3 bezierPoint(std::span<const glm::dvec3> b, double u, double v) {
  const double su = 1.0 - u, sv = 1.0 - v;
  const double bu[4] = {su * su * su, 3.0 * su * su * u, 3.0 * su * u * u, u * u * u};
  const double bv[4] = {sv * sv * sv, 3.0 * sv * sv * v, 3.0 * sv * v * v, v * v * v};
  glm::dvec3 p(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) p += (bu[i] * bv[j]) * b[4 * j + i];
  return p;
}

DomainTriangle counterClockwise(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  const glm::dvec2 d1 = b - a, d2 = c - a;
  if (d1.x * d2.y - d1.y * d2.x < 0.0) std::swap(b, c);
  return {a, b, c};
}

}  // namespace

double ringApexOffset(double outerLevel, double innerLevel) {
  const double sigma = 1.0 / outerLevel, s = 1.0 / innerLevel;
  const double countDiff = std::abs(outerLevel - innerLevel), m = std::min(sigma, s);
  return std::min(1.1 * (countDiff * m + std::abs(sigma - s)),
                  0.8 * (std::max(sigma, s) + 0.5 * countDiff * m));
}

void forEachDrawnTriangle(const QuadTessLevels& levels,
                          const std::function<void(const DomainTriangle&, bool ring)>& fn) {
  std::array<double, 4> lo{}, hi{}, outer{};
  bool allOnes = true;
  for (int e = 0; e < 4; ++e) {
    lo[e] = integerLevel(levels.lo[e], "lo", e);
    hi[e] = integerLevel(levels.hi[e], "hi", e);
    if (lo[e] < 1.0)
      throw Error("forEachDrawnTriangle: edge " + std::to_string(e) + " has no segment (lo 0)");
    outer[e] = lo[e] + hi[e];
    allOnes = allOnes && outer[e] == 1.0;
  }
  auto cell = [&](glm::dvec2 c00, glm::dvec2 c11) {
    const glm::dvec2 c10(c11.x, c00.y), c01(c00.x, c11.y);
    fn({c00, c10, c11}, false);
    fn({c00, c11, c01}, false);
    fn({c00, c10, c01}, false);
    fn({c10, c11, c01}, false);
  };
  if (allOnes) {  // the quad as two triangles, either diagonal
    cell({0.0, 0.0}, {1.0, 1.0});
    return;
  }
  // Inner levels as the tessellator rounds OsdComputeTessLevels' averages (at least 2).
  const double i0 = std::max(2.0, std::ceil(0.5 * (outer[1] + outer[3])));  // subdivides u
  const double i1 = std::max(2.0, std::ceil(0.5 * (outer[0] + outer[2])));  // subdivides v
  for (double k = 1; k + 1 < i0; ++k)
    for (double l = 1; l + 1 < i1; ++l) cell({k / i0, l / i1}, {(k + 1) / i0, (l + 1) / i1});
  for (int e = 0; e < 4; ++e) {
    const double along = (e % 2 == 0) ? i1 : i0, depth = 1.0 / ((e % 2 == 0) ? i0 : i1);
    const double n = outer[e];
    const double o = ringApexOffset(n, along) + 1e-9;
    // Row A: the edge's vertices at j / n (the tessellator's positions), remapped on
    // transition edges (the first lo segments cover [0, 1/2]); row B: the inner row.
    auto rowA = [&](double j) {
      if (hi[e] == 0.0) return j / n;
      return j <= lo[e] ? 0.5 * j / lo[e] : 0.5 * (j - lo[e]) / hi[e] + 0.5;
    };
    for (double j = 0; j < n; ++j)
      for (double k = 1; k < along; ++k) {
        const double s = k / along;
        if (s >= j / n - o && s <= (j + 1) / n + o)
          fn(counterClockwise(ringPoint(e, rowA(j), 0.0), ringPoint(e, rowA(j + 1), 0.0),
                              ringPoint(e, s, depth)),
             true);
      }
    for (double k = 1; k + 1 < along; ++k)
      for (double j = 0; j <= n; ++j) {
        const double t = j / n;
        if (t >= k / along - o && t <= (k + 1) / along + o)
          fn(counterClockwise(ringPoint(e, k / along, depth), ringPoint(e, (k + 1) / along, depth),
                              ringPoint(e, rowA(j), 0.0)),
             true);
      }
  }
}

double tessCoordError(const QuadTessLevels& levels) {
  double l = 1.0;
  for (int e = 0; e < 4; ++e) l = std::max(l, std::ceil(levels.lo[e]) + std::ceil(levels.hi[e]));
  // Inner levels average opposite outer levels, so they are at most the largest outer one.
  return (l + 1.0) * std::ldexp(1.0, -17);
}

bool triangleFacesAway(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                       const glm::dvec3& eye, double vertexError) {
  const glm::dvec3 v = eye - p0, a = p1 - p0, b = p2 - p0;
  const double la = glm::length(a), lb = glm::length(b), eps = vertexError;
  const double d = 2.0 * eps * (la + lb) + 4.0 * eps * eps;
  const double margin = (glm::length(v) + eps) * d + eps * la * lb;
  // Double rounding of the products, relative to their magnitude.
  const double rounding = 1e-14 * glm::length(v) * la * lb;
  return glm::dot(v, glm::cross(a, b)) + margin + rounding < 0.0;
}

bool drawnTrianglesFaceAway(std::span<const glm::dvec3> bezier, const QuadTessLevels& levels,
                            const glm::dvec3& eye, double snapPerDistance) {
  const DerivativeBounds d = bezierDerivativeBounds(bezier);
  double r = 0.0;
  for (const glm::dvec3& p : bezier) r = std::max(r, glm::length(eye - p));
  const double dv =
      drawnVertexError(d.maxAbs, eye, r, snapPerDistance) + 2.0 * d.g * tessCoordError(levels);
  bool away = std::isfinite(dv);
  forEachDrawnTriangle(levels, [&](const DomainTriangle& t, bool) {
    if (!away) return;
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = bezierPoint(bezier, t[k].x, t[k].y);
    away = triangleFacesAway(p[0], p[1], p[2], eye, dv);
  });
  return away;
}

}  // namespace osd_cull::bound
