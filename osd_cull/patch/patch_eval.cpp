#include "osd_cull/patch/patch_eval.h"

#include "osd_cull/error.h"

#include <cmath>
#include <string>

namespace osd_cull {
namespace {

// Cubic Bernstein polynomials and their derivatives at t.
void cubic(double t, double b[4], double d[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * s * s * t;
  b[2] = 3.0 * s * t * t;
  b[3] = t * t * t;
  d[0] = -3.0 * s * s;
  d[1] = 3.0 * s * s - 6.0 * s * t;
  d[2] = 6.0 * s * t - 3.0 * t * t;
  d[3] = 3.0 * t * t;
}

// The rational multipliers of a Gregory interior point at (u, v).
struct Blend {
  double a, b;
};
Blend blendAt(const GregoryInterior& g, double u, double v) {
  return {g.a0 + g.as * u + g.at * v, g.b0 + g.bs * u + g.bt * v};
}

}  // namespace

double bernstein(int degree, int i, double t) {
  double c = 1.0;
  for (int k = 1; k <= i; ++k) c = c * (degree - i + k) / k;
  return c * std::pow(1.0 - t, degree - i) * std::pow(t, i);
}

SurfacePoint evaluateBezier(std::span<const glm::dvec3, kBezierPoints> points, double u, double v) {
  double bu[4], du[4], bv[4], dv[4];
  cubic(u, bu, du);
  cubic(v, bv, dv);
  const double qu[3] = {(1 - u) * (1 - u), 2 * u * (1 - u), u * u};
  const double qv[3] = {(1 - v) * (1 - v), 2 * v * (1 - v), v * v};
  SurfacePoint s;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) s.position += (bu[i] * bv[j]) * points[4 * j + i];
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      s.du += (3.0 * qu[i] * bv[j]) * (points[4 * j + i + 1] - points[4 * j + i]);
      s.dv += (3.0 * qv[i] * bu[j]) * (points[4 * (i + 1) + j] - points[4 * i + j]);
    }
  return s;
}

std::array<glm::dvec3, kBezierPoints> gregoryToBezierAt(
    std::span<const glm::dvec3, kGregoryPoints> p, double u, double v) {
  std::array<glm::dvec3, kBezierPoints> net;
  for (uint32_t k = 0; k < kBezierPoints; ++k)
    if (kGregoryBoundary[k] >= 0) net[k] = p[kGregoryBoundary[k]];
  // Osd_EvalBasisGregory guards the denominator (1 where it vanishes), so each pair's
  // weights sum to one even at the corners.
  for (const GregoryInterior& g : kGregoryInterior) {
    const Blend w = blendAt(g, u, v);
    const double d = w.a + w.b;
    const double wa = w.a * (d <= 0.0 ? 1.0 : 1.0 / d);
    net[4 * g.j + g.i] = wa * p[g.a] + (1.0 - wa) * p[g.b];
  }
  return net;
}

SurfacePoint evaluateGregory(std::span<const glm::dvec3, kGregoryPoints> points, double u,
                             double v) {
  const std::array<glm::dvec3, kBezierPoints> frozen = gregoryToBezierAt(points, u, v);
  return evaluateBezier(frozen, u, v);
}

SurfacePoint evaluateGregoryExact(std::span<const glm::dvec3, kGregoryPoints> points, double u,
                                  double v) {
  SurfacePoint s = evaluateGregory(points, u, v);
  // Product rule: the interior points depend on (u, v) too. For q = (a A + b B)/(a + b),
  // dq/du = (a_u b - a b_u)/(a + b)^2 (A - B), and likewise for v.
  double bu[4], du[4], bv[4], dv[4];
  cubic(u, bu, du);
  cubic(v, bv, dv);
  for (const GregoryInterior& g : kGregoryInterior) {
    const Blend w = blendAt(g, u, v);
    const double d = w.a + w.b;
    if (!(d > 0.0)) continue;  // corner: the basis function and its derivatives vanish
    const glm::dvec3 diff = points[g.a] - points[g.b];
    const double basis = bu[g.i] * bv[g.j];
    s.du += (basis * (g.as * w.b - w.a * g.bs) / (d * d)) * diff;
    s.dv += (basis * (g.at * w.b - w.a * g.bt) / (d * d)) * diff;
  }
  return s;
}

SurfacePoint evaluatePatch(const PatchSet& set, uint32_t patch, double u, double v) {
  if (patch >= set.patchCount())
    throw Error("evaluatePatch: patch " + std::to_string(patch) + " out of range [0, " +
                std::to_string(set.patchCount()) + ")");
  const std::span<const glm::dvec3> cps = set.controlPoints(patch);
  if (set.type(patch) == PatchType::Bezier) return evaluateBezier(cps.first<kBezierPoints>(), u, v);
  return evaluateGregory(cps.first<kGregoryPoints>(), u, v);
}

}  // namespace osd_cull
