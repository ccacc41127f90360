#include "osd_cull/bound/drawn_triangle_set.h"

#include "osd_cull/bound/patch_eval.h"
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

// Outer level of edge e (the Lo and Hi halves together).
double outerLevel(const QuadTessLevels& levels, int e) {
  return std::ceil(levels.lo[e]) + std::ceil(levels.hi[e]);
}

// Whether the tessellator draws the quad as two triangles (every outer level 1).
bool allLevelsOne(const QuadTessLevels& levels) {
  for (int e = 0; e < 4; ++e)
    if (outerLevel(levels, e) != 1.0) return false;
  return true;
}

// The inner levels as the tessellator rounds OsdComputeTessLevels' averages (at least 2):
// [0] subdivides u, [1] subdivides v.
std::array<double, 2> innerLevels(const QuadTessLevels& levels) {
  return {std::max(2.0, std::ceil(0.5 * (outerLevel(levels, 1) + outerLevel(levels, 3)))),
          std::max(2.0, std::ceil(0.5 * (outerLevel(levels, 0) + outerLevel(levels, 2))))};
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
  const auto [i0, i1] = innerLevels(levels);
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

double tessellatorPointError(double level) {
  const double n = std::ceil(level), reciprocal = std::round(65536.0 / n) / 65536.0;
  return std::floor(n / 2.0) * std::abs(reciprocal - 1.0 / n);
}

double tessCoordError(const QuadTessLevels& levels) {
  const std::array<double, 2> inner = innerLevels(levels);
  double e = 0.0;
  if (!allLevelsOne(levels))
    e = std::max(tessellatorPointError(inner[0]), tessellatorPointError(inner[1]));
  return e + std::ldexp(1.0, -21);
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

double gregoryDerivativeBound(std::span<const glm::dvec3> gregory) {
  if (gregory.size() != kGregoryPoints)
    throw Error("gregoryDerivativeBound: a Gregory patch has 20 control points, got " +
                std::to_string(gregory.size()));
  // The two nets the blends move between: Fp (a) or Fm (b) at the interior positions.
  std::array<glm::dvec3, 16> a, b;
  for (size_t k = 0; k < 16; ++k)
    if (kGregoryBoundary[k] >= 0) a[k] = b[k] = gregory[kGregoryBoundary[k]];
  for (const GregoryInterior& g : kGregoryInterior) {
    a[4 * g.j + g.i] = gregory[g.a];
    b[4 * g.j + g.i] = gregory[g.b];
  }
  auto widest = [&](int p, int q) {
    return std::max({glm::length(a[p] - a[q]), glm::length(a[p] - b[q]), glm::length(b[p] - a[q]),
                     glm::length(b[p] - b[q])});
  };
  double hodograph = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i)
      hodograph = std::max(
          {hodograph, widest(4 * j + i, 4 * j + i + 1), widest(4 * i + j, 4 * (i + 1) + j)});
  double rational = 0.0;
  for (const GregoryInterior& g : kGregoryInterior)
    rational += 4.0 / 3.0 * glm::length(gregory[g.a] - gregory[g.b]);
  return 3.0 * hodograph + rational;
}

bool drawnTrianglesFaceAway(std::span<const glm::dvec3> points, const QuadTessLevels& levels,
                            const glm::dvec3& eye, double snapPerDistance) {
  const bool gregory = points.size() == kGregoryPoints;
  if (!gregory && points.size() != kBezierPoints)
    throw Error(
        "drawnTrianglesFaceAway: a patch has 16 (Bezier) or 20 (Gregory) control "
        "points, got " +
        std::to_string(points.size()));
  double g = 0.0, maxAbs = 0.0, r = 0.0;
  if (gregory) {
    g = gregoryDerivativeBound(points);
    for (const glm::dvec3& p : points)
      maxAbs = std::max({maxAbs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  } else {
    const DerivativeBounds d = bezierDerivativeBounds(points);
    g = d.g;
    maxAbs = d.maxAbs;
  }
  // The surface lies in the hull of the points (the Gregory blends are convex).
  for (const glm::dvec3& p : points) r = std::max(r, glm::length(eye - p));
  const double dv = drawnVertexError(maxAbs, eye, r, snapPerDistance) +
                    (gregory ? std::ldexp(kGregoryEvalUlps, -24) * maxAbs : 0.0) +
                    2.0 * g * tessCoordError(levels);
  auto point = [&](glm::dvec2 q) {
    if (!gregory) return bezierPoint(points, q.x, q.y);
    const std::array<glm::dvec3, 16> net = gregoryBezierNet(points, q.x, q.y);
    return bezierPoint(net, q.x, q.y);
  };
  bool away = std::isfinite(dv);
  forEachDrawnTriangle(levels, [&](const DomainTriangle& t, bool) {
    if (!away) return;
    away = triangleFacesAway(point(t[0]), point(t[1]), point(t[2]), eye, dv);
  });
  return away;
}

}  // namespace osd_cull::bound
