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
#include <map>
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
  // Floors a point or two under the rates measured (2026-12-07, lavapipe; the views are
  // seeded, so the figures repeat): with 120 views frustum 7.09%, tangent-plane surface
  // 40.51%, Bézier tangent plane 15.01%, NCONE 13.61%, TCONE 9.66%; with the 60 views of a
  // sanitizer build 7.78%, 40.79%, 15.37%, 13.99%, 10.02%.
  EXPECT_GT(test::totalsOf(verifier, "frustum").cullRate(), 0.06);  // the close-up views
  EXPECT_GT(surface, 0.385);
  EXPECT_GT(bezierRate("tangent-plane"), 0.13);
  EXPECT_GT(bezierRate("ncone"), 0.12);
  EXPECT_GT(bezierRate("tcone"), 0.08);
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

// Floors of the tangent-plane surface rate (culled, or kept only for the drawn triangles) of
// each closed shape, two points under the lower of the rates measured (2026-12-07, lavapipe,
// seeded views) with 120 views and with the 30 of a sanitizer build: chaikin0 45.77/45.28%,
// cube 39.87/40.21%, cube_corner0 40.10/40.31%, cube_creases0 40.03/41.18%, cubes_infsharp
// 38.96/37.73%, cubes_semisharp 35.46/35.36%, pyramid_creases0 28.55/26.88%, smoothtris0
// 26.44/26.57%, toroidal_tet 31.15/31.07%, torus 20.26/20.73%, torus_creases0 33.62/37.01%.
// A shape not listed (other data) must cull a tenth.
double surfaceFloor(const std::string& shape) {
  static const std::map<std::string, double> floors = {
      {"catmark_chaikin0.obj", 0.43},         {"catmark_cube.obj", 0.37},
      {"catmark_cube_corner0.obj", 0.38},     {"catmark_cube_creases0.obj", 0.38},
      {"catmark_cubes_infsharp.obj", 0.35},   {"catmark_cubes_semisharp.obj", 0.33},
      {"catmark_pyramid_creases0.obj", 0.24}, {"catmark_smoothtris0.obj", 0.24},
      {"catmark_toroidal_tet.obj", 0.29},     {"catmark_torus.obj", 0.18},
      {"catmark_torus_creases0.obj", 0.31}};
  const auto it = floors.find(shape);
  return it == floors.end() ? 0.1 : it->second;
}

TEST_F(CullViewsTest, EveryCatmarkShapeNeverCullsWhatTheReferenceOrTheOracleKeeps) {
  OSD_CULL_REQUIRE_DATA();
  uint32_t closedShapes = 0;
  uint64_t drawnCulled = 0, surfaceCulled = 0, drawnPatchViews = 0;
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
      // The surface test culls its share (culled, or kept only for the drawn triangles at
      // this coarse tessellation); the drawn-triangle bound keeps some of it.
      const frame::MethodTotals& tp = test::totalsOf(verifier, "tangent-plane");
      const double surface = double(tp.culled + tp.keptForDrawnTriangles) / double(tp.patchViews);
      std::printf("%s: tangent-plane surface %.2f%%, drawn %.2f%%\n", mesh.name.c_str(),
                  100 * surface, 100 * double(tp.culled) / double(tp.patchViews));
      EXPECT_GT(surface, surfaceFloor(mesh.name)) << mesh.name;
      drawnCulled += tp.culled;
      surfaceCulled += tp.culled + tp.keptForDrawnTriangles;
      drawnPatchViews += tp.patchViews;
    }
  }
  EXPECT_GE(closedShapes, 10u);
  std::printf("closed shapes: %u, tangent-plane surface %.2f%%, drawn %.2f%%\n", closedShapes,
              100 * double(surfaceCulled) / double(drawnPatchViews),
              100 * double(drawnCulled) / double(drawnPatchViews));
  // Measured over the 11 shapes: surface 33.73% and drawn 14.05% with 120 views, 33.79% and
  // 14.19% with 30.
  EXPECT_GT(double(surfaceCulled) / double(drawnPatchViews), 0.31);
  EXPECT_GT(double(drawnCulled) / double(drawnPatchViews), 0.12);
}

}  // namespace
}  // namespace osd_cull
