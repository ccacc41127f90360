// The parametric tangent plane table (Loop, Nießner, Eisenacher §3, §5, §6): derived in
// code, checked against the paper's published counts and against direct evaluation of
// cross4(B, Bu, Bv) in clip space; the factored form of the GPU kernel against the table.
#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/bound/tangent_plane.h"
#include "osd_cull/bound/tangent_plane_factored.h"
#include "osd_cull/bound/tangent_plane_table.h"
#include "test_bound_fixtures.h"

#include <gtest/gtest.h>
#include <glm/matrix.hpp>

#include <set>
#include <string>
#include <tuple>

namespace osd_cull::bound {
namespace {

using test::Bezier;
using test::Rng;

// The distribution matrix printed in §6: how many of the 516 terms write each target.
// Typed in from the paper only to check the derived table against the publication.
constexpr int kPaperTermsPerTarget[8][8] = {
    {1, 2, 4, 5, 5, 4, 2, 1},       {2, 4, 8, 10, 10, 8, 4, 2},     {4, 8, 11, 17, 17, 11, 8, 4},
    {5, 10, 17, 21, 21, 17, 10, 5}, {5, 10, 17, 21, 21, 17, 10, 5}, {4, 8, 11, 17, 17, 11, 8, 4},
    {2, 4, 8, 10, 10, 8, 4, 2},     {1, 2, 4, 5, 5, 4, 2, 1}};

TEST(BoundTangentPlaneTable, HasThe516TermsOfSection5WithThePaperDistribution) {
  const auto terms = tangentPlaneTerms();
  ASSERT_EQ(terms.size(), 516u);
  int count[64] = {};
  std::set<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>> seen;
  for (const TangentPlaneTerm& t : terms) {
    ASSERT_LT(t.target, 64u);
    ASSERT_LT(t.j, t.k);
    ASSERT_LT(t.k, t.l);
    ASSERT_LT(t.l, 16u);
    ASSERT_NE(t.numerator, 0);
    ASSERT_GT(t.denominator, 0);
    EXPECT_DOUBLE_EQ(t.weight, static_cast<double>(t.numerator) / t.denominator);
    EXPECT_TRUE(seen.insert({t.target, t.j, t.k, t.l}).second) << "duplicate term";
    ++count[t.target];
  }
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c)
      EXPECT_EQ(count[8 * r + c], kPaperTermsPerTarget[r][c]) << r << "," << c;
  // The corner plane: T(0,0) = cross4(b0, 3(b1 - b0), 3(b4 - b0)) = 9 cross4(b0, b1, b4).
  EXPECT_EQ(terms[0].target, 0u);
  EXPECT_EQ(std::tie(terms[0].j, terms[0].k, terms[0].l), std::make_tuple(0u, 1u, 4u));
  EXPECT_EQ(terms[0].numerator, 9);
  EXPECT_EQ(terms[0].denominator, 1);
}

TEST(BoundTangentPlaneTable, ParallelOrderGivesEachOfSixteenThreadsItsOwnFourTargets) {
  const auto serial = tangentPlaneTerms();
  const auto parallel = tangentPlaneParallelTerms();
  ASSERT_EQ(parallel.size() % kTangentPlaneThreads, 0u);
  const size_t slots = parallel.size() / kTangentPlaneThreads;
  EXPECT_EQ(slots, 33u);  // §6: "Each thread will need to loop 33 times"
  int perThread[16] = {};
  std::multiset<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>> real;
  for (size_t e = 0; e < parallel.size(); ++e) {
    const uint32_t thread = static_cast<uint32_t>(e % kTangentPlaneThreads);
    const TangentPlaneTerm& t = parallel[e];
    const uint32_t r = t.target / 8, c = t.target % 8;
    EXPECT_EQ(4 * (r % 4) + c % 4, thread) << "entry " << e << " writes another thread's target";
    if (t.weight != 0.0) {
      real.insert({t.target, t.j, t.k, t.l});
      ++perThread[thread];
    }
  }
  EXPECT_EQ(real.size(), serial.size());
  for (const TangentPlaneTerm& t : serial) EXPECT_EQ(real.count({t.target, t.j, t.k, t.l}), 1u);
  // §6's block sums: 32 33 33 32 / 33 31 31 33 / ...
  constexpr int kPaperBlockSums[16] = {32, 33, 33, 32, 33, 31, 31, 33,
                                       33, 31, 31, 33, 32, 33, 33, 32};
  for (int t = 0; t < 16; ++t) EXPECT_EQ(perThread[t], kPaperBlockSums[t]) << "thread " << t;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(BoundTangentPlaneTable, GlslTableListsEveryTermWithItsExactWeight) {
  for (bool parallel : {false, true}) {
    const std::string glsl = tangentPlaneTableGlsl(parallel);
    const size_t n = parallel ? tangentPlaneParallelTerms().size() : tangentPlaneTerms().size();
    EXPECT_EQ(occurrences(glsl, "uvec4("), n);  // the array constructor is "uvec4[]("
    EXPECT_NE(glsl.find("kTangentPlaneTermCount = " + std::to_string(n) + "u;"), std::string::npos);
    EXPECT_EQ(occurrences(glsl, ".0 / "), n);
  }
  const std::string serial = tangentPlaneTableGlsl(false);
  EXPECT_NE(serial.find("uvec4(0u, 0u, 1u, 4u)"), std::string::npos);  // 9 cross4(b0, b1, b4)
  EXPECT_NE(serial.find("9.0 / 1.0"), std::string::npos);
}

TEST(BoundTangentPlaneTable, Cross4IsTheOrientedPlaneThroughThreePoints) {
  Rng rng(11);
  for (int n = 0; n < 200; ++n) {
    const glm::dvec4 a(rng.inBox(2), rng.uniform(-2, 2)), b(rng.inBox(2), rng.uniform(-2, 2)),
        c(rng.inBox(2), rng.uniform(-2, 2)), x(rng.inBox(2), rng.uniform(-2, 2));
    const glm::dvec4 t = cross4(a, b, c);
    EXPECT_NEAR(glm::dot(x, t), glm::determinant(glm::dmat4(x, a, b, c)), 1e-12);
    EXPECT_NEAR(glm::dot(a, t), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(t.z, cross4Z(a, b, c));
  }
}

// Evaluates the control planes' z polynomial (bidegree 7) and its magnitude bound at (u, v).
std::pair<double, double> evaluatePlanes(const TangentPlaneControlPlanes& planes, double u,
                                         double v) {
  double z = 0.0, bound = 0.0;
  for (int q = 0; q < 8; ++q)
    for (int p = 0; p < 8; ++p) {
      const double w = bernstein(7, p, u) * bernstein(7, q, v);
      z += w * planes.z[8 * q + p];
      bound += w * planes.bound[8 * q + p];
    }
  return {z, bound};
}

TEST(BoundTangentPlaneTable, ControlPlanesMatchDirectCross4OfClipSpaceBAndDerivatives) {
  Rng rng(12);
  int checked = 0;
  for (int n = 0; n < 300; ++n) {
    const auto kind = static_cast<test::PatchKind>(n % static_cast<int>(test::PatchKind::Count));
    const Bezier b = test::randomBezier(rng, kind);
    glm::dvec3 centre;
    double radius;
    test::boundingSphere(b, &centre, &radius);
    const auto vk = static_cast<test::ViewKind>(rng.integer(0, 4));
    const PatchSample mid = evaluateBezier(b, 0.5, 0.5);
    const test::View view =
        test::randomView(rng, vk, centre, radius, mid.position, glm::cross(mid.du, mid.dv));
    const TangentPlaneControlPlanes serial = tangentPlaneControlPlanes(b, view.viewProj);
    const TangentPlaneControlPlanes parallel = tangentPlaneControlPlanesParallel(b, view.viewProj);
    for (int i = 0; i < 64; ++i)
      ASSERT_NEAR(serial.z[i], parallel.z[i], 1e-13 * serial.bound[i] + 1e-300);
    const glm::dvec4 eyeH = homogeneousEye(view.viewProj);
    for (int s = 0; s < 20; ++s) {
      const double u = rng.uniform(), v = rng.uniform();
      const PatchSample p = evaluateBezier(b, u, v);
      // Direct: cross4Z of the clip-space point and derivatives (derivatives have w = 0).
      const double direct =
          cross4Z(view.viewProj * glm::dvec4(p.position, 1.0),
                  view.viewProj * glm::dvec4(p.du, 0.0), view.viewProj * glm::dvec4(p.dv, 0.0));
      const auto [viaTable, bound] = evaluatePlanes(serial, u, v);
      ASSERT_NEAR(viaTable, direct, 1e-10 * bound) << "patch " << n << " (u,v) = " << u << "," << v;
      // §4.1: T'_z = e·T = e.w * dot(N, E - B) with e the homogeneous eye.
      const glm::dvec3 eye = glm::dvec3(eyeH) / eyeH.w;
      const double world = eyeH.w * glm::dot(glm::cross(p.du, p.dv), eye - p.position);
      ASSERT_NEAR(viaTable, world, 1e-8 * bound);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 6000);
}

TEST(BoundTangentPlaneTable, EyeOfAViewProjectionIsTheCameraCentre) {
  Rng rng(13);
  for (int n = 0; n < 500; ++n) {
    const auto vk = static_cast<test::ViewKind>(n % 5);
    const test::View view = test::randomView(rng, vk, rng.inBox(3), rng.uniform(0.1, 10.0),
                                             rng.inBox(3), rng.direction());
    const auto eye = eyePosition(view.viewProj);
    ASSERT_TRUE(eye.has_value());
    EXPECT_NEAR(glm::length(*eye - view.eye), 0.0, 1e-7 * (1.0 + glm::length(view.eye)));
    EXPECT_NE(clipSpaceEyeSign(view.viewProj), 0.0);
  }
  // Orthographic: the eye is at infinity, the tangent-plane test has no sign to use.
  const glm::dmat4 ortho = glm::ortho(-1.0, 1.0, -1.0, 1.0, 0.1, 10.0);
  EXPECT_EQ(clipSpaceEyeSign(ortho), 0.0);
  EXPECT_FALSE(eyePosition(ortho).has_value());
  glm::dmat4 bad(1.0);
  bad[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(clipSpaceEyeSign(bad), 0.0);
}

TEST(BoundTangentPlaneTable, CollapsedEdgeGivesExactlyZeroPlanesAlongIt) {
  Rng rng(14);
  for (int n = 0; n < 50; ++n) {
    const Bezier b = test::randomBezier(rng, test::PatchKind::CollapsedEdge);
    ASSERT_EQ(b[0], b[3]);
    const test::View view = test::randomView(rng, test::ViewKind::Around, glm::dvec3(0.0), 3.0,
                                             glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0));
    const TangentPlaneControlPlanes planes = tangentPlaneControlPlanes(b, view.viewProj);
    for (int p = 0; p < 8; ++p) {
      EXPECT_EQ(planes.z[p], 0.0) << "plane " << p;  // row v = 0
      EXPECT_EQ(planes.bound[p], 0.0);
    }
    int nonzero = 0;
    for (int i = 8; i < 64; ++i) nonzero += planes.z[i] != 0.0;
    EXPECT_GT(nonzero, 50);
  }
}

// The table's world-space coefficients F_i = Σ w (E - b_j)·((b_k - b_j) × (b_l - b_j)), with
// the terms of equal points skipped as the reference does, and Σ |w| |products| of each.
std::pair<std::array<double, 64>, std::array<double, 64>> tableWorldCoefficients(
    const Bezier& b, const glm::dvec3& eye) {
  std::array<double, 64> f{}, m{};
  for (const TangentPlaneTerm& t : tangentPlaneTerms()) {
    if (b[t.j] == b[t.k] || b[t.k] == b[t.l] || b[t.j] == b[t.l]) continue;
    const glm::dvec3 q = eye - b[t.j], dk = b[t.k] - b[t.j], dl = b[t.l] - b[t.j];
    f[t.target] += t.weight * glm::dot(q, glm::cross(dk, dl));
    m[t.target] += std::abs(t.weight) * glm::length(q) * glm::length(dk) * glm::length(dl);
  }
  return {f, m};
}

TEST(BoundTangentPlaneFactored, EqualsTheTableCoefficientsForEveryPatchKindAndEye) {
  Rng rng(15);
  for (int n = 0; n < 400; ++n) {
    const auto kind = static_cast<test::PatchKind>(n % static_cast<int>(test::PatchKind::Count));
    const Bezier b = test::randomBezier(rng, kind);
    const glm::dvec3 eye = rng.inBox(n % 2 ? 4.0 : 50.0);
    const auto [f, m] = tableWorldCoefficients(b, eye);
    const TangentPlaneFactored factored = tangentPlaneFactored(b, eye);
    for (int q = 0; q < 8; ++q)
      for (int p = 0; p < 8; ++p) {
        const size_t i = static_cast<size_t>(8 * q + p);
        const double scale = tangentPlaneFactoredScale(p, q);
        ASSERT_NEAR(factored.d[i] / scale, f[i], 1e-11 * (m[i] + factored.bound[i] / scale))
            << test::name(kind) << " patch " << n << " coefficient " << i;
        // The bound bounds the coefficient and vanishes with it along collapsed edges.
        ASSERT_LE(std::abs(factored.d[i]), factored.bound[i] * (1 + 1e-12));
        if (m[i] == 0.0) {
          ASSERT_EQ(factored.bound[i], 0.0) << "coefficient " << i;
        }
      }
  }
}

// Coefficients marked `collapsed` (a boundary of four equal points) must be exactly 0 with
// every table term skipped, so that the kernel may give them margin 0 as the reference
// does (Pcnt); other zero bounds happen (exact cancellation of unskipped terms) and the
// kernel must count those as possibly positive. Adjacent points merged at random.
TEST(BoundTangentPlaneFactored, CollapsedBoundariesAreExactlyZeroAsInTheReference) {
  Rng rng(16);
  int collapsed = 0, otherZeroBounds = 0;
  for (int n = 0; n < 3000; ++n) {
    Bezier b = test::randomBezier(rng, test::PatchKind::SmoothBump);
    const int merges = rng.integer(1, 8);
    for (int k = 0; k < merges; ++k) {
      const int i = rng.integer(0, 3), j = rng.integer(0, 3);
      const bool alongU = rng.integer(0, 1) == 0;
      const int i2 = alongU ? std::min(i + 1, 3) : i, j2 = alongU ? j : std::min(j + 1, 3);
      b[static_cast<size_t>(4 * j2 + i2)] = b[static_cast<size_t>(4 * j + i)];
    }
    if (n % 3 == 0)  // a whole boundary collapsed, as at the teapot's poles
      for (int k = 1; k < 4; ++k)
        b[static_cast<size_t>(n % 2 ? 4 * k : 12 + k)] = b[n % 2 ? 0 : 12];
    const glm::dvec3 eye = rng.inBox(5.0);
    const auto [f, m] = tableWorldCoefficients(b, eye);
    const TangentPlaneFactored factored = tangentPlaneFactored(b, eye);
    for (size_t i = 0; i < 64; ++i) {
      if (factored.collapsed[i]) {
        ++collapsed;
        ASSERT_EQ(factored.bound[i], 0.0) << "patch " << n << " coefficient " << i;
        ASSERT_EQ(factored.d[i], 0.0);
        ASSERT_EQ(m[i], 0.0);
      } else if (factored.bound[i] == 0.0) {
        ++otherZeroBounds;
        ASSERT_EQ(factored.d[i], 0.0);
      }
    }
  }
  EXPECT_GT(collapsed, 5000);
  EXPECT_GT(otherZeroBounds, 100);
}

}  // namespace
}  // namespace osd_cull::bound
