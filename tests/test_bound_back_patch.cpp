// Back-patch tests (TCONE, NCONE, parametric tangent plane): no culled patch may have a
// front-facing point on a dense sampling of its surface, in any view; degenerate input.
#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/frustum.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/bound/sampling.h"
#include "osd_cull/bound/tangent_plane.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural.h"
#include "support/test_data.h"
#include "test_bound_fixtures.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace osd_cull::bound {
namespace {

using test::Bezier;
using test::Rng;

enum Method { kTcone, kNcone, kTangentPlane, kMethods };
const char* kMethodName[kMethods] = {"TCONE", "NCONE", "tangent plane"};

// Every normal sample lies within the cone's angle of its axis, and every surface sample
// lies in the apex cone (within 90° - γ of the axis seen from the apex): the two facts the
// cone test's conservativeness rests on.
void expectConeBoundsSamples(const ConeOfNormals& cone, const SurfaceSamples& s, const char* what) {
  if (!cone.valid) return;
  const double cosGamma = std::sqrt(1.0 - cone.sinAngle * cone.sinAngle);
  for (size_t k = 0; k < s.position.size(); ++k) {
    const double len = glm::length(s.normal[k]);
    if (len > 1e-9 * s.tangentScale[k]) {
      ASSERT_GE(glm::dot(s.normal[k] / len, cone.axis), cosGamma - 1e-9) << what << " normal " << k;
    }
    const glm::dvec3 d = s.position[k] - cone.apex;
    // angle(d, axis) <= 90° - γ  <=>  dot(d, axis) >= |d| sin γ
    ASSERT_GE(glm::dot(d, cone.axis), glm::length(d) * cone.sinAngle - 1e-9 * glm::length(d))
        << what << " point " << k;
  }
}

struct Tally {
  long views = 0;
  long oracle = 0;  // patch-views with no front-facing sample
  long culled[kMethods] = {};
  long pcntOnly = 0;  // tangent-plane culls the paper's Ncnt = 64 rule would miss
};

// Runs the three methods on one patch and view, checks every cull against the samples.
void check(const Bezier& b, const SurfaceSamples& samples, const ConeOfNormals& tcone,
           const ConeOfNormals& ncone, const test::View& view, Tally* t, const char* where) {
  const bool front = anyFrontFacing(samples, view.eye);
  ++t->views;
  t->oracle += !front;
  const BackPatchResult rt = testConeOfNormals(tcone, view.eye);
  const BackPatchResult rn = testConeOfNormals(ncone, view.eye);
  const TangentPlaneResult rp = tangentPlaneTest(b, view.viewProj, clipSpaceEyeSign(view.viewProj));
  ASSERT_FALSE(rt.culled && front) << "TCONE false cull: " << where;
  ASSERT_FALSE(rn.culled && front) << "NCONE false cull: " << where;
  ASSERT_FALSE(rp.culled && front)
      << "tangent-plane false cull: " << where << " pcnt " << rp.pcnt << " ncnt " << rp.ncnt;
  t->culled[kTcone] += rt.culled;
  t->culled[kNcone] += rn.culled;
  t->culled[kTangentPlane] += rp.culled;
  t->pcntOnly += rp.culled && rp.ncnt < 64;
}

Tally sweepKind(test::PatchKind kind, double scale, uint64_t seed, int patches, int views) {
  Rng rng(seed);
  Tally t;
  for (int n = 0; n < patches; ++n) {
    Bezier b = test::randomBezier(rng, kind);
    for (glm::dvec3& p : b) p *= scale;
    const SurfaceSamples s = samplePatch(b, 24);
    const ConeOfNormals tcone = buildConeFromTangentCones(b);
    const ConeOfNormals ncone = buildConeOfNormals(b);
    expectConeBoundsSamples(tcone, s, "TCONE");
    expectConeBoundsSamples(ncone, s, "NCONE");
    glm::dvec3 centre;
    double radius;
    test::boundingSphere(b, &centre, &radius);
    for (int k = 0; k < views; ++k) {
      const auto vk = static_cast<test::ViewKind>(k % static_cast<int>(test::ViewKind::Count));
      const size_t at =
          static_cast<size_t>(rng.integer(0, static_cast<int>(s.position.size()) - 1));
      const test::View view =
          test::randomView(rng, vk, centre, radius, s.position[at], s.normal[at]);
      const std::string where = std::string(test::name(kind)) + " patch " + std::to_string(n) +
                                " view " + std::to_string(k) + " (" + test::name(vk) + ")";
      check(b, s, tcone, ncone, view, &t, where.c_str());
      if (::testing::Test::HasFatalFailure()) return t;
    }
  }
  return t;
}

void print(const char* label, const Tally& t) {
  std::printf(
      "%-16s views %6ld  truly back-facing %5.1f%%  TCONE %5.1f%%  NCONE %5.1f%%  "
      "tangent plane %5.1f%% (Pcnt-only %ld)\n",
      label, t.views, 100.0 * t.oracle / t.views, 100.0 * t.culled[kTcone] / t.views,
      100.0 * t.culled[kNcone] / t.views, 100.0 * t.culled[kTangentPlane] / t.views, t.pcntOnly);
}

TEST(BoundBackPatch, RandomPatchesAndViewsNeverCullAFrontFacingSample) {
  Tally all;
  for (int k = 0; k < static_cast<int>(test::PatchKind::Count); ++k) {
    const auto kind = static_cast<test::PatchKind>(k);
    const Tally t = sweepKind(kind, 1.0, 100 + k, 60, 100);
    if (HasFatalFailure()) return;
    print(test::name(kind), t);
    // The sweep exercises culling, not just "keep": the tangent plane finds most of the
    // patch-views that are truly back-facing on the samples (fewer on folded random nets,
    // where sign changes of the degree-7 control planes need not mean a silhouette).
    const double found = kind == test::PatchKind::RandomNet ? 0.2 : 0.85;
    EXPECT_GT(t.culled[kTangentPlane], 0) << test::name(kind);
    EXPECT_GE(t.culled[kTangentPlane], found * t.oracle) << test::name(kind);
    if (kind == test::PatchKind::CollapsedEdge)
      EXPECT_GT(t.pcntOnly, 0);
    else
      EXPECT_EQ(t.pcntOnly, 0) << "only collapsed edges make control planes exactly zero";
    all.views += t.views;
    all.oracle += t.oracle;
    all.pcntOnly += t.pcntOnly;
    for (int m = 0; m < kMethods; ++m) all.culled[m] += t.culled[m];
  }
  print("all", all);
  EXPECT_EQ(all.views, 5 * 60 * 100);
}

TEST(BoundBackPatch, ScalingTheSceneBy1eMinus4And1e5StaysConservativeWithTheSameCullCounts) {
  for (test::PatchKind kind : {test::PatchKind::SmoothBump, test::PatchKind::CollapsedEdge}) {
    const Tally ref = sweepKind(kind, 1.0, 300, 20, 40);
    for (double scale : {1e-4, 1e5}) {
      const Tally t = sweepKind(kind, scale, 300, 20, 40);
      if (HasFatalFailure()) return;
      char label[64];
      std::snprintf(label, sizeof label, "%s x%g", test::name(kind), scale);
      print(label, t);
      for (int m = 0; m < kMethods; ++m)
        EXPECT_NEAR(t.culled[m], ref.culled[m], 0.01 * ref.culled[m] + 2) << kMethodName[m];
    }
  }
}

// A flat regular 1x1 grid in z = 0: N = Bu x Bv = +z.
Bezier flatGrid() {
  Bezier b;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) b[4 * j + i] = {i / 3.0 - 0.5, j / 3.0 - 0.5, 0.0};
  return b;
}

// Every field of two cones, bit for bit (NaN equal to NaN).
void expectSameCone(const ConeOfNormals& a, const ConeOfNormals& b, const std::string& what) {
  auto bits = [](double x) { return std::bit_cast<uint64_t>(x); };
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(bits(a.apex[k]), bits(b.apex[k])) << what << " apex " << k;
    EXPECT_EQ(bits(a.axis[k]), bits(b.axis[k])) << what << " axis " << k;
  }
  EXPECT_EQ(bits(a.sinAngle), bits(b.sinAngle)) << what;
  EXPECT_EQ(bits(a.angle), bits(b.angle)) << what;
  EXPECT_EQ(bits(a.maxRadius), bits(b.maxRadius)) << what;
  EXPECT_EQ(bits(a.minNormal), bits(b.minNormal)) << what;
  EXPECT_EQ(a.valid, b.valid) << what;
  EXPECT_EQ(a.reason, b.reason) << what;
}

// The filtered axis search (atan2 only near the largest pseudo-angle) builds the same cones
// as the exhaustive one, on every patch kind and scale, for TCONE, NCONE and Gregory TCONE.
TEST(BoundBackPatch, FilteredConeSearchBuildsBitIdenticalCones) {
  Rng rng(77);
  int valid = 0, total = 0;
  for (int n = 0; n < 3000; ++n) {
    const auto kind = static_cast<test::PatchKind>(n % static_cast<int>(test::PatchKind::Count));
    const double scale = std::pow(10.0, rng.uniform(-4.0, 5.0));
    const Bezier b = test::transformed(test::randomBezier(rng, kind), rng, scale);
    const std::string what = std::string(test::name(kind)) + " #" + std::to_string(n);
    const ConeOfNormals t = buildConeFromTangentCones(b, ConeSearch::Filtered);
    expectSameCone(t, buildConeFromTangentCones(b, ConeSearch::Exhaustive), what + " TCONE");
    if (n % 2 == 0)
      expectSameCone(buildConeOfNormals(b, ConeSearch::Filtered),
                     buildConeOfNormals(b, ConeSearch::Exhaustive), what + " NCONE");
    if (n % 5 == 0) {
      const test::Gregory g =
          test::gregoryFromBezier(b, rng, std::pow(10.0, rng.uniform(-3, -0.5)));
      expectSameCone(buildGregoryConeFromTangentCones(g, ConeSearch::Filtered),
                     buildGregoryConeFromTangentCones(g, ConeSearch::Exhaustive),
                     what + " Gregory");
    }
    if (HasFailure()) return;
    valid += t.valid;
    ++total;
  }
  // Not only the "no cone" early exits: most TCONEs of these patches are valid.
  EXPECT_GT(valid, total / 2);
  expectSameCone(buildConeFromTangentCones(flatGrid(), ConeSearch::Filtered),
                 buildConeFromTangentCones(flatGrid(), ConeSearch::Exhaustive), "flat grid");
}

// buildPatchCones over two threads with the filtered search equals one thread with the
// exhaustive search, patch for patch (a torus large enough to be split).
TEST(BoundBackPatch, PatchConesOverTwoThreadsEqualTheExhaustiveSingleThreadedCones) {
  PatchOptions po;
  po.isolationLevel = 1;
  const PatchSet set = extractPatches(scene::torus(130, 130), po).patches;
  ASSERT_GE(set.patchCount(), kParallelConePatches);
  const auto fast = buildPatchCones(set, BackPatchMethod::TCone, ConeSearch::Filtered, 2);
  const auto slow = buildPatchCones(set, BackPatchMethod::TCone, ConeSearch::Exhaustive, 1);
  ASSERT_EQ(fast.size(), set.patchCount());
  ASSERT_EQ(slow.size(), set.patchCount());
  size_t valid = 0;
  for (uint32_t p = 0; p < set.patchCount(); ++p) {
    expectSameCone(fast[p], slow[p], "patch " + std::to_string(p));
    if (HasFailure()) return;
    valid += fast[p].valid;
  }
  EXPECT_EQ(valid, set.patchCount());  // smooth torus patches all have a cone
}

TEST(BoundBackPatch, PlanarPatchIsKeptFromJustInFrontAndCulledFromJustBehind) {
  const Bezier b = flatGrid();
  const ConeOfNormals tcone = buildConeFromTangentCones(b), ncone = buildConeOfNormals(b);
  ASSERT_TRUE(tcone.valid);
  ASSERT_TRUE(ncone.valid);
  for (double side : {1.0, -1.0}) {
    const glm::dvec3 eye(0.1, 0.2, side * 1e-6);
    const glm::dmat4 vp = glm::perspective(1.0, 1.0, 1e-8, 10.0) *
                          glm::lookAt(eye, glm::dvec3(0.3, 0.0, 0.0), glm::dvec3(0, 0, 1));
    const bool expectCulled = side < 0.0;
    const TangentPlaneResult rp = tangentPlaneTest(b, vp, clipSpaceEyeSign(vp));
    EXPECT_EQ(rp.culled, expectCulled) << side;
    EXPECT_EQ(rp.verdict,
              expectCulled ? BackPatchVerdict::BackFacing : BackPatchVerdict::FrontFacing);
    EXPECT_EQ(testConeOfNormals(ncone, eye).culled, expectCulled) << side;
    EXPECT_EQ(testConeOfNormals(tcone, eye).culled, expectCulled) << side;
  }
}

TEST(BoundBackPatch, EyeInsideAClosedSphereSeesOnlyBackFacesIncludingBehindTheEye) {
  const std::vector<Bezier> sphere = test::bezierSphere(12, 8);
  Rng rng(7);
  long withPointsBehindEye = 0, culled = 0, total = 0;
  for (int v = 0; v < 40; ++v) {
    const glm::dvec3 eye = rng.inBox(0.3);
    const test::View view = test::makeView(rng, eye, eye + rng.direction(), 0.01, 10.0);
    const double sign = clipSpaceEyeSign(view.viewProj);
    for (const Bezier& b : sphere) {
      ASSERT_FALSE(anyFrontFacing(samplePatch(b, 8), eye));
      const TangentPlaneResult r = tangentPlaneTest(b, view.viewProj, sign);
      ++total;
      culled += r.culled;
      EXPECT_TRUE(r.culled) << "view " << v;
      EXPECT_EQ(r.pcnt, 0u);
      withPointsBehindEye += clipBounds(b, view.viewProj).behindEye;
    }
  }
  std::printf(
      "inside the sphere: %ld of %ld patch-views culled by the tangent plane, %ld of "
      "them with control points behind the eye\n",
      culled, total, withPointsBehindEye);
  EXPECT_GT(withPointsBehindEye, total / 4);
}

TEST(BoundBackPatch, CollapsedPolePatchesAreCulledByPcntWhereNcntWouldKeepThem) {
  // Bottom and top rows of the sphere have one edge collapsed to the pole.
  const int lon = 12, lat = 8;
  const std::vector<Bezier> sphere = test::bezierSphere(lon, lat);
  const glm::dvec3 eye(0.05, -0.03, -10.0);  // far below the south pole
  const glm::dmat4 vp = glm::perspective(0.5, 1.0, 0.1, 100.0) *
                        glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  const double sign = clipSpaceEyeSign(vp);
  for (int a = 0; a < lon; ++a) {
    const Bezier& north = sphere[static_cast<size_t>((lat - 1) * lon + a)];
    ASSERT_EQ(north[12], north[15]);  // row 3 collapsed
    ASSERT_FALSE(anyFrontFacing(samplePatch(north, 16), eye));
    const TangentPlaneResult r = tangentPlaneTest(north, vp, sign);
    EXPECT_TRUE(r.culled);
    EXPECT_EQ(r.pcnt, 0u);
    EXPECT_EQ(r.ncnt, 56u) << "the 8 control planes along the collapsed edge are exactly 0";
    // The south pole patches face the eye: front-facing, also with 8 zero planes.
    const TangentPlaneResult s = tangentPlaneTest(sphere[static_cast<size_t>(a)], vp, sign);
    EXPECT_FALSE(s.culled);
    EXPECT_EQ(s.verdict, BackPatchVerdict::FrontFacing);
    EXPECT_EQ(s.pcnt, 56u);
  }
}

TEST(BoundBackPatch, TeapotCollapsedPatchesAreClassifiedByPcnt) {
  OSD_CULL_REQUIRE_DATA();
  const std::vector<Bezier> teapot =
      test::bptPatches(osd_cull::test::dataDir() / "bezier" / "teapot.bpt");
  ASSERT_EQ(teapot.size(), 32u);
  // Lid-top (20-23: the knob, which wraps round and is never wholly back-facing from above
  // or below) and bottom (28-31: a disc whose first row collapses to the centre) patches.
  int bottomCulledFromAbove = 0;
  for (size_t p : {20u, 21u, 22u, 23u, 28u, 29u, 30u, 31u}) {
    const Bezier& b = teapot[p];
    ASSERT_EQ(b[0], b[3]) << "patch " << p << " has its first row collapsed";
    const SurfaceSamples s = samplePatch(b, 24);
    for (double z : {30.0, -30.0}) {
      const glm::dvec3 eye(0.4, -0.3, z);
      const glm::dmat4 vp = glm::perspective(0.5, 1.0, 0.1, 100.0) *
                            glm::lookAt(eye, glm::dvec3(0, 0, 1.5), glm::dvec3(0, 1, 0));
      const TangentPlaneResult r = tangentPlaneTest(b, vp, clipSpaceEyeSign(vp));
      const bool front = anyFrontFacing(s, eye);
      EXPECT_FALSE(r.culled && front) << "false cull of patch " << p;
      if (r.culled) {
        EXPECT_LT(r.ncnt, 64u) << "the paper's Ncnt = 64 rule would keep patch " << p;
      }
      if (p >= 28 && z > 0.0) {
        EXPECT_FALSE(front) << "the bottom faces down";
        EXPECT_TRUE(r.culled) << "bottom patch " << p << " seen from above";
        bottomCulledFromAbove += r.culled;
      }
      if (p >= 28 && z < 0.0) {
        EXPECT_FALSE(r.culled) << "the bottom seen from below";
      }
    }
  }
  EXPECT_EQ(bottomCulledFromAbove, 4);
}

TEST(BoundBackPatch, NaNAndInfControlPointsAreKeptWithoutCrashing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Bezier good = flatGrid();
  const glm::dvec3 eye(0.1, 0.2, -3.0);  // behind the patch: every method culls `good`
  const glm::dmat4 vp = glm::perspective(1.0, 1.0, 0.1, 10.0) *
                        glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  const double sign = clipSpaceEyeSign(vp);
  ASSERT_TRUE(tangentPlaneTest(good, vp, sign).culled);
  ASSERT_TRUE(testConeOfNormals(buildConeOfNormals(good), eye).culled);
  ASSERT_TRUE(testConeOfNormals(buildConeFromTangentCones(good), eye).culled);
  for (double bad : {nan, inf, -inf}) {
    for (size_t k : {0u, 5u, 15u}) {
      Bezier b = good;
      b[k].z = bad;
      const TangentPlaneResult r = tangentPlaneTest(b, vp, sign);
      EXPECT_FALSE(r.culled);
      EXPECT_EQ(r.verdict, BackPatchVerdict::NonFinite);
      const ConeOfNormals n = buildConeOfNormals(b), t = buildConeFromTangentCones(b);
      EXPECT_FALSE(n.valid);
      EXPECT_EQ(n.reason, BackPatchVerdict::NonFinite);
      EXPECT_FALSE(testConeOfNormals(n, eye).culled);
      EXPECT_FALSE(testConeOfNormals(t, eye).culled);
    }
    glm::dmat4 m = vp;
    m[3][0] = bad;
    EXPECT_FALSE(tangentPlaneTest(good, m, sign).culled);
    EXPECT_FALSE(tangentPlaneTest(good, m, clipSpaceEyeSign(m)).culled);
    EXPECT_FALSE(testConeOfNormals(buildConeOfNormals(good), glm::dvec3(0, 0, bad)).culled);
  }
  // Finite points too large to transform: control planes overflow, the patch is kept.
  Bezier huge = good;
  for (glm::dvec3& p : huge) p *= 1e200;
  EXPECT_FALSE(tangentPlaneTest(huge, vp, sign).culled);
}

TEST(BoundBackPatch, ZeroAreaPatchesAreHandled) {
  const glm::dvec3 eye(0.3, 0.2, 4.0);
  const glm::dmat4 vp = glm::perspective(1.0, 1.0, 0.1, 10.0) *
                        glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  // A patch collapsed to a point has no area and no front-facing point: every control
  // plane is exactly zero and Pcnt = 0 culls it; the cones have no normal and keep it.
  Bezier point;
  point.fill(glm::dvec3(0.25, -0.5, 1.0));
  const TangentPlaneResult r = tangentPlaneTest(point, vp, clipSpaceEyeSign(vp));
  EXPECT_TRUE(r.culled);
  EXPECT_EQ(r.pcnt, 0u);
  EXPECT_EQ(r.ncnt, 0u);
  EXPECT_EQ(buildConeOfNormals(point).reason, BackPatchVerdict::NoNormal);
  EXPECT_EQ(buildConeFromTangentCones(point).reason, BackPatchVerdict::NoNormal);
  // A patch collapsed to a curve (all rows equal): zero area; rounding makes its planes
  // tiny but not provably zero, so it is kept; no crash, no NaN.
  Bezier curve;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) curve[4 * j + i] = {i * 0.3, i * i * 0.1, 0.5 * i};
  const TangentPlaneResult c = tangentPlaneTest(curve, vp, clipSpaceEyeSign(vp));
  EXPECT_NE(c.verdict, BackPatchVerdict::NonFinite);
  EXPECT_FALSE(buildConeFromTangentCones(curve).valid);
  EXPECT_FALSE(buildConeOfNormals(curve).valid);
}

TEST(BoundBackPatch, NormalPatchCoefficientsReproduceBuCrossBv) {
  Rng rng(5);
  for (int n = 0; n < 100; ++n) {
    const Bezier b = test::randomBezier(rng, static_cast<test::PatchKind>(n % 5));
    const std::array<glm::dvec3, 36> np = normalPatch(b);
    for (int s = 0; s < 10; ++s) {
      const double u = rng.uniform(), v = rng.uniform();
      glm::dvec3 viaCoefficients(0.0);
      for (int q = 0; q < 6; ++q)
        for (int p = 0; p < 6; ++p)
          viaCoefficients += bernstein(5, p, u) * bernstein(5, q, v) * np[6 * q + p];
      const PatchSample d = evaluateBezier(b, u, v);
      const glm::dvec3 direct = glm::cross(d.du, d.dv);
      EXPECT_NEAR(glm::length(viaCoefficients - direct), 0.0,
                  1e-12 * (1.0 + glm::length(d.du) * glm::length(d.dv)));
    }
  }
}

}  // namespace
}  // namespace osd_cull::bound
