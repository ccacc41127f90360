// The Hi-Z occlusion stage of the cull kernel ("hiz": shaders/cull/occlusion_hiz.glsl with
// shaders/hiz/occlusion.glsl) against its double-precision reference
// (bound::hizOcclusionTest) and the item-buffer oracle.
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/bound/occlusion.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "support/displacement_test_maps.h"
#include "support/vk_test_context.h"
#include "support/vk_test_images.h"

#include <gtest/gtest.h>
#include <osd_cull/shared/draw_layout.h>

#include <cstdio>

namespace osd_cull {
namespace {

class HiZOcclusionTest : public test::VkTest {
 protected:
  struct Comparison {
    // tested: kept by the GPU and tested by the reference (the GPU reports their level).
    uint32_t gpuCulled = 0, cpuCulled = 0, tested = 0, sameLevel = 0;
  };

  // Draws everything, builds the pyramid from that depth, runs the GPU test and the
  // reference on the read-back depth, and checks GPU culled => reference culled and GPU
  // culled => zero oracle pixels.
  Comparison compare(const PatchSet& set, std::span<const frame::TriangleMesh> meshes,
                     const frame::Camera& camera, bool fullResolution,
                     bound::HiZLookup lookup = bound::HiZLookup::Paper) {
    frame::GpuPatchSet gpu(context(), set);
    std::vector<frame::GpuTriangleMesh> gpuMeshes;
    for (const auto& m : meshes) gpuMeshes.emplace_back(context(), m);
    std::vector<const frame::GpuTriangleMesh*> occluders;
    for (const auto& m : gpuMeshes) occluders.push_back(&m);
    frame::RenderTarget target(context(), camera.width, camera.height);
    frame::Renderer renderer(context());
    frame::VisibilityOracle oracle(context());
    frame::TessellationOptions tess;
    tess.uniformLevel = 6;
    const auto counts = oracle.query(renderer, target, camera, gpu, &set, occluders, tess);
    frame::HiZPyramid pyramid(context(), target.depth(),
                              {fullResolution, frame::HiZReduction::Auto, lookup});
    pyramid.build(context(), frame::RenderTarget::kDepthLayout);
    frame::HiZCullStage stage(context(), pyramid);
    frame::CullSettings settings;
    settings.frustum = false;
    settings.occlusion = "hiz";
    frame::CullPass pass(context(), gpu, set, settings);
    pass.run(camera, tess, stage.set());
    const std::vector<uint32_t> codes(pass.results().begin(), pass.results().end());
    const bound::HiZPyramid ref = bound::buildHiZPyramid(target.readDepth(context()), camera.width,
                                                         camera.height, fullResolution);
    const glm::dmat4 vp = camera.viewProjection();
    Comparison c;
    for (uint32_t p = 0; p < set.patchCount(); ++p) {
      const bound::OcclusionResult r =
          bound::hizOcclusionTest(set.controlPoints(p), vp, ref, lookup);
      const bool culled = (codes[p] & 0xFu) == shader::kStageOcclusion;
      const uint32_t verdict = (codes[p] >> shader::kResultShiftOcclusion) & 0xFFu;
      EXPECT_EQ(verdict != shader::kOcclusionVerdictUntested, r.tested) << "patch " << p;
      if (culled) {
        EXPECT_TRUE(r.culled) << "patch " << p << ": GPU culls, the reference does not";
        EXPECT_EQ(counts.pixels[p], 0u) << "patch " << p << " culled with visible pixels";
      } else if (r.tested) {
        const uint32_t level = verdict >> shader::kOcclusionVerdictLevelShift;
        c.sameLevel += level == r.footprint.level;
        EXPECT_GE(level, r.footprint.level) << "patch " << p;
      }
      c.tested += r.tested && !culled;
      c.gpuCulled += culled;
      c.cpuCulled += r.culled;
    }
    return c;
  }
};

TEST_F(HiZOcclusionTest, GpuCullsWhatTheReferenceCullsOnTheDemoScene) {
  const scene::Scene scene = scene::defaultScene();
  const frame::Bounds bounds = frame::boundsOf(scene.patches.points);
  Comparison total;
  int view = 0;
  for (const auto& size : {std::pair{333u, 517u}, std::pair{160u, 96u}})
    for (double degrees : {0.0, 70.0, 160.0, 250.0}) {
      const frame::Camera base =
          frame::frameBounds(bounds, scene.viewDirection, scene.up, 40.0, size.first, size.second);
      const frame::Camera camera = frame::orbit(base, bounds.center(), scene.up, degrees);
      const Comparison c =
          compare(scene.patches, scene.occluders, camera, view % 2 == 1,
                  view % 4 < 2 ? bound::HiZLookup::Paper : bound::HiZLookup::Tight);
      ++view;
      total.gpuCulled += c.gpuCulled;
      total.cpuCulled += c.cpuCulled;
      total.tested += c.tested;
      total.sameLevel += c.sameLevel;
    }
  std::printf("occlusion-culled: gpu %u, reference %u of %u tested; same level %u\n",
              total.gpuCulled, total.cpuCulled, total.tested, total.sameLevel);
  // The scene has occluded patches (the sphere behind the wall, far sides of the tori).
  EXPECT_GT(total.cpuCulled, 40u);
  // fp32 margins are twice the reference's: they may keep a few patches more, not many.
  EXPECT_GE(total.gpuCulled * 100, total.cpuCulled * 97);
  EXPECT_GE(total.sameLevel * 100, total.tested * 97);
}

TEST_F(HiZOcclusionTest, PatchesBehindAWallAreCulledExactlyWhereTheyShouldBe) {
  // Four 16 x 16 patches at z = -5 in a row; a wall at z = -3 over columns 0..39 of 64x32.
  std::vector<std::array<glm::dvec3, 16>> row;
  for (int i = 0; i < 4; ++i)
    row.push_back(
        scene::flatBezierPatch({16.0 * i + 0.1, -(8 + 15.8), -5}, {15.8, 0, 0}, {0, 15.8, 0}));
  const PatchSet set = scene::bezierPatchSet(row, "test:row");
  const frame::TriangleMesh wall =
      frame::quadMesh({-4, 4, -3}, {40, 4, -3}, {40, -40, -3}, {-4, -40, -3});
  for (bool full : {false, true}) {
    const Comparison c = compare(set, {&wall, 1}, test::pixelCamera(64, 32), full);
    // Patches 0 and 1 (pixels 0..31) are behind the wall; patch 2 (32..47) is half visible.
    EXPECT_EQ(c.gpuCulled, 2u);
    EXPECT_EQ(c.cpuCulled, 2u);
  }
}

// Sub-pixel patches (docs/algorithms/occlusion.md, "Sub-pixel patches"): a 100 x 100 torus
// at level 1 (10,000 patches) on a 32 x 32 image, a fraction of a pixel each, reproduces
// the false culls of the 700 x 700 torus at 256 x 256: without the depth clamp of the patch
// draw (patch.tesc, patch.frag), view 19 of these views has a patch whose rasterized depth
// lies below all its control points' depths (lavapipe extrapolates depth past its thin
// triangles), and the reference and the kernel, which bound depth by the control points,
// both cull it.
PatchSet subPixelTorus() {
  PatchOptions po;
  po.isolationLevel = 1;
  return extractPatches(scene::torus(100, 100), po).patches;
}

std::vector<frame::Camera> subPixelTorusViews(const PatchSet& set) {
  frame::ViewSetOptions vo;
  vo.count = 30;
  vo.width = vo.height = 32;
  return frame::randomViews(frame::boundsOf(set.points), vo);
}

// Calls f(patch, x, y, depth) for every pixel of `target` that a patch owns (item buffer).
template <class F>
void forEachPatchPixel(vulkan::Context& context, const frame::RenderTarget& target,
                       uint32_t patchCount, F f) {
  const std::vector<uint32_t> items = target.readItems(context);
  const std::vector<float> depth = target.readDepth(context);
  for (uint32_t i = 0; i < items.size(); ++i) {
    if (items[i] == shader::kItemBackground) continue;
    const uint32_t p = items[i] - 1;
    ASSERT_LT(p, patchCount);
    f(p, i % target.width(), i / target.width(), depth[i]);
  }
}

// The property the cull rests on, pixel by pixel: the depth stored for a pixel a patch owns
// is never in front of that patch's nearest depth as the reference bounds it
// (bound::hizScreenBox), and the pixel lies in its box.
// Fails without the clamp (view 19: depth 0.823346 where the control points start at
// 0.823423).
TEST_F(HiZOcclusionTest, NoFragmentOfASubPixelPatchLiesInFrontOfItsControlPoints) {
  const PatchSet set = subPixelTorus();
  ASSERT_EQ(set.patchCount(), 10000u);
  const auto cameras = subPixelTorusViews(set);
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 32, 32);
  frame::Renderer renderer(context());
  frame::VisibilityOracle oracle(context());
  frame::TessellationOptions tess;
  tess.uniformLevel = 4;
  uint32_t pixels = 0, clampedAtTheBound = 0;
  for (uint32_t v = 17; v < 22; ++v) {
    const frame::Camera& camera = cameras[v];
    oracle.query(renderer, target, camera, gpu, &set, {}, tess);
    const glm::dmat4 vp = camera.viewProjection();
    forEachPatchPixel(
        context(), target, set.patchCount(), [&](uint32_t p, uint32_t x, uint32_t y, float depth) {
          const bound::HiZScreenBox box = bound::hizScreenBox(set.controlPoints(p), vp, 32, 32);
          ASSERT_TRUE(box.valid) << "view " << v << " patch " << p;
          EXPECT_TRUE(x >= box.x0 && x <= box.x1 && y >= box.y0 && y <= box.y1)
              << "view " << v << " patch " << p << " pixel " << x << ", " << y;
          EXPECT_GE(double{depth}, box.nearestDepth)
              << "view " << v << " patch " << p << " pixel " << x << ", " << y;
          ++pixels;
          clampedAtTheBound += double{depth} - box.nearestDepth < 1e-5;
        });
  }
  std::printf("%u pixels checked, %u within 1e-5 of their patch's nearest depth\n", pixels,
              clampedAtTheBound);
  EXPECT_GT(pixels, 5u * 32 * 32 / 10);  // the torus fills much of each view
}

TEST_F(HiZOcclusionTest, SubPixelPatchesOfAClosedTorusAreNeverFalselyCulled) {
  const PatchSet set = subPixelTorus();
  ASSERT_EQ(set.patchCount(), 10000u);  // one regular patch per quad
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 4;
  frame::CullVerifier verifier(context(), set, {"hiz"}, {true, "closed torus"}, options);
  const auto cameras = subPixelTorusViews(set);
  for (uint32_t v = 17; v < 22; ++v) verifier.verifyView(cameras[v]);
  const frame::MethodTotals& t = verifier.totals().at(0);
  EXPECT_EQ(t.falseCulls, 0u);
  EXPECT_EQ(t.notInReference, 0u);
  EXPECT_GT(t.culled, t.patchViews / 4);  // the back half of the torus is still culled
}

// Displaced sub-pixel patches (docs/algorithms/occlusion.md, "Displaced patches"): the same
// torus with planar texture coordinates and the procedural map. The displaced draw clamps fragment
// depth to the nearest corner of the boxes p_i ± max|D| around the control points (patch.tesc,
// common/displaced_reach.glsl), the depth the displaced kernels and their reference
// (bound::displacedReachCorners) bound the fragments with. Pixel by pixel, over 30 random views:
// every pixel a patch owns lies in the screen box of its displaced bound and its depth is not in
// front of that nearest depth. Without the clamp (RenderOptions::clampDepthToControlPoints false,
// drawn too) the rasterizer puts fragments in front of it, so the check has teeth.
struct DisplacedTorus {
  PatchExtraction ex;
  bound::DisplacementMap map;
};

// `relativeScale`: the map's scale over the torus's bounding radius.
DisplacedTorus displacedSubPixelTorus(double relativeScale) {
  PatchOptions po;
  po.isolationLevel = 1;
  PatchExtraction ex = extractPatches(test::withPlanarUVs(scene::torus(100, 100)), po);
  const double scale = relativeScale * frame::boundsOf(ex.patches.points).radius();
  return {std::move(ex),
          bound::DisplacementMap("procedural", 128, 128,
                                 scene::proceduralDisplacementTexels(128, 4), scale, 0.5)};
}

TEST_F(HiZOcclusionTest, NoFragmentOfASubPixelDisplacedPatchLiesInFrontOfItsDisplacedBound) {
  // A small displacement (max |D| about 0.2% of a patch's side): the boxes around the
  // control points are then tight enough for the rasterizer's extrapolation to leave them
  // without the clamp (2 pixels over these views; at 5e-4 and above the boxes absorb it
  // here, which no margin can promise in general).
  const DisplacedTorus torus = displacedSubPixelTorus(1e-4);
  const PatchSet& set = torus.ex.patches;
  ASSERT_EQ(set.patchCount(), 10000u);
  const std::vector<bound::DisplacedPatch> data = bound::buildDisplacedPatches(
      set, torus.ex.uvCorners, torus.map, bound::DisplacedExtension::Full);
  frame::GpuPatchSet gpu(context(), set);
  frame::GpuDisplacement displacement(context(), torus.map, torus.ex.uvCorners, set.patchCount());
  gpu.setDisplacement(&displacement);
  frame::RenderTarget target(context(), 32, 32);
  frame::Renderer renderer(context());
  const auto cameras = subPixelTorusViews(set);
  struct Count {
    uint32_t pixels = 0, outsideBox = 0, inFront = 0;
  };
  Count counts[2];  // [0]: clamped (the default draw), [1]: not clamped
  for (int clamp = 0; clamp < 2; ++clamp) {
    frame::RenderOptions options;
    options.tessellation.uniformLevel = 4;
    options.clampDepthToControlPoints = clamp == 0;
    Count& c = counts[clamp];
    for (uint32_t v = 0; v < cameras.size(); ++v) {
      const frame::Camera& camera = cameras[v];
      renderer.render(target, camera, gpu, &set, options);
      const glm::dmat4 vp = camera.viewProjection();
      forEachPatchPixel(
          context(), target, set.patchCount(),
          [&](uint32_t p, uint32_t x, uint32_t y, float depth) {
            const bound::DisplacedBound b = bound::displacedBound(
                set.controlPoints(p), data[p], bound::DisplacedExtension::Full,
                bound::DisplacedBox::OOBB, camera.view, camera.projection);
            const std::vector<glm::dvec3> reach =
                bound::displacedReachCorners(set.controlPoints(p), data[p].range.maxAbs());
            const bound::HiZDepthPoints nearest{reach, vp};
            const bound::HiZScreenBox box =
                bound::hizScreenBox(b.corners, b.toClip, 32, 32, 1.0, &nearest);
            ASSERT_TRUE(box.valid) << "view " << v << " patch " << p;
            ++c.pixels;
            c.outsideBox += !(x >= box.x0 && x <= box.x1 && y >= box.y0 && y <= box.y1);
            const bool inFront = double{depth} < box.nearestDepth;
            c.inFront += inFront;
            if (clamp == 0 && inFront && c.inFront == 1)
              ADD_FAILURE() << "first: view " << v << " patch " << p << " pixel " << x << ", " << y
                            << ": depth " << depth << " < " << box.nearestDepth;
          });
    }
  }
  std::printf("clamped: %u pixels, %u in front of the bound; not clamped: %u pixels, %u in front\n",
              counts[0].pixels, counts[0].inFront, counts[1].pixels, counts[1].inFront);
  EXPECT_EQ(counts[0].outsideBox, 0u);
  EXPECT_EQ(counts[0].inFront, 0u);
  EXPECT_GT(counts[0].pixels, 30u * 32 * 32 / 8);  // the torus fills a fifth of each view
  // The clamp is what makes the bound hold: the unclamped draw breaks it.
  EXPECT_GT(counts[1].inFront, 0u);
}

// The same torus through CullVerifier with the displaced kernels and Hi-Z occlusion: no
// false cull against the oracle of the displaced draw, every GPU cull a reference cull.
TEST_F(HiZOcclusionTest, SubPixelDisplacedPatchesAreNeverFalselyCulled) {
  const DisplacedTorus torus = displacedSubPixelTorus(0.02);
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 4;
  options.displacementMap = &torus.map;
  options.uvCorners = torus.ex.uvCorners;
  const std::vector<std::string> kernels = {"full-oobb", "con-caf"};
  frame::CullVerifier verifier(context(), torus.ex.patches, kernels, {false, "displaced torus"},
                               options);
  const auto cameras = subPixelTorusViews(torus.ex.patches);
  for (uint32_t v = 0; v < cameras.size(); v += 3) verifier.verifyView(cameras[v]);
  for (const frame::MethodTotals& t : verifier.totals()) {
    EXPECT_EQ(t.falseCulls, 0u) << t.name;
    EXPECT_EQ(t.notInReference, 0u) << t.name;
    EXPECT_GT(t.culled, 0u) << t.name;
  }
}

}  // namespace
}  // namespace osd_cull
