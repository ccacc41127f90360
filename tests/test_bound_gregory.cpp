// Gregory patches: evaluation against OpenSubdiv, frustum culling on the 20 points and the
// conservative Gregory TCONE (tangent cones including the rational blend derivatives).
#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/frustum.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/bound/sampling.h"
#include "test_bound_fixtures.h"
#include "test_patch_support.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace osd_cull::bound {
namespace {

using test::Bezier;
using test::Gregory;
using test::Rng;

TEST(BoundGregory, EvaluationMatchesOpenSubdivOnTheGregoryPatchesOfACube) {
  const CageMesh cube = scene::cube();
  const test::CagePatches patches = test::cagePatches(cube, 2);
  const PatchSet& set = patches.extraction.patches;
  PatchOptions options;
  options.isolationLevel = 2;
  const osd_cull::test::OsdReference osd(cube, options);
  Rng rng(41);
  int checked = 0;
  for (uint32_t p = set.bezierCount; p < set.patchCount(); ++p) {
    const Gregory& g = patches.gregory.at(p - set.bezierCount);
    for (int s = 0; s < 8; ++s) {
      const double u = rng.uniform(), v = rng.uniform();
      SurfacePoint expected;  // OpenSubdiv's own basis on its own patch
      ASSERT_TRUE(osd.evaluate(set.params[p], u, v, expected)) << "patch " << p;
      const PatchSample mine = evaluateGregory(g, u, v);
      EXPECT_NEAR(glm::length(mine.position - expected.position), 0.0, 1e-6);
      // True derivatives: central differences of the positions.
      const double h = 1e-6;
      const glm::dvec3 fdU =
          (evaluateGregory(g, u + h, v).position - evaluateGregory(g, u - h, v).position) / (2 * h);
      const glm::dvec3 fdV =
          (evaluateGregory(g, u, v + h).position - evaluateGregory(g, u, v - h).position) / (2 * h);
      EXPECT_NEAR(glm::length(mine.du - fdU), 0.0, 1e-6 * (1.0 + glm::length(fdU)));
      EXPECT_NEAR(glm::length(mine.dv - fdV), 0.0, 1e-6 * (1.0 + glm::length(fdV)));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 24 * 8) << "a cube at level 2 has 3 Gregory patches at each of its 8 corners";
}

TEST(BoundGregory, GregoryWithEqualInteriorPairsIsTheBezierPatch) {
  Rng rng(42);
  for (int n = 0; n < 50; ++n) {
    const Bezier b = test::randomBezier(rng, test::PatchKind::SmoothBump);
    const Gregory g = test::gregoryFromBezier(b, rng, 0.0);
    for (int s = 0; s < 10; ++s) {
      const double u = rng.uniform(), v = rng.uniform();
      const PatchSample pb = evaluateBezier(b, u, v), pg = evaluateGregory(g, u, v);
      EXPECT_NEAR(glm::length(pb.position - pg.position), 0.0, 1e-12);
      EXPECT_NEAR(glm::length(pb.du - pg.du), 0.0, 1e-11);
      EXPECT_NEAR(glm::length(pb.dv - pg.dv), 0.0, 1e-11);
    }
  }
}

TEST(BoundGregory, BlendDerivativeWeightsAreAtMostOneThird) {
  // The bound behind the Gregory tangent cone: B_i(u) B_j(v) |a_u b - a b_u| / (a + b)²
  // <= 1/3 on the unit square for the four interior blends, along u and along v.
  double worst = 0.0;
  for (int y = 0; y <= 400; ++y)
    for (int x = 0; x <= 400; ++x) {
      const double u = x / 400.0, v = y / 400.0;
      for (const GregoryInterior& g : kGregoryInterior) {
        const double a = g.a0 + g.as * u + g.at * v, b = g.b0 + g.bs * u + g.bt * v;
        if (!(a + b > 0.0)) continue;
        const double w = bernstein(3, g.i, u) * bernstein(3, g.j, v) / ((a + b) * (a + b));
        worst =
            std::max({worst, w * std::abs(g.as * b - a * g.bs), w * std::abs(g.at * b - a * g.bt)});
      }
    }
  EXPECT_LE(worst, 1.0 / 3.0);
  EXPECT_GT(worst, 0.2);  // the bound is not vacuous
}

// Cone facts the cull test rests on: every sampled normal within the half-angle of the
// axis, every sampled point inside the apex cone.
void expectConeBounds(const ConeOfNormals& cone, const SurfaceSamples& s) {
  if (!cone.valid) return;
  const double cosGamma = std::sqrt(1.0 - cone.sinAngle * cone.sinAngle);
  for (size_t k = 0; k < s.position.size(); ++k) {
    const double len = glm::length(s.normal[k]);
    if (len > 1e-9 * s.tangentScale[k]) {
      ASSERT_GE(glm::dot(s.normal[k] / len, cone.axis), cosGamma - 1e-9) << "normal " << k;
    }
    const glm::dvec3 d = s.position[k] - cone.apex;
    ASSERT_GE(glm::dot(d, cone.axis), glm::length(d) * (cone.sinAngle - 1e-9)) << "point " << k;
  }
}

TEST(BoundGregory, RandomGregoryPatchesAndViewsNeverCullAVisibleSample) {
  Rng rng(43);
  long views = 0, oracle = 0, tcone = 0, frustum = 0, validCones = 0;
  for (int n = 0; n < 150; ++n) {
    const auto kind = static_cast<test::PatchKind>(n % static_cast<int>(test::PatchKind::Count));
    const double split = std::pow(10.0, rng.uniform(-3.0, -0.5));
    const Gregory g = test::gregoryFromBezier(test::randomBezier(rng, kind), rng, split);
    const SurfaceSamples s = samplePatch(g, 24);
    const ConeOfNormals cone = buildGregoryConeFromTangentCones(g);
    validCones += cone.valid;
    expectConeBounds(cone, s);
    if (HasFatalFailure()) return;
    glm::dvec3 centre;
    double radius;
    test::boundingSphere(g, &centre, &radius);
    for (int k = 0; k < 60; ++k) {
      const auto vk = static_cast<test::ViewKind>(k % static_cast<int>(test::ViewKind::Count));
      const size_t at =
          static_cast<size_t>(rng.integer(0, static_cast<int>(s.position.size()) - 1));
      const test::View view =
          test::randomView(rng, vk, centre, radius, s.position[at], s.normal[at]);
      const bool front = anyFrontFacing(s, view.eye);
      const bool culled = testConeOfNormals(cone, view.eye).culled;
      const bool outside = frustumTest(g, view.viewProj).culled;
      ASSERT_FALSE(culled && front) << "Gregory TCONE false cull, patch " << n << " view " << k;
      ASSERT_FALSE(outside && anyInsideClipVolume(s, view.viewProj)) << "frustum false cull";
      ++views;
      oracle += !front;
      tcone += culled;
      frustum += outside;
    }
  }
  std::printf(
      "random Gregory patches: %ld patch-views, truly back-facing %.1f%%, Gregory TCONE "
      "%.1f%%, frustum %.1f%%, valid cones %ld of 150\n",
      views, 100.0 * oracle / views, 100.0 * tcone / views, 100.0 * frustum / views, validCones);
  EXPECT_GT(tcone, 0);
  EXPECT_GT(frustum, 0);
}

TEST(BoundGregory, OpenSubdivCubeGregoryPatchesAreCulledConservatively) {
  const std::vector<Gregory> patches = test::cagePatches(scene::cube(), 2).gregory;
  ASSERT_GE(patches.size(), 24u);
  std::vector<SurfaceSamples> samples;
  std::vector<ConeOfNormals> cones;
  for (const Gregory& g : patches) {
    samples.push_back(samplePatch(g, 12));
    cones.push_back(buildGregoryConeFromTangentCones(g));
    expectConeBounds(cones.back(), samples.back());
  }
  Rng rng(44);
  long views = 0, oracle = 0, culled = 0;
  for (int v = 0; v < 500; ++v) {
    const glm::dvec3 eye = rng.uniform(1.5, 6.0) * rng.direction();
    for (size_t p = 0; p < patches.size(); ++p) {
      const bool front = anyFrontFacing(samples[p], eye);
      const bool c = testConeOfNormals(cones[p], eye).culled;
      ASSERT_FALSE(c && front) << "patch " << p;
      ++views;
      oracle += !front;
      culled += c;
    }
  }
  std::printf(
      "OpenSubdiv cube (level 2), %zu Gregory patches x 500 views: truly back-facing "
      "%.1f%%, Gregory TCONE %.1f%%\n",
      patches.size(), 100.0 * oracle / views, 100.0 * culled / views);
  EXPECT_GT(culled, views / 10);
}

}  // namespace
}  // namespace osd_cull::bound
