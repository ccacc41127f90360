// The cull kernel on the hard cases of issue 4, each its own test: the teapot's collapsed
// patches (Pcnt), catmark_pole64, a camera inside the bounding box close to the surface,
// patches crossing the near plane, and coordinates scaled by 1e-4 and 1e5. (NaN and Inf
// control points: test_cull_kernel.cpp, NonFiniteControlPointsAreKeptByEveryStage.)
#include "adapters/load_mesh.h"
#include "osd_cull/bound/frustum.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/bound/sampling.h"
#include "osd_cull/bound/tangent_plane.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "support/cull_test_meshes.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <osd_cull/shared/cull_layout.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <random>

namespace osd_cull {
namespace {

using bound::CullCode;
namespace sh = shader;

const std::vector<std::string> kAllMethods = {"frustum", "tcone", "ncone", "tangent-plane",
                                              "tangent-plane-16"};

class CullHardCasesTest : public test::VkTest {};

TEST_F(CullHardCasesTest, TeapotCollapsedPatchesAreClassifiedByPcnt) {
  OSD_CULL_REQUIRE_DATA();
  // The teapot is open (rims, spout), so back-patch culling is off for the mesh; this test
  // forces it on to check the per-patch classification of its collapsed patches.
  const PatchSet teapot = adapters::loadBezierPatches(test::dataDir() / "bezier" / "teapot.bpt");
  ASSERT_EQ(teapot.patchCount(), 32u);
  frame::GpuPatchSet gpu(context(), teapot);
  for (const char* method : {"tangent-plane", "tangent-plane-16"}) {
    frame::CullSettings settings;
    settings.frustum = false;
    settings.backPatch = method;
    settings.backPatchValidity = {true, "per-patch classification test"};
    settings.drawnTriangles = false;  // the surface classification (Pcnt) is under test
    frame::CullPass pass(context(), gpu, teapot, settings);
    for (double z : {30.0, -30.0}) {
      const glm::dvec3 eye(0.4, -0.3, z);
      const auto camera =
          frame::Camera::lookAt(eye, {0, 0, 1.5}, {0, 1, 0}, 30.0, 64, 64, 0.1, 100.0);
      pass.run(camera);
      const bound::CullView view = bound::makeCullView(camera.viewProjection());
      for (uint32_t p = 0; p < teapot.patchCount(); ++p) {
        const CullCode code{pass.results()[p]};
        const auto points = teapot.controlPoints(p);
        const bound::TangentPlaneResult ref =
            bound::tangentPlaneTest(points, view.viewProj, view.eyeSign);
        EXPECT_TRUE(!code.culled() || ref.culled) << method << " patch " << p;
        if (code.culled()) {
          EXPECT_FALSE(bound::anyFrontFacing(bound::samplePatch(points, 16), eye))
              << method << " patch " << p;
        }
        if (p >= 28) {  // the bottom: a disc whose first row collapses to its centre
          ASSERT_EQ(points[0], points[3]);
          EXPECT_EQ(code.culled(), z > 0.0) << method << " bottom patch " << p << " z " << z;
          // Culled only thanks to section 7's Pcnt rule: Ncnt = 64 would keep it.
          if (z > 0.0) {
            EXPECT_LT(ref.ncnt, 64u);
          }
        }
      }
    }
  }
}

// catmark_pole64 is an open disc around a valence-64 pole (Gregory end caps): back-patch
// culling is off for the mesh, with the reason; forced on, the per-patch classification
// (double reference, dense sampling) still holds, the oracle cannot apply (the back side
// shows through the open boundary).
TEST_F(CullHardCasesTest, CatmarkPole64) {
  OSD_CULL_REQUIRE_DATA();
  const test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "shapes" / "catmark_pole64.obj");
  ASSERT_GT(mesh.patches.gregoryCount, 0u);  // the valence-64 pole gets Gregory end caps
  EXPECT_FALSE(mesh.validity.enabled);
  EXPECT_NE(mesh.validity.reason.find("open"), std::string::npos) << mesh.validity.reason;
  frame::ViewSetOptions vo;
  vo.width = vo.height = 96;
  vo.count = 30;
  std::vector<frame::Camera> cameras;
  for (frame::ViewSet set : {frame::ViewSet::Sphere, frame::ViewSet::WholeObject}) {
    vo.set = set;
    for (const auto& c : frame::randomViews(frame::boundsOf(mesh.patches.points), vo))
      cameras.push_back(c);
  }
  {
    frame::VerifyOptions options;
    options.tessellation.uniformLevel = 3;
    options.samplingGrid = 6;
    options.imageCheck = true;
    frame::CullVerifier verifier(context(), mesh.patches, kAllMethods, mesh.validity, options);
    EXPECT_EQ(verifier.totals().size(), 1u);  // frustum only
    EXPECT_EQ(verifier.skipped().size(), 4u);
    for (const auto& camera : cameras) verifier.verifyView(camera);
    test::expectNoViolations(verifier, mesh.name);
  }
  frame::VerifyOptions options;
  options.oracle = false;
  options.samplingGrid = 8;
  frame::CullVerifier forced(context(), mesh.patches, kAllMethods, {true, "forced"}, options);
  for (const auto& camera : cameras) forced.verifyView(camera);
  test::expectNoViolations(forced, mesh.name + " (per patch)");
  // Bézier patches are classified; the thin Gregory patches around the pole never fit a
  // Gregory TCONE narrower than 90 degrees (kept: WideCone), which is conservative.
  // The drawn-triangle bound keeps most of the thin patches near the pole (their chords
  // deviate far from the surface at this tessellation); the surface tests cull a fifth.
  for (const std::string m : {"tcone", "ncone", "tangent-plane", "tangent-plane-16"}) {
    const frame::MethodTotals& t = test::totalsOf(forced, m);
    EXPECT_GT(t.culledBezier + t.keptForDrawnTriangles, t.bezierViews / 5) << m;
    EXPECT_GT(t.culledBezier, t.bezierViews / 50) << m;
  }
}

// Cameras just outside the surface of BigGuy (1e-3 to 3e-2 of its radius along the
// outward normal of a random surface point, so inside its bounding box), looking in random
// directions, with a near plane closer than the surface.
TEST_F(CullHardCasesTest, CameraInsideTheBoundingBoxCloseToTheSurface) {
  OSD_CULL_REQUIRE_DATA();
  const test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "characters" / "bigguy.obj");
  const frame::Bounds box = frame::boundsOf(mesh.patches.points);
  const double r = box.radius();
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<frame::Camera> cameras;
  while (cameras.size() < 24) {
    const uint32_t p = uint32_t(u(rng) * (mesh.patches.bezierCount - 1));
    const bound::PatchSample s =
        bound::evaluateBezier(mesh.patches.controlPoints(p), u(rng), u(rng));
    const glm::dvec3 n = glm::normalize(glm::cross(s.du, s.dv));
    const double d = r * std::pow(10.0, -3.0 + 1.5 * u(rng));
    const glm::dvec3 eye = s.position + d * n;
    if (glm::any(glm::lessThan(eye, box.lo)) || glm::any(glm::greaterThan(eye, box.hi))) continue;
    glm::dvec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    if (cameras.size() % 3 == 0) dir = -n + 0.3 * dir;  // towards the surface
    cameras.push_back(frame::Camera::lookAt(eye, eye + dir, glm::dvec3(0.1, 1, 0.2), 70.0, 96, 96,
                                            0.2 * d, 4.0 * r));
  }
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 3;
  options.samplingGrid = 6;
  options.imageCheck = true;
  frame::CullVerifier verifier(context(), mesh.patches, kAllMethods, mesh.validity, options);
  for (const auto& camera : cameras) verifier.verifyView(camera);
  test::expectNoViolations(verifier, mesh.name);
  // Close up, most of the mesh is outside the view.
  EXPECT_GT(test::totalsOf(verifier, "frustum").cullRate(), 0.5);
}

// Near planes through the middle of the object: patches crossing it must be kept, patches
// wholly in front of it culled by plane Near.
TEST_F(CullHardCasesTest, PatchesCrossingTheNearPlaneAreKept) {
  const PatchSet set = scene::concatenate(
      scene::bezierSphere({0, 0, 0}, 1.0, 6),
      scene::convertToGregory(scene::bsplineTorus({12, 8, 1.6, 0.3, {0, 0, 0}, -1}),
                              [](uint32_t p) { return p % 3 == 0; }));
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 4;
  options.samplingGrid = 8;
  options.imageCheck = true;
  frame::CullVerifier verifier(context(), set, {"frustum"}, {false, "not needed"}, options);
  frame::GpuPatchSet gpu(context(), set);
  frame::CullSettings settings;
  frame::CullPass pass(context(), gpu, set, settings);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  uint32_t nearCulls = 0, crossing = 0;
  for (int v = 0; v < 24; ++v) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    const double dist = 2.5 + u(rng);
    const auto camera = frame::Camera::lookAt(dist * dir, {0, 0, 0}, {0.3, 0.2, 1}, 50.0, 96, 96,
                                              dist - 0.5 + 0.4 * u(rng), dist + 4.0);
    verifier.verifyView(camera);
    pass.run(camera);
    for (uint32_t p = 0; p < set.patchCount(); ++p) {
      const CullCode code{pass.results()[p]};
      nearCulls += code.culled() && code.frustum() == uint32_t(bound::FrustumPlane::Near);
      // Patches with points on both sides of the near plane.
      bool front = false, behind = false;
      for (const glm::dvec3& q : set.controlPoints(p)) {
        const double z = (camera.viewProjection() * glm::dvec4(q, 1.0)).z;
        front |= z > 0.0;
        behind |= z < 0.0;
      }
      if (front && behind) {
        ++crossing;
        EXPECT_FALSE(code.culled() && code.frustum() == uint32_t(bound::FrustumPlane::Near));
      }
    }
  }
  test::expectNoViolations(verifier, "near-plane views");
  EXPECT_GT(nearCulls, 0u);
  EXPECT_GT(crossing, 0u);
}

// The same views of the same shapes at scales 1e-4 and 1e5: every check holds and the
// decisions stay the same (up to fp32 rounding of the scaled coordinates).
TEST_F(CullHardCasesTest, CoordinatesScaledBy1eMinus4And1e5KeepDecisions) {
  const PatchSet unit = scene::concatenate(
      scene::translated(scene::bezierSphere({0, 0, 0}, 1.0, 4), {0.3, -0.2, 0.1}),
      scene::convertToGregory(scene::bsplineTorus({10, 6, 1.7, 0.35, {0, 0, 0.2}, 3}),
                              [](uint32_t p) { return p % 4 == 1; }));
  std::vector<uint64_t> culledAtScale;
  for (double scale : {1.0, 1e-4, 1e5}) {
    PatchSet set = unit;
    for (glm::dvec3& p : set.points) p *= scale;
    frame::VerifyOptions options;
    options.tessellation.uniformLevel = 4;
    options.samplingGrid = 6;
    frame::CullVerifier verifier(context(), set, kAllMethods, {true, "closed by construction"},
                                 options);
    frame::ViewSetOptions vo;
    vo.width = vo.height = 96;
    vo.count = 40;
    vo.set = frame::ViewSet::WholeObject;
    for (const auto& camera : frame::randomViews(frame::boundsOf(set.points), vo))
      verifier.verifyView(camera);
    test::expectNoViolations(verifier, "scale " + std::to_string(scale));
    uint64_t culled = 0;
    for (const auto& t : verifier.totals()) culled += t.culled;
    culledAtScale.push_back(culled);
    EXPECT_GT(test::totalsOf(verifier, "tangent-plane").cullRate(), 0.2) << scale;
  }
  for (size_t i = 1; i < culledAtScale.size(); ++i)
    EXPECT_NEAR(double(culledAtScale[i]), double(culledAtScale[0]), 0.002 * culledAtScale[0]);
}

}  // namespace
}  // namespace osd_cull
