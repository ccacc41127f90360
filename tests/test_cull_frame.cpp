// The two-pass frame with temporal visibility (Niessner & Loop §3): the image equals the
// unculled image frame after frame, occlusion-culled patches are invisible in the oracle,
// both draw modes and every first-frame policy agree, at odd and tiny sizes and with the
// camera inside the scene, with all cull stages in one kernel, for several meshes and
// several views sharing them.
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/scene/demo_shapes.h"
#include "support/cull_test_meshes.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>
#include <osd_cull/shared/draw_layout.h>

#include <cstdio>

namespace osd_cull {
namespace {

using frame::CullDrawMode;
using frame::FirstFrame;

struct ImageDiff {
  uint32_t uncovered = 0;  ///< covered without culling, background with culling
  uint32_t different = 0;  ///< item or color differs
  uint32_t pixels = 0;
};

class CullFrameTest : public test::VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    renderer_ = std::make_unique<frame::Renderer>(context());
    use(scene::defaultScene());
  }

  void use(scene::Scene scene) {
    occluders_.clear();
    occluderMeshes_.clear();
    scene_ = std::move(scene);
    gpu_ = std::make_unique<frame::GpuPatchSet>(context(), scene_.patches);
    for (const auto& m : scene_.occluders) occluderMeshes_.emplace_back(context(), m);
    for (const auto& m : occluderMeshes_) occluders_.push_back(&m);
    bounds_ = frame::boundsOf(scene_.patches.points);
  }

  // BigGuy (y up) with a wall in front of its legs.
  void useBigGuy(int level) {
    test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "characters" / "bigguy.obj", level);
    scene::Scene s;
    s.patches = std::move(mesh.patches);
    s.occluders.push_back(
        frame::quadMesh({-30, -30, 12}, {30, -30, 12}, {30, -2, 12}, {-30, -2, 12}));
    s.up = {0, 1, 0};
    s.viewDirection = {0.3, 0.25, 1.0};
    use(std::move(s));
    validity_ = mesh.validity;
  }
  void TearDown() override {
    occluders_.clear();
    occluderMeshes_.clear();
    renderer_.reset();
    gpu_.reset();
    VkTest::TearDown();
  }

  frame::Camera camera(uint32_t w, uint32_t h, double degrees) const {
    const frame::Camera base =
        frame::frameBounds(bounds_, scene_.viewDirection, scene_.up, 40.0, w, h);
    return frame::orbit(base, bounds_.center(), scene_.up, degrees);
  }

  frame::CullMesh mesh() { return {gpu_.get(), &scene_.patches}; }

  static frame::CullFrameOptions options(CullDrawMode mode, FirstFrame first, bool aggressive) {
    frame::CullFrameOptions o;
    o.render.tessellation.uniformLevel = 4;
    o.drawMode = mode;
    o.firstFrame = first;
    o.aggressive = aggressive;
    return o;
  }

  // Frustum, tangent-plane back-patch (where valid for the mesh) and Hi-Z occlusion.
  frame::CullFrameOptions allStages(frame::CullFrameOptions o) const {
    o.cull = {true, "tangent-plane", "hiz", validity_};
    return o;
  }

  // The culled frame in `culled` against everything drawn into `reference`.
  ImageDiff compare(frame::RenderTarget& culled, frame::RenderTarget& reference,
                    const frame::Camera& cam, const frame::RenderOptions& render) {
    const frame::PatchDraw draw{gpu_.get(), &scene_.patches, 0};
    renderer_->render(reference, cam, {&draw, 1}, occluders_, render);
    const auto a = culled.readItems(context()), b = reference.readItems(context());
    const auto ca = culled.readColor(context()), cb = reference.readColor(context());
    ImageDiff d;
    d.pixels = static_cast<uint32_t>(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
      if (b[i] != 0 && a[i] == 0) ++d.uncovered;
      bool differs = a[i] != b[i];
      for (int c = 0; c < 4; ++c) differs = differs || ca[4 * i + c] != cb[4 * i + c];
      d.different += differs;
    }
    return d;
  }

  // Runs `frames` frames orbiting by `step` degrees; every final image is compared (the
  // aggressive mode from the second frame on at a standstill only).
  // Returns the culls of all frames summed.
  frame::CullFrameStats expectSameImages(uint32_t w, uint32_t h, const frame::CullFrameOptions& o,
                                         int frames, double step,
                                         frame::Camera (*override)(uint32_t, uint32_t) = nullptr) {
    frame::CullFrameStats total;
    frame::RenderTarget target(context(), w, h), reference(context(), w, h);
    const frame::CullMesh meshes[] = {mesh()};
    frame::CullFrame cull(context(), *renderer_, target, meshes, o);
    for (int f = 0; f < frames; ++f) {
      const frame::Camera cam = override ? override(w, h) : camera(w, h, step * f);
      const frame::CullFrameStats s = cull.render(cam, occluders_);
      total.culledFrustum += s.culledFrustum;
      total.culledBackPatch += s.culledBackPatch;
      total.culledOcclusion += s.culledOcclusion;
      EXPECT_EQ(s.patchesTotal, scene_.patches.patchCount());
      EXPECT_EQ(s.survivors + s.culled(), s.patchesTotal);
      const ImageDiff d = compare(target, reference, cam, o.render);
      EXPECT_EQ(d.uncovered, 0u) << w << "x" << h << " frame " << f << " mode "
                                 << toString(o.drawMode) << " first " << toString(o.firstFrame);
      EXPECT_EQ(d.different, 0u) << d.different << " pixels differ, " << w << "x" << h << " frame "
                                 << f;
    }
    return total;
  }

  void expectCulledPatchesInvisible(uint32_t w, uint32_t h, int views, double step,
                                    uint32_t minCulled);

  scene::Scene scene_;
  std::unique_ptr<frame::GpuPatchSet> gpu_;
  std::vector<frame::GpuTriangleMesh> occluderMeshes_;
  std::vector<const frame::GpuTriangleMesh*> occluders_;
  std::unique_ptr<frame::Renderer> renderer_;
  frame::Bounds bounds_;
  // The built-in scene's objects are closed cages with outward normals.
  bound::BackPatchValidity validity_{true, "built-in scene: closed, outward cages"};
};

TEST_F(CullFrameTest, FilteredFramesEqualTheUnculledImageOverAMovingCamera) {
  expectSameImages(200, 150, options(CullDrawMode::Filtered, FirstFrame::AllVisible, false), 8,
                   6.0);
}

TEST_F(CullFrameTest, BigGuyFramesEqualTheUnculledImageOverAMovingCamera) {
  OSD_CULL_REQUIRE_DATA();
  useBigGuy(1);
  expectSameImages(180, 180, options(CullDrawMode::Filtered, FirstFrame::HalfVisible, false), 5,
                   9.0);
}

TEST_F(CullFrameTest, AllStagesInOneKernelKeepTheImage) {
  // Frustum, back-patch and occlusion in the same dispatch, from a camera close enough that
  // parts of the scene leave the view.
  auto close = [](uint32_t w, uint32_t h) {
    return frame::Camera::lookAt({4.5, -3.0, 2.0}, {0.5, 1.0, 0.0}, {0, 0, 1}, 35.0, w, h, 0.05,
                                 30.0);
  };
  const auto total = expectSameImages(
      200, 150, allStages(options(CullDrawMode::Filtered, FirstFrame::AllVisible, false)), 3, 0.0,
      close);
  EXPECT_GT(total.culledFrustum, 0u);
  EXPECT_GT(total.culledBackPatch, 0u);
  EXPECT_GT(total.culledOcclusion, 0u);
  const auto orbiting = expectSameImages(
      200, 150, allStages(options(CullDrawMode::TessFactorZero, FirstFrame::NoneVisible, false)), 5,
      8.0);
  EXPECT_GT(orbiting.culledBackPatch, 0u);
  EXPECT_GT(orbiting.culledOcclusion, 0u);
}

TEST_F(CullFrameTest, BigGuyWithAllStagesKeepsTheImage) {
  OSD_CULL_REQUIRE_DATA();
  useBigGuy(1);
  ASSERT_TRUE(validity_.enabled) << validity_.reason;
  const auto total = expectSameImages(
      180, 180, allStages(options(CullDrawMode::Filtered, FirstFrame::AllVisible, false)), 5, 12.0);
  EXPECT_GT(total.culledBackPatch, 0u);
  EXPECT_GT(total.culledOcclusion, 0u);
}

// The cull kernel runs the occlusion test before it hands a patch to the listed-triangle
// pass (shaders/cull/cull_main.glsl): a hidden patch is culled by occlusion and never listed,
// and every patch the listing culls was tested and found not hidden. Same image.
TEST_F(CullFrameTest, HiddenPatchesAreCulledByOcclusionBeforeAnyTriangleIsListed) {
  OSD_CULL_REQUIRE_DATA();
  useBigGuy(1);
  ASSERT_TRUE(validity_.enabled) << validity_.reason;
  frame::CullFrameOptions o = options(CullDrawMode::Filtered, FirstFrame::AllVisible, false);
  o.cull = {true, "ncone", "hiz", validity_};
  o.render.tessellation.uniformLevel = 1;  // the listed test decides where the bound keeps
  const auto total = expectSameImages(180, 180, o, 3, 12.0);
  EXPECT_GT(total.culledBackPatch, 0u);
  EXPECT_GT(total.culledOcclusion, 0u);
  frame::RenderTarget target(context(), 180, 180);
  const frame::CullMesh meshes[] = {mesh()};
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  for (int f = 0; f < 3; ++f) cull.render(camera(180, 180, 12.0 * f), occluders_);
  uint32_t listedCulls = 0, hiddenCandidates = 0;
  for (const uint32_t v : cull.cullPass(0)->results(cull.instanceInPass(0))) {
    const bound::CullCode c{v};
    // Culled by the listing: its occlusion verdict was computed first, and said visible.
    if (c.stage() == shader::kStageBackPatch && c.occlusion() != 0xFFu) {
      ++listedCulls;
      EXPECT_NE(c.occlusion(), 0u) << bound::describe(c);
    }
    // Kept by the bound, hidden: culled by occlusion without a listing.
    hiddenCandidates +=
        c.stage() == shader::kStageOcclusion && c.backPatch() == shader::kVerdictDrawnTriangles;
  }
  EXPECT_GT(listedCulls, 0u);
  EXPECT_GT(hiddenCandidates, 0u);
}

TEST_F(CullFrameTest, TessFactorZeroFramesEqualTheUnculledImageOverAMovingCamera) {
  expectSameImages(200, 150, options(CullDrawMode::TessFactorZero, FirstFrame::AllVisible, false),
                   6, 6.0);
}

TEST_F(CullFrameTest, EveryFirstFramePolicyGivesTheSameImage) {
  for (FirstFrame first :
       {FirstFrame::AllVisible, FirstFrame::HalfVisible, FirstFrame::NoneVisible})
    expectSameImages(160, 120, options(CullDrawMode::Filtered, first, false), 2, 10.0);
}

TEST_F(CullFrameTest, NonPowerOfTwoAndTinyImages) {
  for (auto [w, h] :
       {std::pair{333u, 517u}, std::pair{1u, 1u}, std::pair{2u, 3u}, std::pair{37u, 5u}})
    expectSameImages(w, h, options(CullDrawMode::Filtered, FirstFrame::NoneVisible, false), 2,
                     15.0);
}

TEST_F(CullFrameTest, CameraInsideTheScene) {
  // Inside the default mesh (a closed object around the origin), near plane close.
  auto insideObject = [](uint32_t w, uint32_t h) {
    return frame::Camera::lookAt({0.2, 0.4, 0.1}, {-1.3, 2.8, 0.0}, {0, 0, 1}, 70.0, w, h, 0.01,
                                 20.0);
  };
  // Between the objects, just in front of the wall, the pole sphere behind it.
  auto betweenObjects = [](uint32_t w, uint32_t h) {
    return frame::Camera::lookAt({-1.2, 1.1, 0.2}, {-1.3, 2.8, 0.0}, {0, 0, 1}, 90.0, w, h, 0.01,
                                 20.0);
  };
  expectSameImages(160, 120, options(CullDrawMode::Filtered, FirstFrame::AllVisible, false), 3, 0.0,
                   insideObject);
  expectSameImages(160, 120, options(CullDrawMode::Filtered, FirstFrame::NoneVisible, false), 3,
                   0.0, betweenObjects);
}

TEST_F(CullFrameTest, OcclusionCulledPatchesHaveNoPixelsInTheOracle) {
  expectCulledPatchesInvisible(160, 120, 24, 15.0, 24);
}

TEST_F(CullFrameTest, OcclusionCulledBigGuyPatchesHaveNoPixelsInTheOracle) {
  OSD_CULL_REQUIRE_DATA();
  useBigGuy(1);
  expectCulledPatchesInvisible(128, 128, 8, 45.0, 3226);
}

void CullFrameTest::expectCulledPatchesInvisible(uint32_t w, uint32_t h, int views, double step,
                                                 uint32_t minCulled) {
  frame::RenderTarget target(context(), w, h), oracleTarget(context(), w, h);
  const frame::CullMesh meshes[] = {mesh()};
  auto o = options(CullDrawMode::Filtered, FirstFrame::AllVisible, false);
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  frame::VisibilityOracle oracle(context());
  uint32_t culled = 0, invisible = 0;
  for (int f = 0; f < views; ++f) {
    const frame::Camera cam = camera(w, h, step * f);
    const auto s = cull.render(cam, occluders_);
    const auto counts = oracle.query(*renderer_, oracleTarget, cam, *gpu_, &scene_.patches,
                                     occluders_, o.render.tessellation);
    const auto results = cull.readResults(0);
    for (uint32_t p = 0; p < results.size(); ++p) {
      if ((results[p] & 0xFu) != shader::kStageOcclusion) continue;
      ++culled;
      EXPECT_EQ(counts.pixels[p], 0u) << "frame " << f << " patch " << p;
    }
    invisible += s.patchesTotal - counts.visiblePatchCount();
    EXPECT_EQ(s.culledOcclusion,
              static_cast<uint32_t>(std::count_if(results.begin(), results.end(), [](uint32_t r) {
                return (r & 0xFu) == shader::kStageOcclusion;
              })));
  }
  std::printf("occlusion-culled %u, oracle-invisible %u (%d views)\n", culled, invisible, views);
  EXPECT_GT(culled, minCulled);
}

TEST_F(CullFrameTest, AggressiveModeSkipsTheSecondPassAndCatchesUpNextFrame) {
  const uint32_t w = 160, h = 120;
  frame::RenderTarget target(context(), w, h), reference(context(), w, h);
  const frame::CullMesh meshes[] = {mesh()};
  const auto o = options(CullDrawMode::Filtered, FirstFrame::NoneVisible, true);
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  const frame::Camera cam = camera(w, h, 30.0);
  const auto first = cull.render(cam, occluders_);
  EXPECT_EQ(first.drawnPass1, 0u);  // nothing was visible before
  EXPECT_EQ(first.drawnPass2, 0u);  // and the second pass is skipped
  EXPECT_GT(first.newlyVisible, 0u);
  EXPECT_EQ(first.pass2.tessEvaluationInvocations, 0u);
  EXPECT_GT(compare(target, reference, cam, o.render).uncovered, 0u);  // one frame late
  const auto second = cull.render(cam, occluders_);
  EXPECT_EQ(second.drawnPass1, first.survivors);
  const ImageDiff d = compare(target, reference, cam, o.render);
  EXPECT_EQ(d.uncovered, 0u);
  EXPECT_EQ(d.different, 0u);
}

TEST_F(CullFrameTest, DrawModesDrawTheSamePatchesButTessFactorZeroRunsEveryControlShader) {
  const uint32_t w = 160, h = 120;
  frame::RenderTarget a(context(), w, h), b(context(), w, h);
  const frame::CullMesh meshes[] = {mesh()};
  frame::CullFrame filtered(context(), *renderer_, a, meshes,
                            options(CullDrawMode::Filtered, FirstFrame::AllVisible, false));
  frame::CullFrame tf0(context(), *renderer_, b, meshes,
                       options(CullDrawMode::TessFactorZero, FirstFrame::AllVisible, false));
  for (int f = 0; f < 3; ++f) {
    const frame::Camera cam = camera(w, h, 12.0 * f);
    const auto s = filtered.render(cam, occluders_);
    const auto t = tf0.render(cam, occluders_);
    EXPECT_EQ(s.drawnPass1, t.drawnPass1);
    EXPECT_EQ(s.drawnPass2, t.drawnPass2);
    EXPECT_EQ(s.pass1.tessEvaluationInvocations, t.pass1.tessEvaluationInvocations);
    EXPECT_EQ(s.pass2.tessEvaluationInvocations, t.pass2.tessEvaluationInvocations);
    // Every patch goes through the control shader in the variant, in both passes; with
    // conditional rendering not in a second pass that has nothing newly visible.
    EXPECT_EQ(t.pass1.tessControlPatches, s.patchesTotal);
    const bool skipped = context().info().optional.conditionalRendering && t.drawnPass2 == 0;
    EXPECT_EQ(t.pass2.tessControlPatches, skipped ? 0u : s.patchesTotal) << "frame " << f;
    EXPECT_EQ(s.pass1.tessControlPatches, s.drawnPass1);
    EXPECT_EQ(s.pass2.tessControlPatches, s.drawnPass2);
    EXPECT_EQ(a.readItems(context()), b.readItems(context()));
  }
}

TEST_F(CullFrameTest, StatusViewColorsEveryPatch) {
  const uint32_t w = 96, h = 64;
  frame::RenderTarget target(context(), w, h), view(context(), w, h);
  const frame::CullMesh meshes[] = {mesh()};
  frame::CullFrame cull(context(), *renderer_, target, meshes,
                        options(CullDrawMode::Filtered, FirstFrame::AllVisible, false));
  cull.render(camera(w, h, 0.0), occluders_);
  const auto s = cull.renderStatusView(view, camera(w, h, 180.0), occluders_);
  EXPECT_EQ(s.patchesDrawn, scene_.patches.patchCount());
}

TEST_F(CullFrameTest, TwoViewsShareTheMeshesWithTheirOwnStatus) {
  // Two cameras looking from opposite sides at the same patch set: each view keeps its own
  // visibility, so each frame is right for its camera although the other view sees the
  // back of what it sees.
  const uint32_t w = 128, h = 96;
  frame::RenderTarget a(context(), w, h), b(context(), w, h), reference(context(), w, h);
  const frame::CullMesh meshes[] = {mesh()};
  const auto o = options(CullDrawMode::Filtered, FirstFrame::AllVisible, false);
  frame::CullFrame front(context(), *renderer_, a, meshes, o);
  frame::CullFrame back(context(), *renderer_, b, meshes, o);
  frame::CullFrameStats lastA, lastB;
  for (int f = 0; f < 3; ++f) {
    const frame::Camera ca = camera(w, h, 5.0 * f), cb = camera(w, h, 180.0 + 5.0 * f);
    const auto sa = front.render(ca, occluders_);
    const auto sb = back.render(cb, occluders_);
    if (f > 0) {  // each view's first pass draws what survived in that view
      EXPECT_EQ(sa.drawnPass1, lastA.survivors);
      EXPECT_EQ(sb.drawnPass1, lastB.survivors);
    }
    lastA = sa;
    lastB = sb;
    const ImageDiff da = compare(a, reference, ca, o.render);
    const ImageDiff db = compare(b, reference, cb, o.render);
    EXPECT_EQ(da.uncovered + db.uncovered, 0u) << "frame " << f;
    EXPECT_EQ(da.different + db.different, 0u) << "frame " << f;
    EXPECT_GT(sa.culledOcclusion, 0u);
    EXPECT_GT(sb.culledOcclusion, 0u);
  }
  // The views disagree about which patches are visible.
  const auto statusA = front.visibility(0).readStatus(context());
  const auto statusB = back.visibility(0).readStatus(context());
  uint32_t differ = 0;
  for (size_t p = 0; p < statusA.size(); ++p)
    differ += (statusA[p] & shader::kStatusVisible) != (statusB[p] & shader::kStatusVisible);
  EXPECT_GT(differ, statusA.size() / 10);
}

TEST_F(CullFrameTest, SeveralMeshesEachWithItsOwnStatusAndItemRange) {
  // The built-in scene and a torus patch set in front of it, as two meshes of one frame;
  // item values are itemBase(m) + p + 1.
  const PatchSet torus = scene::translated(scene::bsplineTorus({10, 6, 1.2, 0.5, {0, 0, 0}, -1}),
                                           bounds_.center() + glm::dvec3(0, -4.0, 0));
  frame::GpuPatchSet torusGpu(context(), torus);
  const uint32_t w = 160, h = 120;
  frame::RenderTarget target(context(), w, h), reference(context(), w, h);
  const frame::CullMesh meshes[] = {mesh(), {&torusGpu, &torus}};
  const auto o = options(CullDrawMode::Filtered, FirstFrame::HalfVisible, false);
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  ASSERT_EQ(cull.meshCount(), 2u);
  EXPECT_EQ(cull.itemBase(1), scene_.patches.patchCount());
  const frame::PatchDraw draws[] = {{gpu_.get(), &scene_.patches, 0},
                                    {&torusGpu, &torus, scene_.patches.patchCount()}};
  for (int f = 0; f < 3; ++f) {
    const frame::Camera cam = camera(w, h, 10.0 * f);
    const auto s = cull.render(cam, occluders_);
    EXPECT_EQ(s.patchesTotal, scene_.patches.patchCount() + torus.patchCount());
    renderer_->render(reference, cam, draws, occluders_, o.render);
    const auto items = target.readItems(context()), full = reference.readItems(context());
    uint32_t uncovered = 0, different = 0, torusPixels = 0;
    for (size_t i = 0; i < items.size(); ++i) {
      uncovered += full[i] != 0 && items[i] == 0;
      different += full[i] != items[i];
      torusPixels += items[i] > scene_.patches.patchCount() && items[i] != shader::kItemOccluder;
    }
    EXPECT_EQ(uncovered, 0u) << "frame " << f;
    EXPECT_EQ(different, 0u) << "frame " << f;
    EXPECT_GT(torusPixels, 0u);
    EXPECT_EQ(cull.readResults(1).size(), torus.patchCount());
  }
}

}  // namespace
}  // namespace osd_cull
