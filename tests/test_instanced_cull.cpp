// Instanced culling (issue 10: "many instances of one patch set share the control points
// and are culled in the same dispatch; the bounds respect each instance's transform"):
// - a CullFrame culls all instances of a patch set with one dispatch per view, each
//   instance keeping its own results and status;
// - the batched frame gives the same result codes, status and image as a pass per instance,
//   also with the dispatch spread over y (a lowered maxComputeWorkGroupCount[0]), and the
//   image of the unculled draw (0 pixels lost, < 0.01% differing);
// - mirrored (negative determinant) and non-uniformly scaled instances in one dispatch cull
//   no patch that has a pixel in the oracle of that instance, and only reference culls.
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/verify/item_comparison.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/scene_description.h"
#include "support/vk_test_context.h"

#include <osd_cull/shared/cull_layout.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

namespace osd_cull {
namespace {

struct Mesh {
  PatchSet patches;
  bound::BackPatchValidity validity;
};

Mesh creasedCube() {
  bound::CullablePatches c = bound::cullablePatches(scene::creasedCube(), PatchOptions{2});
  return {std::move(c.extraction.patches), std::move(c.backPatch)};
}

// Mirrored, non-uniformly scaled, both, and plain instances side by side.
std::vector<glm::dmat4> models() {
  return {scene::composeTransform({-3, 0, 0}, {0, 0, 20}, {1, 1, 1}),
          scene::composeTransform({0, 0, 0}, {0, 0, 0}, {-1, 1, 1}),
          scene::composeTransform({3, 0, 0}, {30, 0, 50}, {1.0, 2.5, 0.4}),
          scene::composeTransform({-3, 0, 3}, {0, 70, 0}, {-0.5, 1.5, -2.0}),
          scene::composeTransform({0, 0, 3}, {10, 0, 0}, {-0.5, -1.5, -2.0}),
          scene::composeTransform({3, 0, 3}, {0, 0, 0}, {0.7, 0.7, 0.7})};
}

// An instance of `mesh` (drawn from `gpu`) per model.
std::vector<frame::CullMesh> instancesOf(frame::GpuPatchSet& gpu, const Mesh& mesh,
                                         const std::vector<glm::dmat4>& placed) {
  std::vector<frame::CullMesh> out;
  for (const glm::dmat4& m : placed)
    out.push_back(
        {.gpu = &gpu, .host = &mesh.patches, .model = m, .backPatchValidity = mesh.validity});
  return out;
}

frame::Camera orbitCamera(int step, uint32_t width, uint32_t height) {
  const frame::Bounds bounds{{-5, -2, -2}, {5, 2, 5}};
  return frame::orbit(frame::frameBounds(bounds, {0.3, -1.0, 0.6}, {0, 0, 1}, 40.0, width, height),
                      bounds.center(), {0, 0, 1}, 40.0 * step);
}

// What one CullFrame did over a few frames.
struct Played {
  std::vector<std::vector<uint32_t>> items;               // per frame
  std::vector<std::vector<std::vector<uint32_t>>> codes;  // per frame, per instance
  std::vector<std::vector<uint32_t>> status;              // per instance, after the last frame
  std::vector<uint32_t> culled;                           // per frame
  size_t passes = 0;
  uint64_t dispatches = 0;
};

Played play(vulkan::Context& context, const Mesh& mesh, bool batch, int frames) {
  frame::GpuPatchSet gpu(context, mesh.patches);
  frame::GpuPatchSet other(context, mesh.patches);  // a second patch set: its own pass
  frame::Renderer renderer(context);
  frame::RenderTarget target(context, 128, 96), plain(context, 128, 96);
  const std::vector<glm::dmat4> placed = models();
  std::vector<frame::CullMesh> meshes = instancesOf(gpu, mesh, placed);
  meshes.push_back(
      instancesOf(other, mesh, {scene::composeTransform({0, 3, 1}, {0, 0, 45}, {1, 1, 1})})[0]);
  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = 3;
  options.render.cullBackFaces = true;
  options.cull.backPatch = "tangent-plane";
  options.batchInstances = batch;
  frame::CullFrame cull(context, renderer, target, meshes, options);
  Played out;
  out.passes = cull.cullPassCount();
  for (int f = 0; f < frames; ++f) {
    const frame::Camera camera = orbitCamera(f, 128, 96);
    const frame::CullFrameStats s = cull.render(camera, {});
    out.culled.push_back(s.culled());
    out.items.push_back(target.readItems(context));
    out.codes.emplace_back();
    for (size_t i = 0; i < meshes.size(); ++i) out.codes.back().push_back(cull.readResults(i));
    // Against the same frame drawn without culling.
    std::vector<frame::PatchDraw> draws;
    for (size_t i = 0; i < meshes.size(); ++i) {
      draws.push_back({meshes[i].gpu, meshes[i].host, cull.itemBase(i)});
      draws.back().model = &meshes[i].model;
    }
    renderer.render(plain, camera, draws, {}, options.render);
    const frame::ItemComparison c = frame::compareItems(out.items.back(), plain.readItems(context));
    EXPECT_GT(c.covered, c.pixels / 20) << "frame " << f;  // the instances are in view
    EXPECT_EQ(c.lost, 0u) << "frame " << f;
    EXPECT_LE(c.differing, c.pixels / 10000) << "frame " << f;
  }
  for (size_t i = 0; i < meshes.size(); ++i)
    out.status.push_back(cull.visibility(i).readStatus(context));
  out.dispatches = cull.cullDispatches();
  return out;
}

void expectSame(const Played& a, const Played& b) {
  ASSERT_EQ(a.items.size(), b.items.size());
  for (size_t f = 0; f < a.items.size(); ++f) {
    EXPECT_EQ(a.items[f], b.items[f]) << "frame " << f;
    EXPECT_EQ(a.codes[f], b.codes[f]) << "frame " << f;
    EXPECT_EQ(a.culled[f], b.culled[f]) << "frame " << f;
  }
  EXPECT_EQ(a.status, b.status);
}

class InstancedCullTest : public test::VkTest {};

TEST_F(InstancedCullTest, OneDispatchPerPatchSetCullsEveryInstanceAsAPassPerInstanceDoes) {
  const Mesh cube = creasedCube();
  const int frames = 4;
  const Played batched = play(context(), cube, true, frames);
  const Played separate = play(context(), cube, false, frames);
  // Six instances of one patch set and one of another: two passes, two dispatches a frame,
  // against seven of each.
  EXPECT_EQ(batched.passes, 2u);
  EXPECT_EQ(batched.dispatches, 2u * frames);
  EXPECT_EQ(separate.passes, 7u);
  EXPECT_EQ(separate.dispatches, 7u * frames);
  expectSame(batched, separate);
  uint32_t culled = 0;
  for (uint32_t c : batched.culled) culled += c;
  EXPECT_GT(culled, 0u);                             // the comparison compares culls
  for (size_t f = 0; f < batched.codes.size(); ++f)  // instances differ: per-instance codes
    EXPECT_NE(batched.codes[f][0], batched.codes[f][1]) << "frame " << f;
}

// Six instances of ~400 patches take 6 x 7 groups of 64; with at most 5 groups in x the
// dispatch spreads over y and the instance of each group comes from its flattened index.
TEST_F(InstancedCullTest, DispatchSpreadOverYCullsAsInOneRow) {
  const Mesh cube = creasedCube();
  const Played wide = play(context(), cube, true, 2);
  auto log = std::make_shared<vulkan::ValidationLog>();
  Played narrow;
  {
    vulkan::ContextOptions options = test::validatedContextOptions(log);
    options.adjustDeviceInfo = [](vulkan::DeviceInfo& info) {
      info.limits.maxComputeWorkGroupCount[0] = 5;
    };
    vulkan::Context adjusted(options);
    narrow = play(adjusted, cube, true, 2);
  }
  EXPECT_EQ(log->count(), 0u) << log->summary();
  expectSame(wide, narrow);
}

TEST_F(InstancedCullTest, MirroredAndNonUniformInstancesInOneDispatchCullNothingVisible) {
  const Mesh cube = creasedCube();
  frame::GpuPatchSet gpu(context(), cube.patches);
  frame::Renderer renderer(context());
  frame::RenderTarget target(context(), 128, 96), solo(context(), 128, 96);
  frame::VisibilityOracle oracle(context());
  const std::vector<glm::dmat4> placed = models();
  const std::vector<frame::CullMesh> meshes = instancesOf(gpu, cube, placed);
  for (const std::string method : {"tcone", "tangent-plane"}) {
    frame::CullFrameOptions options;
    options.render.tessellation.uniformLevel = 3;
    options.render.cullBackFaces = true;
    options.cull.backPatch = method;
    options.cull.occlusion = "";  // each instance alone must not see its culled patches
    frame::CullFrame cull(context(), renderer, target, meshes, options);
    ASSERT_EQ(cull.cullPassCount(), 1u);
    const frame::CullPass& pass = *cull.cullPass(0);
    ASSERT_EQ(pass.instanceCount(), placed.size());
    ASSERT_TRUE(pass.backPatchEnabled()) << pass.backPatchNote();
    const bound::BackPatchMethod ref = frame::cullMethod(method).reference;
    const auto cones = bound::buildPatchCones(cube.patches, ref);
    std::vector<uint32_t> backPatchCulls(placed.size(), 0);
    for (int f = 0; f < 6; ++f) {
      const frame::Camera camera = orbitCamera(f, 128, 96);
      cull.render(camera, {});
      for (size_t i = 0; i < placed.size(); ++i) {
        const std::string label =
            method + " instance " + std::to_string(i) + " frame " + std::to_string(f);
        const frame::Camera c = frame::instanceCamera(camera, placed[i]);
        const frame::VisibilityCounts counts =
            oracle.query(renderer, solo, c, gpu, &cube.patches, {}, options.render.tessellation);
        std::vector<bound::TriangleShape> shapes;
        const auto reference = bound::referenceCull(
            cube.patches, bound::makeCullView(c.viewProjection()),
            pass.referenceTests(c, options.render.tessellation, shapes), cones);
        const std::vector<uint32_t> codes = cull.readResults(i);
        EXPECT_EQ(codes, std::vector<uint32_t>(pass.results(cull.instanceInPass(i)).begin(),
                                               pass.results(cull.instanceInPass(i)).end()));
        uint32_t falseCulls = 0, notInReference = 0;
        for (uint32_t p = 0; p < cube.patches.patchCount(); ++p) {
          const bound::CullCode g{codes[p]};
          if (!g.culled()) continue;
          backPatchCulls[i] += g.stage() == shader::kStageBackPatch;
          falseCulls += counts.visible(p);
          notInReference += !bound::CullCode{reference[p]}.culled();
        }
        EXPECT_EQ(falseCulls, 0u) << label;
        EXPECT_EQ(notInReference, 0u) << label;
      }
    }
    // Every instance kind, mirrored or not, has its back patches found.
    for (size_t i = 0; i < placed.size(); ++i)
      EXPECT_GT(backPatchCulls[i], 0u) << method << " instance " << i;
    std::printf("%s: back-patch culls per instance over 6 frames:", method.c_str());
    for (uint32_t n : backPatchCulls) std::printf(" %u", n);
    std::printf("\n");
  }
}

}  // namespace
}  // namespace osd_cull
