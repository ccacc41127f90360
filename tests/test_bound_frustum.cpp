// Clip-space bounds and the view-frustum test (Sathe, Run-Time Step; homogeneous form).
#include "osd_cull/bound/frustum.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/bound/sampling.h"
#include "test_bound_fixtures.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <limits>

namespace osd_cull::bound {
namespace {

using test::Bezier;
using test::Rng;

// Camera at the origin looking down -z, 90° field of view, near 0.1, far 100.
glm::dmat4 simpleViewProj() {
  return glm::perspective(glm::radians(90.0), 1.0, 0.1, 100.0) *
         glm::lookAt(glm::dvec3(0.0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
}

// A flat 1x1 patch centred at `c`, facing +z.
Bezier flatPatch(const glm::dvec3& c, double size = 1.0) {
  Bezier b;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      b[4 * j + i] = c + size * glm::dvec3(i / 3.0 - 0.5, j / 3.0 - 0.5, 0.0);
  return b;
}

TEST(BoundFrustum, PatchInViewIsKeptWithAnNdcBoxAroundItsProjection) {
  const glm::dmat4 vp = simpleViewProj();
  const Bezier b = flatPatch({0.2, -0.1, -5.0});
  const ClipBounds cb = clipBounds(b, vp);
  EXPECT_TRUE(cb.finite);
  EXPECT_FALSE(cb.behindEye);
  EXPECT_TRUE(cb.hasNdcBox);
  EXPECT_EQ(cb.outsideAll, 0u);
  EXPECT_EQ(cb.outsideAny, 0u);
  // x/w of the corner at x = 0.2 - 0.5 at depth 5 with a 90° frustum: -0.06.
  EXPECT_NEAR(cb.ndcMin.x, -0.3 / 5.0, 1e-9);
  EXPECT_NEAR(cb.ndcMax.x, 0.7 / 5.0, 1e-9);
  EXPECT_FALSE(frustumTest(b, vp).culled);
}

TEST(BoundFrustum, PatchBesideTheFrustumIsCulledByThatPlane) {
  const glm::dmat4 vp = simpleViewProj();
  struct Case {
    glm::dvec3 centre;
    FrustumPlane plane;
  } cases[] = {{{-9, 0, -5}, FrustumPlane::Left},   {{9, 0, -5}, FrustumPlane::Right},
               {{0, -9, -5}, FrustumPlane::Bottom}, {{0, 9, -5}, FrustumPlane::Top},
               {{0, 0, -0.05}, FrustumPlane::Near}, {{0, 0, -200}, FrustumPlane::Far}};
  for (const Case& c : cases) {
    const Bezier b = flatPatch(c.centre, c.plane == FrustumPlane::Near ? 0.01 : 1.0);
    const FrustumResult r = frustumTest(b, vp);
    EXPECT_TRUE(r.culled) << static_cast<int>(c.plane);
    EXPECT_EQ(r.plane, static_cast<uint32_t>(c.plane));
  }
  // Straddling the left plane: kept, but some point is outside it.
  const Bezier straddle = flatPatch({-5.0, 0.0, -5.0});
  EXPECT_FALSE(frustumTest(straddle, vp).culled);
  EXPECT_NE(clipBounds(straddle, vp).outsideAny & 1u, 0u);
}

TEST(BoundFrustum, PatchBehindTheEyeIsCulledWithoutAnNdcBox) {
  const glm::dmat4 vp = simpleViewProj();
  // Behind the camera (z > 0): w < 0 for every point; x/w would flip the box.
  const Bezier behind = flatPatch({0.0, 0.0, 5.0});
  const ClipBounds cb = clipBounds(behind, vp);
  EXPECT_TRUE(cb.behindEye);
  EXPECT_FALSE(cb.hasNdcBox);
  const FrustumResult r = frustumTest(behind, vp);
  EXPECT_TRUE(r.culled);
  // Every point is outside the near plane (z < 0); with w < 0 and |x| < |w| each is also
  // outside both side planes (x < -w and x > w), so Left is the first plane reported.
  EXPECT_NE(cb.outsideAll & (1u << static_cast<uint32_t>(FrustumPlane::Near)), 0u);
  EXPECT_EQ(r.plane, static_cast<uint32_t>(FrustumPlane::Left));
  // Crossing the eye plane (z from -0.5 to 0.5 around the camera, offset sideways so
  // it is partly in view): kept, behindEye set, no box.
  Bezier crossing;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) crossing[4 * j + i] = {i / 3.0 - 0.5, -0.2, j / 3.0 - 0.5};
  const ClipBounds cc = clipBounds(crossing, vp);
  EXPECT_TRUE(cc.behindEye);
  EXPECT_FALSE(cc.hasNdcBox);
  EXPECT_FALSE(frustumTest(crossing, vp).culled);
}

TEST(BoundFrustum, NonFiniteInputIsKeptWithoutCrashing) {
  const glm::dmat4 vp = simpleViewProj();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {nan, inf, -inf}) {
    Bezier b = flatPatch({-9, 0, -5});  // would be culled
    b[7].y = bad;
    const FrustumResult r = frustumTest(b, vp);
    EXPECT_FALSE(r.culled);
    EXPECT_FALSE(r.finite);
    glm::dmat4 m = vp;
    m[1][2] = bad;
    EXPECT_FALSE(frustumTest(flatPatch({-9, 0, -5}), m).culled);
  }
  // Finite points whose clip coordinates overflow (the matrix scaled by 10 is the same
  // projection): kept, not culled on an infinity.
  const Bezier huge = flatPatch({-1e308, 0, -5});
  EXPECT_TRUE(frustumTest(huge, vp).culled);  // x = -1e308 is far left: a valid cull
  EXPECT_FALSE(frustumTest(huge, 10.0 * vp).culled);
  EXPECT_FALSE(clipBounds(huge, 10.0 * vp).finite);
}

// Sweeps random patches (Bézier and Gregory) and views; every culled patch must have no
// surface sample in the clip volume, and the NDC box must contain every sample it bounds.
void sweep(double scale, uint64_t seed, int* culledOut, int* testsOut) {
  Rng rng(seed);
  int culled = 0, tests = 0;
  for (int n = 0; n < 120; ++n) {
    const auto kind = static_cast<test::PatchKind>(n % static_cast<int>(test::PatchKind::Count));
    Bezier b = test::randomBezier(rng, kind);
    for (glm::dvec3& p : b) p *= scale;
    const test::Gregory g = test::gregoryFromBezier(b, rng, 0.2 * scale);
    const SurfaceSamples sb = samplePatch(b, 16), sg = samplePatch(g, 16);
    glm::dvec3 centre;
    double radius;
    test::boundingSphere(b, &centre, &radius);
    for (int k = 0; k < 40; ++k) {
      const auto vk = static_cast<test::ViewKind>(k % static_cast<int>(test::ViewKind::Count));
      const size_t s =
          static_cast<size_t>(rng.integer(0, static_cast<int>(sb.position.size()) - 1));
      const test::View view =
          test::randomView(rng, vk, centre, radius, sb.position[s], sb.normal[s]);
      for (int which = 0; which < 2; ++which) {
        const SurfaceSamples& samples = which == 0 ? sb : sg;
        const std::span<const glm::dvec3> pts =
            which == 0 ? std::span<const glm::dvec3>(b) : std::span<const glm::dvec3>(g);
        const FrustumResult r = frustumTest(pts, view.viewProj);
        ++tests;
        if (r.culled) {
          ++culled;
          ASSERT_FALSE(anyInsideClipVolume(samples, view.viewProj))
              << "false cull: patch " << n << " (" << test::name(kind) << ", "
              << (which ? "Gregory" : "Bézier") << ") view " << test::name(vk) << " plane "
              << r.plane;
        }
        const ClipBounds cb = clipBounds(pts, view.viewProj);
        if (!cb.hasNdcBox) continue;
        for (const glm::dvec3& p : samples.position) {
          const glm::dvec4 c = view.viewProj * glm::dvec4(p, 1.0);
          ASSERT_GT(c.w, 0.0);
          const glm::dvec3 ndc = glm::dvec3(c) / c.w;
          for (int a = 0; a < 3; ++a) {
            ASSERT_GE(ndc[a], cb.ndcMin[a] - 1e-9 * (1.0 + std::abs(ndc[a])));
            ASSERT_LE(ndc[a], cb.ndcMax[a] + 1e-9 * (1.0 + std::abs(ndc[a])));
          }
        }
      }
    }
  }
  *culledOut = culled;
  *testsOut = tests;
}

TEST(BoundFrustum, RandomPatchesAndViewsNeverCullAVisibleSample) {
  int culled = 0, tests = 0;
  sweep(1.0, 21, &culled, &tests);
  std::printf("frustum sweep: %d of %d patch-views culled (%.1f%%)\n", culled, tests,
              100.0 * culled / tests);
  EXPECT_EQ(tests, 120 * 40 * 2);
  // The views are built to miss patches often (looking away, crossing planes): the sweep
  // must exercise culling, not just keep everything.
  EXPECT_GT(culled, tests / 5);
}

TEST(BoundFrustum, ScalingTheSceneBy1eMinus4And1e5KeepsDecisions) {
  int c1 = 0, t1 = 0, cSmall = 0, tSmall = 0, cLarge = 0, tLarge = 0;
  sweep(1.0, 22, &c1, &t1);
  sweep(1e-4, 22, &cSmall, &tSmall);
  sweep(1e5, 22, &cLarge, &tLarge);
  std::printf("frustum culls at scale 1: %d, 1e-4: %d, 1e5: %d (of %d)\n", c1, cSmall, cLarge, t1);
  // Same random choices, scaled geometry and views: identical up to rare rounding ties.
  EXPECT_NEAR(cSmall, c1, 0.005 * c1 + 2);
  EXPECT_NEAR(cLarge, c1, 0.005 * c1 + 2);
}

}  // namespace
}  // namespace osd_cull::bound
