// B-spline → Bézier conversion with OpenSubdiv's boundary extrapolation, and the
// double-precision evaluation of Bézier and Gregory patches.
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/patch_eval.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <random>

namespace osd_cull {
namespace {

std::array<glm::dvec3, 16> randomPoints(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::array<glm::dvec3, 16> p;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      p[4 * j + i] = glm::dvec3(i, j, 0.0) + 0.4 * glm::dvec3(uni(rng), uni(rng), uni(rng));
  return p;
}

// Uniform cubic B-spline basis (independent of the conversion matrices).
void bsplineBasis(double t, double b[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
  b[2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
  b[3] = t * t * t / 6.0;
}

glm::dvec3 evalBSpline(const std::array<glm::dvec3, 16>& p, double u, double v) {
  double bu[4], bv[4];
  bsplineBasis(u, bu);
  bsplineBasis(v, bv);
  glm::dvec3 out(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) out += bu[i] * bv[j] * p[4 * j + i];
  return out;
}

glm::dvec3 evalCurve(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                     const glm::dvec3& d, double t) {
  double w[4];
  bsplineBasis(t, w);
  return w[0] * a + w[1] * b + w[2] * c + w[3] * d;
}

TEST(BSplineToBezier, InteriorPatchIsTheSameSurface) {
  const auto cv = randomPoints(1);
  const auto bez = bsplineToBezier(cv, 0);
  for (double u : {0.0, 0.21, 0.5, 0.93, 1.0})
    for (double v : {0.0, 0.37, 0.66, 1.0})
      EXPECT_LE(glm::length(evaluateBezier(bez, u, v).position - evalBSpline(cv, u, v)), 1e-14)
          << u << " " << v;
}

TEST(BSplineToBezier, BoundaryEdgeInterpolatesTheRowNextToIt) {
  // With the v = 0 edge on the boundary (bit 0), the limit curve at v = 0 is the B-spline
  // curve of row 1: the extrapolated row 0 = 2 * row 1 - row 2 makes (r0 + 4 r1 + r2) / 6 = r1.
  const auto cv = randomPoints(2);
  const auto bez = bsplineToBezier(cv, 1u);
  for (double u : {0.0, 0.3, 0.8, 1.0})
    EXPECT_LE(glm::length(evaluateBezier(bez, u, 0.0).position -
                          evalCurve(cv[4], cv[5], cv[6], cv[7], u)),
              1e-14);
  // Bit 1: the u = 1 edge interpolates column 2.
  const auto bez2 = bsplineToBezier(cv, 2u);
  for (double v : {0.0, 0.45, 1.0})
    EXPECT_LE(glm::length(evaluateBezier(bez2, 1.0, v).position -
                          evalCurve(cv[2], cv[6], cv[10], cv[14], v)),
              1e-14);
  // Corner (bits 0 and 3): the corner point is the inner point 5.
  EXPECT_LE(glm::length(evaluateBezier(bsplineToBezier(cv, 9u), 0.0, 0.0).position - cv[5]), 1e-14);
}

TEST(BSplineToBezier, StoredDuplicatesBeyondTheBoundaryAreIgnored) {
  const auto cv = randomPoints(3);
  for (unsigned mask = 1; mask < 16; ++mask) {
    auto other = cv;
    // Overwrite every point on a boundary row/column with junk: the result must not change.
    for (int k = 0; k < 16; ++k) {
      const int i = k % 4, j = k / 4;
      const bool outside = ((mask & 1u) && j == 0) || ((mask & 2u) && i == 3) ||
                           ((mask & 4u) && j == 3) || ((mask & 8u) && i == 0);
      if (outside) other[k] = glm::dvec3(1e3, -7e2, 5e2);
    }
    const auto a = bsplineToBezier(cv, mask), b = bsplineToBezier(other, mask);
    for (int k = 0; k < 16; ++k)
      EXPECT_LE(glm::length(a[k] - b[k]), 1e-10) << "mask " << mask << " point " << k;
  }
}

TEST(BSplineToBezier, WeightTableMatchesThePointConversionAndIsAffine) {
  const auto cv = randomPoints(4);
  for (unsigned mask = 0; mask < 16; ++mask) {
    const PatchConversion& w = bsplineToBezierWeights(mask);
    const auto direct = bsplineToBezier(cv, mask);
    for (int r = 0; r < 16; ++r) {
      glm::dvec3 p(0.0);
      double sum = 0.0;
      for (int k = 0; k < 16; ++k) {
        p += w[r][k] * cv[k];
        sum += w[r][k];
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << mask << " " << r;
      EXPECT_LE(glm::length(p - direct[r]), 1e-13) << mask << " " << r;
    }
  }
  // Bits above the fourth (triangle patches) do not change the quad conversion.
  EXPECT_EQ(bsplineToBezierWeights(16u | 5u), bsplineToBezierWeights(5u));
}

TEST(BezierEval, DerivativesMatchFiniteDifferences) {
  const auto p = randomPoints(5);
  const double h = 1e-6;
  for (double u : {0.1, 0.5, 0.77})
    for (double v : {0.2, 0.9}) {
      const SurfacePoint s = evaluateBezier(p, u, v);
      const glm::dvec3 fu =
          (evaluateBezier(p, u + h, v).position - evaluateBezier(p, u - h, v).position) / (2 * h);
      const glm::dvec3 fv =
          (evaluateBezier(p, u, v + h).position - evaluateBezier(p, u, v - h).position) / (2 * h);
      EXPECT_LE(glm::length(s.du - fu), 1e-8);
      EXPECT_LE(glm::length(s.dv - fv), 1e-8);
    }
  // Corner interpolation.
  EXPECT_EQ(evaluateBezier(p, 0.0, 0.0).position, p[0]);
  EXPECT_LE(glm::length(evaluateBezier(p, 1.0, 1.0).position - p[15]), 1e-15);
}

// A Gregory patch whose face-point pairs coincide is the Bézier patch with those points.
std::array<glm::dvec3, 20> gregoryFromBezier(const std::array<glm::dvec3, 16>& b) {
  // Corner c: P, Ep, Em, Fp, Fm (OpenSubdiv Gregory basis order, patch_set.h).
  auto at = [&](int i, int j) { return b[4 * j + i]; };
  return {at(0, 0), at(1, 0), at(0, 1), at(1, 1), at(1, 1),   // corner (0,0)
          at(3, 0), at(3, 1), at(2, 0), at(2, 1), at(2, 1),   // corner (1,0)
          at(3, 3), at(2, 3), at(3, 2), at(2, 2), at(2, 2),   // corner (1,1)
          at(0, 3), at(0, 2), at(1, 3), at(1, 2), at(1, 2)};  // corner (0,1)
}

TEST(GregoryEval, CoincidentFacePointsGiveTheBezierPatch) {
  const auto b = randomPoints(6);
  const auto g = gregoryFromBezier(b);
  for (double u : {0.0, 0.15, 0.5, 1.0})
    for (double v : {0.0, 0.6, 1.0}) {
      const SurfacePoint sb = evaluateBezier(b, u, v), sg = evaluateGregory(g, u, v);
      EXPECT_LE(glm::length(sb.position - sg.position), 1e-14);
      EXPECT_LE(glm::length(sb.du - sg.du), 1e-13);
      EXPECT_LE(glm::length(sb.dv - sg.dv), 1e-13);
    }
}

TEST(GregoryEval, FacePointsBlendByDistanceToTheirEdges) {
  auto g = gregoryFromBezier(randomPoints(7));
  // Corner (0,0): Fp (3) has weight u / (u + v): it alone counts on the edge v = 0, Fm (4)
  // alone on the edge u = 0 (Osd_EvalBasisGregory).
  g[3] += glm::dvec3(0, 0, 1);
  const auto onEdge = gregoryToBezierAt(g, 0.4, 0.0);
  EXPECT_EQ(onEdge[5], g[3]);
  const auto onOther = gregoryToBezierAt(g, 0.0, 0.4);
  EXPECT_EQ(onOther[5], g[4]);
  // At the corner itself both weights are guarded (no NaN) and sum to one.
  const auto atCorner = gregoryToBezierAt(g, 0.0, 0.0);
  EXPECT_TRUE(glm::all(glm::equal(atCorner[5], atCorner[5])));
  // Inside, each Gregory point still has its place: corners are interpolated.
  EXPECT_EQ(evaluateGregory(g, 0.0, 0.0).position, g[0]);
  EXPECT_LE(glm::length(evaluateGregory(g, 1.0, 0.0).position - g[5]), 1e-15);
  EXPECT_LE(glm::length(evaluateGregory(g, 1.0, 1.0).position - g[10]), 1e-15);
  EXPECT_LE(glm::length(evaluateGregory(g, 0.0, 1.0).position - g[15]), 1e-15);
}

TEST(GregoryEval, ExactDerivativesAreThoseOfTheRationalSurface) {
  auto g = gregoryFromBezier(randomPoints(8));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> uni(-0.3, 0.3);
  for (int k : {3, 4, 8, 9, 13, 14, 18, 19}) g[k] += glm::dvec3(uni(rng), uni(rng), uni(rng));
  const double h = 1e-6;
  double conventionGap = 0.0;
  for (double u : {0.1, 0.45, 0.8})
    for (double v : {0.25, 0.7}) {
      const SurfacePoint exact = evaluateGregoryExact(g, u, v);
      const SurfacePoint osd = evaluateGregory(g, u, v);
      EXPECT_EQ(exact.position, osd.position);
      const glm::dvec3 fu =
          (evaluateGregory(g, u + h, v).position - evaluateGregory(g, u - h, v).position) / (2 * h);
      const glm::dvec3 fv =
          (evaluateGregory(g, u, v + h).position - evaluateGregory(g, u, v - h).position) / (2 * h);
      EXPECT_LE(glm::length(exact.du - fu), 1e-8);
      EXPECT_LE(glm::length(exact.dv - fv), 1e-8);
      conventionGap = std::max(conventionGap, glm::length(osd.du - exact.du));
    }
  // OpenSubdiv's convention omits the multipliers' derivatives: it differs where Fp != Fm.
  EXPECT_GT(conventionGap, 1e-3);
}

TEST(PatchEval, RejectsPatchOutOfRange) {
  PatchSet set;
  EXPECT_THROW(evaluatePatch(set, 0, 0.5, 0.5), std::runtime_error);
}

}  // namespace
}  // namespace osd_cull
