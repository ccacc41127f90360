#include "osd_cull/bound/patch_eval.h"

#include "osd_cull/error.h"

#include <cmath>
#include <string>

namespace osd_cull::bound {
namespace {

void requireSize(std::span<const glm::dvec3> points, size_t expected, const char* what) {
  if (points.size() != expected)
    throw Error(std::string(__FILE__) + ": a " + what + " patch has " + std::to_string(expected) +
                " control points, got " + std::to_string(points.size()));
}

// Cubic Bernstein values and derivatives at t.
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

}  // namespace

double bernstein(int degree, int i, double t) {
  double c = 1.0;
  for (int k = 1; k <= i; ++k) c = c * (degree - i + k) / k;
  return c * std::pow(1.0 - t, degree - i) * std::pow(t, i);
}

PatchSample evaluateBezier(std::span<const glm::dvec3> bezier, double u, double v) {
  requireSize(bezier, 16, "bicubic Bézier");
  double bu[4], du[4], bv[4], dv[4];
  cubic(u, bu, du);
  cubic(v, bv, dv);
  const double qu[3] = {(1 - u) * (1 - u), 2 * u * (1 - u), u * u};
  const double qv[3] = {(1 - v) * (1 - v), 2 * v * (1 - v), v * v};
  PatchSample s;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) s.position += (bu[i] * bv[j]) * bezier[4 * j + i];
  // Derivatives from the differences of control points (the hodographs): translation
  // invariant, and exactly zero along a collapsed edge, where the points are equal.
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      s.du += (3.0 * qu[i] * bv[j]) * (bezier[4 * j + i + 1] - bezier[4 * j + i]);
      s.dv += (3.0 * qv[i] * bu[j]) * (bezier[4 * (i + 1) + j] - bezier[4 * i + j]);
    }
  return s;
}

std::array<glm::dvec3, 16> gregoryBezierNet(std::span<const glm::dvec3> gregory, double u,
                                            double v) {
  requireSize(gregory, 20, "Gregory");
  std::array<glm::dvec3, 16> net;
  for (int k = 0; k < 16; ++k)
    if (kGregoryBoundary[k] >= 0) net[k] = gregory[kGregoryBoundary[k]];
  for (const GregoryInterior& g : kGregoryInterior) {
    const double a = g.a0 + g.as * u + g.at * v;
    const double b = g.b0 + g.bs * u + g.bt * v;
    const double wa = (a + b > 0.0) ? a / (a + b) : 0.5;
    net[4 * g.j + g.i] = wa * gregory[g.a] + (1.0 - wa) * gregory[g.b];
  }
  return net;
}

PatchSample evaluateGregory(std::span<const glm::dvec3> gregory, double u, double v) {
  const std::array<glm::dvec3, 16> net = gregoryBezierNet(gregory, u, v);
  PatchSample s = evaluateBezier(net, u, v);
  // Product rule: the interior points depend on (u, v) too. For q = (a A + b B)/(a + b),
  // dq/du = (a_u b - a b_u)/(a + b)^2 (A - B), and likewise for v.
  double bu[4], du[4], bv[4], dv[4];
  cubic(u, bu, du);
  cubic(v, bv, dv);
  for (const GregoryInterior& g : kGregoryInterior) {
    const double a = g.a0 + g.as * u + g.at * v;
    const double b = g.b0 + g.bs * u + g.bt * v;
    const double d = a + b;
    if (!(d > 0.0)) continue;  // corner: the basis function and its derivatives vanish
    const glm::dvec3 diff = gregory[g.a] - gregory[g.b];
    const double w = bu[g.i] * bv[g.j];
    s.du += (w * (g.as * b - a * g.bs) / (d * d)) * diff;
    s.dv += (w * (g.at * b - a * g.bt) / (d * d)) * diff;
  }
  return s;
}

}  // namespace osd_cull::bound
