// Instances and large coordinates (issue 10): a mesh is culled and drawn in its own
// coordinates with view · model composed in double (frame::instanceCamera), so
// - a creased cube placed 1e3, 1e4 or 1e5 from the origin culls within one point of the
//   same cube at the origin and draws the same image, where baking the offset into fp32
//   control points loses the margins' bits;
// - mirrored (negative determinant) and non-uniformly scaled instances cull no visible
//   patch, back-patch orientation included, against the double reference and the oracle;
// - instances sharing one GpuPatchSet in a CullFrame draw what the unculled frame draws.
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/item_comparison.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/scene_description.h"
#include "support/cull_test_meshes.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>

namespace osd_cull {
namespace {

const std::vector<std::string> kMethods = {"frustum", "tcone", "tangent-plane"};

test::CullMesh creasedCube(int level = 2) {
  const CageMesh cage = scene::creasedCube();
  test::CullMesh m;
  m.name = cage.source;
  bound::CullablePatches c = bound::cullablePatches(cage, PatchOptions{level});
  m.validity = std::move(c.backPatch);
  m.patches = std::move(c.extraction.patches);
  return m;
}

// Random views of the mesh's bounds (at the origin), and a close third cutting through it.
std::vector<frame::Camera> originViews(const PatchSet& patches, uint32_t count, uint64_t seed) {
  frame::ViewSetOptions o;
  o.count = count;
  o.seed = seed;
  o.width = o.height = 96;
  o.set = frame::ViewSet::WholeObject;
  std::vector<frame::Camera> views = frame::randomViews(frame::boundsOf(patches.points), o);
  o.set = frame::ViewSet::Sphere;
  o.seed = seed + 1;
  for (const frame::Camera& c : frame::randomViews(frame::boundsOf(patches.points), o))
    views.push_back(c);
  return views;
}

// The same camera moved by `offset` in world space.
frame::Camera moved(const frame::Camera& c, const glm::dvec3& offset) {
  frame::Camera m = c;
  m.view = c.view * glm::translate(glm::dmat4(1.0), -offset);
  return m;
}

double rate(const frame::CullVerifier& v, const std::string& method) {
  return test::totalsOf(v, method).cullRate();
}

class SceneInstancesTest : public test::VkTest {};

TEST_F(SceneInstancesTest, FarFromTheOriginCullsAsAtTheOrigin) {
  const test::CullMesh cube = creasedCube();
  ASSERT_TRUE(cube.validity.enabled) << cube.validity.reason;
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 3;
  options.imageCheck = true;
  const std::vector<frame::Camera> views = originViews(cube.patches, 16, 7);

  frame::CullVerifier origin(context(), cube.patches, kMethods, cube.validity, options);
  for (const frame::Camera& c : views) origin.verifyView(c);
  test::expectNoViolations(origin, "origin");
  EXPECT_GT(rate(origin, "tangent-plane"), 0.10);

  for (const double offset : {1e3, 1e4, 1e5}) {
    const glm::dvec3 at(offset, 0.0, 0.0);
    const glm::dmat4 model = glm::translate(glm::dmat4(1.0), at);
    // The instance: object-space points, world cameras composed with the model in double.
    frame::CullVerifier instance(context(), cube.patches, kMethods, cube.validity, options);
    // Today's alternative: the offset baked into the (fp32 on the GPU) control points.
    const PatchSet baked = scene::translated(cube.patches, at);
    frame::CullVerifier world(context(), baked, kMethods, cube.validity, options);
    for (const frame::Camera& c : views) {
      instance.verifyView(frame::instanceCamera(moved(c, at), model));
      world.verifyView(moved(c, at));
    }
    const std::string label = "offset " + std::to_string(offset);
    test::expectNoViolations(instance, label);
    for (const std::string& m : kMethods) {
      std::printf("%-14s offset %.0e: origin %.4f, instance %.4f, baked world %.4f\n", m.c_str(),
                  offset, rate(origin, m), rate(instance, m), rate(world, m));
      EXPECT_NEAR(rate(instance, m), rate(origin, m), 0.01) << label << " " << m;
    }
  }
}

TEST_F(SceneInstancesTest, FarFromTheOriginDrawsTheSameImage) {
  const test::CullMesh cube = creasedCube();
  frame::GpuPatchSet gpu(context(), cube.patches);
  frame::Renderer renderer(context());
  frame::RenderTarget target(context(), 160, 120);
  frame::RenderOptions o;
  o.tessellation.uniformLevel = 6;
  o.cullBackFaces = true;
  const frame::Camera camera = frame::frameBounds(frame::boundsOf(cube.patches.points),
                                                  {0.6, -1.0, 0.5}, {0, 0, 1}, 40.0, 160, 120);
  auto items = [&](const glm::dvec3& at) {
    const glm::dmat4 model = glm::translate(glm::dmat4(1.0), at);
    frame::PatchDraw draw{&gpu, &cube.patches, 0};
    draw.model = &model;
    renderer.render(target, moved(camera, at), {&draw, 1}, {}, o);
    return target.readItems(context());
  };
  const std::vector<uint32_t> reference = items(glm::dvec3(0.0));
  uint32_t covered = 0;
  for (uint32_t v : reference) covered += v != 0;
  ASSERT_GT(covered, 2000u);
  for (const double offset : {1e3, 1e5}) {
    const std::vector<uint32_t> far = items({offset, -offset, offset});
    uint32_t differing = 0;
    for (size_t i = 0; i < far.size(); ++i) differing += far[i] != reference[i];
    EXPECT_EQ(differing, 0u) << "offset " << offset;
  }
}

TEST_F(SceneInstancesTest, MirroredAndNonUniformInstancesCullNothingVisible) {
  const test::CullMesh cube = creasedCube();
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 3;
  options.imageCheck = true;
  options.samplingGrid = 4;
  const std::vector<glm::dmat4> models = {
      scene::composeTransform({0, 0, 0}, {0, 0, 0}, {-1, 1, 1}),           // mirrored in x
      scene::composeTransform({2, 1, 0}, {30, 0, 50}, {1.0, 2.5, 0.4}),    // non-uniform
      scene::composeTransform({0, 0, 3}, {0, 70, 0}, {-0.5, 1.5, -2.0}),   // both, det > 0
      scene::composeTransform({0, 0, 3}, {10, 0, 0}, {-0.5, -1.5, -2.0}),  // both, det < 0
  };
  for (size_t i = 0; i < models.size(); ++i) {
    frame::CullVerifier v(context(), cube.patches, kMethods, cube.validity, options);
    // World views of the placed instance, culled in its object space.
    std::vector<glm::dvec3> world;
    for (const glm::dvec3& p : cube.patches.points)
      world.push_back(glm::dvec3(models[i] * glm::dvec4(p, 1.0)));
    PatchSet placed = cube.patches;
    placed.points = world;
    for (const frame::Camera& c : originViews(placed, 12, 20 + i))
      v.verifyView(frame::instanceCamera(c, models[i]));
    const std::string label = "model " + std::to_string(i);
    test::expectNoViolations(v, label);
    // Back-facing patches are found, so orientation is handled, not just kept.
    EXPECT_GT(rate(v, "tangent-plane"), 0.10) << label;
    EXPECT_GT(rate(v, "tcone"), 0.05) << label;
    std::printf("%s (det %+.2f): tcone %.3f, tangent plane %.3f, oracle invisible %.3f\n",
                label.c_str(), glm::determinant(glm::dmat3(models[i])), rate(v, "tcone"),
                rate(v, "tangent-plane"), test::totalsOf(v, "tangent-plane").oracleInvisibleRate());
  }
}

TEST_F(SceneInstancesTest, InstancesSharingPointsDrawTheUnculledImage) {
  const test::CullMesh cube = creasedCube(2);
  frame::GpuPatchSet gpu(context(), cube.patches);
  frame::Renderer renderer(context());
  frame::RenderTarget culled(context(), 128, 96), plain(context(), 128, 96);
  const std::vector<glm::dmat4> models = {
      scene::composeTransform({-2.5, 0, 0}, {0, 0, 20}, {1, 1, 1}),
      scene::composeTransform({0, 0, 0}, {0, 0, 0}, {-1, 1, 1}),
      scene::composeTransform({2.5, 0, 0}, {0, 30, 0}, {0.6, 1.4, 1.0})};
  std::vector<frame::CullMesh> meshes;
  for (const glm::dmat4& m : models)
    meshes.push_back(
        {.gpu = &gpu, .host = &cube.patches, .model = m, .backPatchValidity = cube.validity});
  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = 4;
  options.render.cullBackFaces = true;
  options.cull.backPatch = "tangent-plane";
  frame::CullFrame cullFrame(context(), renderer, culled, meshes, options);
  for (size_t i = 0; i < models.size(); ++i)
    ASSERT_TRUE(cullFrame.cullPass(i)->backPatchEnabled())
        << cullFrame.cullPass(i)->backPatchNote();
  const frame::Bounds bounds{{-4, -2, -2}, {4, 2, 2}};
  uint32_t culledTotal = 0;
  for (int f = 0; f < 4; ++f) {
    const frame::Camera camera =
        frame::orbit(frame::frameBounds(bounds, {0.3, -1.0, 0.6}, {0, 0, 1}, 40.0, 128, 96),
                     bounds.center(), {0, 0, 1}, 25.0 * f);
    const frame::CullFrameStats s = cullFrame.render(camera, {});
    culledTotal += s.culledBackPatch;
    std::printf("frame %d: culled frustum %u, back-patch %u, occlusion %u of %u\n", f,
                s.culledFrustum, s.culledBackPatch, s.culledOcclusion, s.patchesTotal);
    std::vector<frame::PatchDraw> draws;
    for (size_t i = 0; i < models.size(); ++i) {
      draws.push_back({&gpu, &cube.patches, cullFrame.itemBase(i)});
      draws.back().model = &models[i];
    }
    renderer.render(plain, camera, draws, {}, options.render);
    const frame::ItemComparison c =
        frame::compareItems(culled.readItems(context()), plain.readItems(context()));
    EXPECT_GT(c.covered, 500u) << "frame " << f;
    EXPECT_EQ(c.lost, 0u) << "frame " << f;
    EXPECT_LE(c.differing, c.covered / 10000) << "frame " << f;
  }
  EXPECT_GT(culledTotal, 0u);  // the back-patch stage culled on every instance kind
}

}  // namespace
}  // namespace osd_cull
