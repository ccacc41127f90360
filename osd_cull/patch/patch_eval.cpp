#include "osd_cull/patch/patch_eval.h"

#include "osd_cull/error.h"

#include <string>

namespace osd_cull {
namespace {

// Cubic Bernstein polynomials and their derivatives at t.
void bernstein(double t, double b[4], double d[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * t * s * s;
  b[2] = 3.0 * t * t * s;
  b[3] = t * t * t;
  d[0] = -3.0 * s * s;
  d[1] = 3.0 * s * s - 6.0 * t * s;
  d[2] = 6.0 * t * s - 3.0 * t * t;
  d[3] = 3.0 * t * t;
}

// Where each Gregory point sits in the 4x4 Bézier grid (column i along u, row j along v).
// Boundary points map one to one (Osd_EvalBasisGregory: boundaryGregory / BezSCol / BezTRow).
struct GridSlot {
  int gregory;
  int i;
  int j;
};
constexpr GridSlot kBoundarySlots[12] = {{0, 0, 0},  {1, 1, 0},  {7, 2, 0},  {5, 3, 0},
                                         {2, 0, 1},  {6, 3, 1},  {16, 0, 2}, {12, 3, 2},
                                         {15, 0, 3}, {17, 1, 3}, {11, 2, 3}, {10, 3, 3}};

}  // namespace

SurfacePoint evaluateBezier(std::span<const glm::dvec3, kBezierPoints> points, double u, double v) {
  double bu[4], du[4], bv[4], dv[4];
  bernstein(u, bu, du);
  bernstein(v, bv, dv);
  SurfacePoint out;
  for (int j = 0; j < 4; ++j) {
    glm::dvec3 row(0.0), rowDu(0.0);
    for (int i = 0; i < 4; ++i) {
      row += bu[i] * points[4 * j + i];
      rowDu += du[i] * points[4 * j + i];
    }
    out.position += bv[j] * row;
    out.du += bv[j] * rowDu;
    out.dv += dv[j] * row;
  }
  return out;
}

std::array<glm::dvec3, kBezierPoints> gregoryToBezierAt(
    std::span<const glm::dvec3, kGregoryPoints> p, double u, double v) {
  std::array<glm::dvec3, kBezierPoints> b;
  for (const GridSlot& s : kBoundarySlots) b[4 * s.j + s.i] = p[s.gregory];

  // Rational weights of the face points (Osd_EvalBasisGregory: G[8] with the df guards, so
  // each pair sums to one even at the corners where the denominator vanishes).
  const double uc = 1.0 - u;
  const double vc = 1.0 - v;
  auto inv = [](double d) { return d <= 0.0 ? 1.0 : 1.0 / d; };
  const double g0 = u * inv(u + v);     // corner (0,0): Fp (3) weight
  const double g1 = v * inv(uc + v);    // corner (1,0): Fp (8) weight
  const double g2 = uc * inv(uc + vc);  // corner (1,1): Fp (13) weight
  const double g3 = vc * inv(u + vc);   // corner (0,1): Fp (18) weight
  b[4 * 1 + 1] = g0 * p[3] + (1.0 - g0) * p[4];
  b[4 * 1 + 2] = g1 * p[8] + (1.0 - g1) * p[9];
  b[4 * 2 + 2] = g2 * p[13] + (1.0 - g2) * p[14];
  b[4 * 2 + 1] = g3 * p[18] + (1.0 - g3) * p[19];
  return b;
}

SurfacePoint evaluateGregory(std::span<const glm::dvec3, kGregoryPoints> points, double u,
                             double v) {
  const std::array<glm::dvec3, kBezierPoints> frozen = gregoryToBezierAt(points, u, v);
  return evaluateBezier(frozen, u, v);
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
