// Every cull method on many random views of real meshes (BigGuy and the closed Catmull-Clark
// shapes of the shared data), checked against every ground truth (frame/cull_verification.h):
// GPU culls ⊆ double-precision reference culls, culled patches have no pixel in the
// oracle, no visible sample on a dense sampling, and culling loses no pixel of the image.
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "support/cull_test_meshes.h"
#include "support/sanitizer.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cstdio>
#include <random>

namespace osd_cull {
namespace {

using frame::ViewSet;

const std::vector<std::string> kAllMethods = {"frustum", "tcone", "ncone", "tangent-plane",
                                              "tangent-plane-16"};

std::vector<frame::Camera> views(const PatchSet& patches, ViewSet set, uint32_t count,
                                 uint64_t seed, uint32_t size = 96) {
  frame::ViewSetOptions o;
  o.set = set;
  o.count = count;
  o.seed = seed;
  o.width = o.height = size;
  return frame::randomViews(frame::boundsOf(patches.points), o);
}

// A third of the views close up: the eye at 0.3..1 times the sphere distance, looking at a
// random point of the object, so the frustum cuts through it and culls patches.
std::vector<frame::Camera> closeViews(const PatchSet& patches, uint32_t count, uint64_t seed,
                                      uint32_t size = 96) {
  std::vector<frame::Camera> out = views(patches, ViewSet::WholeObject, count, seed, size);
  const frame::Bounds b = frame::boundsOf(patches.points);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (frame::Camera& c : out) {
    const glm::dvec3 eye = c.eye(), centre = b.center();
    const glm::dvec3 target = patches.points[size_t(u(rng) * double(patches.points.size() - 1))];
    const glm::dvec3 closer = centre + (eye - centre) * (0.3 + 0.7 * u(rng));
    const double d = glm::distance(closer, target) + 1e-9;
    c = frame::Camera::lookAt(closer, target, glm::dvec3(0, 1, 0.1), 30.0, c.width, c.height,
                              d * 0.05, d + 3.0 * b.radius());
  }
  return out;
}

class CullViewsTest : public test::VkTest {};

TEST_F(CullViewsTest, BigGuyNeverCullsWhatTheReferenceOrTheOracleKeeps) {
  OSD_CULL_REQUIRE_DATA();
  const test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "characters" / "bigguy.obj");
  ASSERT_TRUE(mesh.validity.enabled) << mesh.validity.reason;
  ASSERT_EQ(mesh.patches.patchCount(), 5554u);
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 3;
  frame::CullVerifier verifier(context(), mesh.patches, kAllMethods, mesh.validity, options);
  const uint32_t n = test::sanitizerScaled(40, 2);  // per view set; 20 under ASan
  std::vector<frame::Camera> cameras = views(mesh.patches, ViewSet::Sphere, n, 11);
  for (const auto& c : views(mesh.patches, ViewSet::WholeObject, n, 12)) cameras.push_back(c);
  for (const auto& c : closeViews(mesh.patches, n, 13)) cameras.push_back(c);
  for (const auto& camera : cameras) verifier.verifyView(camera);
  test::expectNoViolations(verifier, mesh.name);

  // Rates in line with the double reference (docs/algorithms/back-patch.md, surface-exact:
  // tangent plane 44.7%, NCONE 42.2%, TCONE 36.4% of the Bézier patches on sphere views), the
  // fp32 kernel agreeing with the reference on nearly every patch.
  for (const auto& t : verifier.totals()) {
    EXPECT_GT(t.referenceAgreement(), t.name == "frustum" ? 0.9999 : 0.99) << t.name;
    EXPECT_GE(t.oracleInvisibleRate(), t.cullRate()) << t.name;
  }
  EXPECT_GT(test::totalsOf(verifier, "frustum").cullRate(), 0.05);  // the close-up views
  const auto bezierRate = [&](const std::string& m) {
    const auto& t = test::totalsOf(verifier, m);
    return double(t.culledBezier) / double(t.bezierViews);
  };
  // The surface test culls what the paper's does; the drawn-triangle bound keeps part of it
  // at this coarse tessellation (docs/results/backpatch.md).
  const auto& tp = test::totalsOf(verifier, "tangent-plane");
  const double surface = double(tp.culled + tp.keptForDrawnTriangles) / double(tp.patchViews);
  std::printf(
      "BigGuy, %zu views: frustum %.2f%%, tangent-plane surface %.2f%%, Bezier tangent-plane "
      "%.2f%% ncone %.2f%% tcone %.2f%%\n",
      cameras.size(), 100 * test::totalsOf(verifier, "frustum").cullRate(), 100 * surface,
      100 * bezierRate("tangent-plane"), 100 * bezierRate("ncone"), 100 * bezierRate("tcone"));
  EXPECT_GT(surface, 0.33);
  EXPECT_GT(bezierRate("tangent-plane"), 0.12);
  EXPECT_GT(bezierRate("tangent-plane"), bezierRate("ncone"));
  EXPECT_GT(bezierRate("ncone"), bezierRate("tcone"));
  // The one-thread kernel computes the coefficients by the factored form with its own fp32
  // margins (docs/algorithms/cull-kernel.md), the 16-thread one by the §5 table: both cull a
  // subset of the reference, within a few percent of each other (measured: 1.9% fewer).
  const double one = double(test::totalsOf(verifier, "tangent-plane").culled);
  const double sixteen = double(test::totalsOf(verifier, "tangent-plane-16").culled);
  EXPECT_GT(one, 0.97 * sixteen);
  EXPECT_LT(one, 1.03 * sixteen);
}

TEST_F(CullViewsTest, BigGuyCulledPatchesHaveNoVisibleSampleAndCullingLosesNoPixel) {
  OSD_CULL_REQUIRE_DATA();
  const test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "characters" / "bigguy.obj");
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 3;
  options.samplingGrid = 8;
  options.imageCheck = true;
  frame::CullVerifier verifier(context(), mesh.patches, kAllMethods, mesh.validity, options);
  std::vector<frame::Camera> cameras = views(mesh.patches, ViewSet::Sphere, 6, 21, 160);
  for (const auto& c : closeViews(mesh.patches, 6, 22, 160)) cameras.push_back(c);
  for (auto& c : cameras) verifier.verifyView(c);
  test::expectNoViolations(verifier, mesh.name);
  for (const auto& t : verifier.totals()) {
    EXPECT_EQ(t.imageViews, 12u) << t.name;
    EXPECT_GT(t.sampledCulls, 0u) << t.name;
  }
}

TEST_F(CullViewsTest, EveryCatmarkShapeNeverCullsWhatTheReferenceOrTheOracleKeeps) {
  OSD_CULL_REQUIRE_DATA();
  uint32_t closedShapes = 0;
  uint64_t drawnCulled = 0, drawnPatchViews = 0;
  for (const auto& path : test::catmarkShapes()) {
    const test::CullMesh mesh = test::loadCullMesh(path);
    if (mesh.patches.patchCount() == 0) continue;
    closedShapes += mesh.validity.enabled;
    frame::VerifyOptions options;
    options.tessellation.uniformLevel = 3;
    options.samplingGrid = 4;
    options.imageCheck = true;
    frame::CullVerifier verifier(context(), mesh.patches, kAllMethods, mesh.validity, options);
    // Open shapes: back-patch culling is off, only the frustum test runs.
    EXPECT_EQ(verifier.skipped().size(), mesh.validity.enabled ? 0u : 4u) << mesh.name;
    const uint32_t n = test::sanitizerScaled(40, 4);  // per view set; 10 under ASan
    std::vector<frame::Camera> cameras = views(mesh.patches, ViewSet::Sphere, n, 31, 64);
    for (const auto& c : views(mesh.patches, ViewSet::WholeObject, n, 32, 64)) cameras.push_back(c);
    for (const auto& c : closeViews(mesh.patches, n, 33, 64)) cameras.push_back(c);
    for (const auto& camera : cameras) verifier.verifyView(camera);
    test::expectNoViolations(verifier, mesh.name);
    if (mesh.validity.enabled) {
      // The surface test culls a tenth or more (culled, or kept only for the drawn
      // triangles at this coarse tessellation); the drawn-triangle bound keeps some of it.
      const frame::MethodTotals& tp = test::totalsOf(verifier, "tangent-plane");
      const double surface = double(tp.culled + tp.keptForDrawnTriangles) / double(tp.patchViews);
      std::printf("%s: tangent-plane surface %.2f%%, drawn %.2f%%\n", mesh.name.c_str(),
                  100 * surface, 100 * double(tp.culled) / double(tp.patchViews));
      EXPECT_GT(surface, 0.1) << mesh.name;
      drawnCulled += tp.culled;
      drawnPatchViews += tp.patchViews;
    }
  }
  EXPECT_GE(closedShapes, 10u);
  std::printf("closed shapes: %u, tangent-plane drawn %.2f%%\n", closedShapes,
              100 * double(drawnCulled) / double(drawnPatchViews));
  EXPECT_GT(double(drawnCulled) / double(drawnPatchViews), 0.05);
}

}  // namespace
}  // namespace osd_cull
