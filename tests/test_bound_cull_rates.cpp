// Cull rates of TCONE, NCONE and the tangent plane on closed objects made of Bézier
// patches (a sphere with collapsed poles, a B-spline torus) and of Gregory TCONE on a
// Gregory sphere, over random "sphere" views (uniform directions, as in Loop et al. §7).
// Rates are printed; the assertions are conservativeness on every patch-view and sane
// lower bounds (a closed object shows about half its area back-facing).
#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/frustum.h"
#include "osd_cull/bound/sampling.h"
#include "osd_cull/bound/tangent_plane.h"
#include "test_bound_fixtures.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace osd_cull::bound {
namespace {

using test::Bezier;
using test::Gregory;
using test::Rng;

struct Rates {
  long patchViews = 0, oracle = 0, frustum = 0, tcone = 0, ncone = 0, tangentPlane = 0;
  void print(const char* shape, size_t patches, int views) const {
    auto pct = [&](long n) {
      return 100.0 * static_cast<double>(n) / static_cast<double>(patchViews);
    };
    std::printf(
        "%-16s %4zu patches x %d sphere views: truly back-facing %5.1f%%  frustum %5.1f%%  "
        "TCONE %5.1f%%  NCONE %5.1f%%  tangent plane %5.1f%%\n",
        shape, patches, views, pct(oracle), pct(frustum), pct(tcone), pct(ncone),
        pct(tangentPlane));
  }
  double rate(long n) const { return static_cast<double>(n) / static_cast<double>(patchViews); }
};

// A random view from a uniform direction at 2..6 radii, looking at the centre, wide enough
// to keep the object on screen.
test::View sphereView(Rng& rng, double radius) {
  const double dist = radius * rng.uniform(2.0, 6.0);
  const glm::dvec3 eye = dist * rng.direction();
  const double fovy = 2.2 * std::asin(radius / dist);
  glm::dmat4 proj = glm::perspective(fovy, 1.0, 0.1 * radius, dist + 2 * radius);
  proj[1][1] = -proj[1][1];  // Vulkan y flip
  return {proj * glm::lookAt(eye, glm::dvec3(0.0), rng.direction()), eye};
}

Rates bezierRates(const std::vector<Bezier>& patches, double radius, int views, uint64_t seed) {
  std::vector<SurfaceSamples> samples;
  std::vector<ConeOfNormals> ncones;  // NCONE: built once (static mesh)
  for (const Bezier& b : patches) {
    samples.push_back(samplePatch(b, 8));
    ncones.push_back(buildConeOfNormals(b));
  }
  Rng rng(seed);
  Rates r;
  for (int v = 0; v < views; ++v) {
    const test::View view = sphereView(rng, radius);
    const double sign = clipSpaceEyeSign(view.viewProj);
    for (size_t p = 0; p < patches.size(); ++p) {
      const bool front = anyFrontFacing(samples[p], view.eye);
      const bool tc = testConeOfNormals(buildConeFromTangentCones(patches[p]), view.eye).culled;
      const bool nc = testConeOfNormals(ncones[p], view.eye).culled;
      const bool tp = tangentPlaneTest(patches[p], view.viewProj, sign).culled;
      const bool fr = frustumTest(patches[p], view.viewProj).culled;
      EXPECT_FALSE(front && (tc || nc || tp))
          << "false back-patch cull, patch " << p << " view " << v;
      EXPECT_FALSE(fr && anyInsideClipVolume(samples[p], view.viewProj)) << "false frustum cull";
      ++r.patchViews;
      r.oracle += !front;
      r.tcone += tc;
      r.ncone += nc;
      r.tangentPlane += tp;
      r.frustum += fr;
    }
  }
  return r;
}

TEST(BoundCullRates, BezierSphereTangentPlaneCullsNearlyHalfOverSphereViews) {
  const std::vector<Bezier> sphere = test::bezierSphere(12, 8);
  const int views = 1000;
  const Rates r = bezierRates(sphere, 1.0, views, 31);
  r.print("Bézier sphere", sphere.size(), views);
  // About half the patches of a convex closed object face away; patches on the silhouette
  // are kept, so the rate is somewhat below one half.
  EXPECT_GT(r.rate(r.tangentPlane), 0.30);
  EXPECT_GT(r.rate(r.oracle), 0.35);
  EXPECT_LE(r.tangentPlane, r.oracle);
  EXPECT_GT(r.rate(r.ncone), 0.15);
  EXPECT_GT(r.rate(r.tcone), 0.0);
}

TEST(BoundCullRates, BsplineTorusCullRatesOverSphereViews) {
  const std::vector<Bezier> torus = test::bsplineTorus(16, 8);
  const int views = 600;
  const Rates r = bezierRates(torus, 1.4, views, 32);
  r.print("B-spline torus", torus.size(), views);
  EXPECT_GT(r.rate(r.tangentPlane), 0.30);
  EXPECT_LE(r.tangentPlane, r.oracle);
  EXPECT_GT(r.rate(r.ncone), 0.15);
}

TEST(BoundCullRates, GregorySphereIsCulledOnlyByAConservativeTangentCone) {
  Rng build(33);
  std::vector<Gregory> sphere;
  for (const Bezier& b : test::bezierSphere(12, 8))
    sphere.push_back(test::gregoryFromBezier(b, build, 0.01));
  std::vector<SurfaceSamples> samples;
  std::vector<ConeOfNormals> cones;
  for (const Gregory& g : sphere) {
    samples.push_back(samplePatch(g, 8));
    cones.push_back(buildGregoryConeFromTangentCones(g));
  }
  Rng rng(34);
  Rates r;
  const int views = 600;
  for (int v = 0; v < views; ++v) {
    const test::View view = sphereView(rng, 1.0);
    for (size_t p = 0; p < sphere.size(); ++p) {
      const bool front = anyFrontFacing(samples[p], view.eye);
      const bool tc = testConeOfNormals(cones[p], view.eye).culled;
      const bool fr = frustumTest(sphere[p], view.viewProj).culled;
      EXPECT_FALSE(front && tc) << "false Gregory TCONE cull, patch " << p << " view " << v;
      EXPECT_FALSE(fr && anyInsideClipVolume(samples[p], view.viewProj));
      ++r.patchViews;
      r.oracle += !front;
      r.tcone += tc;
      r.frustum += fr;
    }
  }
  std::printf(
      "%-16s %4zu patches x %d sphere views: truly back-facing %5.1f%%  frustum %5.1f%%  "
      "Gregory TCONE %5.1f%%\n",
      "Gregory sphere", sphere.size(), views, 100 * r.rate(r.oracle), 100 * r.rate(r.frustum),
      100 * r.rate(r.tcone));
  EXPECT_GT(r.rate(r.tcone), 0.10);
}

}  // namespace
}  // namespace osd_cull::bound
