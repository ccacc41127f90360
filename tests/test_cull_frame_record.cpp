// The frame records into one command buffer: render() is one submission (the diagnostic
// mode one per pass), record() never submits, and the statistics read frames later from
// the ring equal the ones read right after each frame.
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/query.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace osd_cull {
namespace {

class CullFrameRecordTest : public test::VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    renderer_ = std::make_unique<frame::Renderer>(context());
    scene_ = scene::defaultScene();
    gpu_ = std::make_unique<frame::GpuPatchSet>(context(), scene_.patches);
    for (const auto& m : scene_.occluders) occluderMeshes_.emplace_back(context(), m);
    for (const auto& m : occluderMeshes_) occluders_.push_back(&m);
    bounds_ = frame::boundsOf(scene_.patches.points);
  }
  void TearDown() override {
    occluders_.clear();
    occluderMeshes_.clear();
    renderer_.reset();
    gpu_.reset();
    VkTest::TearDown();
  }

  frame::Camera camera(double degrees) const {
    const frame::Camera base =
        frame::frameBounds(bounds_, scene_.viewDirection, scene_.up, 40.0, kW, kH);
    return frame::orbit(base, bounds_.center(), scene_.up, degrees);
  }

  // All stages (the built-in scene's cages are closed and outward), tessellation 4.
  frame::CullFrameOptions options(bool aggressive) const {
    frame::CullFrameOptions o;
    o.render.tessellation.uniformLevel = 4;
    o.cull = {true, "tangent-plane", "hiz", {true, "built-in scene: closed, outward cages"}};
    o.firstFrame = frame::FirstFrame::HalfVisible;
    o.aggressive = aggressive;
    return o;
  }

  static void expectEqualStats(const frame::CullFrameStats& a, const frame::CullFrameStats& b,
                               int frame) {
    EXPECT_EQ(a.patchesTotal, b.patchesTotal) << "frame " << frame;
    EXPECT_EQ(a.drawnPass1, b.drawnPass1) << "frame " << frame;
    EXPECT_EQ(a.drawnPass2, b.drawnPass2) << "frame " << frame;
    EXPECT_EQ(a.survivors, b.survivors) << "frame " << frame;
    EXPECT_EQ(a.newlyVisible, b.newlyVisible) << "frame " << frame;
    EXPECT_EQ(a.culledFrustum, b.culledFrustum) << "frame " << frame;
    EXPECT_EQ(a.culledBackPatch, b.culledBackPatch) << "frame " << frame;
    EXPECT_EQ(a.culledOcclusion, b.culledOcclusion) << "frame " << frame;
    EXPECT_EQ(a.pass1.tessEvaluationInvocations, b.pass1.tessEvaluationInvocations)
        << "frame " << frame;
    EXPECT_EQ(a.pass2.tessEvaluationInvocations, b.pass2.tessEvaluationInvocations)
        << "frame " << frame;
    EXPECT_EQ(a.pass1.clippingPrimitives, b.pass1.clippingPrimitives) << "frame " << frame;
    EXPECT_EQ(a.pass2.tessControlPatches, b.pass2.tessControlPatches) << "frame " << frame;
  }

  static constexpr uint32_t kW = 160, kH = 120;
  scene::Scene scene_;
  std::unique_ptr<frame::GpuPatchSet> gpu_;
  std::vector<frame::GpuTriangleMesh> occluderMeshes_;
  std::vector<const frame::GpuTriangleMesh*> occluders_;
  std::unique_ptr<frame::Renderer> renderer_;
  frame::Bounds bounds_;
};

TEST_F(CullFrameRecordTest, ANormalFrameIsOneSubmissionAndTheDiagnosticModeOnePerPass) {
  frame::RenderTarget target(context(), kW, kH);
  const frame::CullMesh meshes[] = {{gpu_.get(), &scene_.patches}};
  for (bool aggressive : {false, true}) {
    frame::CullFrameOptions o = options(aggressive);
    frame::CullFrame cull(context(), *renderer_, target, meshes, o);
    for (int f = 0; f < 3; ++f) {
      const uint64_t before = context().submissionCount();
      const frame::CullFrameStats s = cull.render(camera(10.0 * f), occluders_);
      EXPECT_EQ(context().submissionCount() - before, 1u) << "frame " << f;
      EXPECT_EQ(s.frame, uint64_t(f));
      EXPECT_GT(s.frameMs, 0.0);
      EXPECT_EQ(s.pass1Ms + s.pyramidMs + s.cullMs + s.pass2Ms, 0.0);
      EXPECT_GT(s.pass1.tessEvaluationInvocations, 0u);
      EXPECT_EQ(s.survivors + s.culled(), s.patchesTotal);
    }
    o.timePasses = true;
    cull.setOptions(o);
    const uint64_t before = context().submissionCount();
    const frame::CullFrameStats s = cull.render(camera(30.0), occluders_);
    EXPECT_EQ(context().submissionCount() - before, 4u);  // pass 1, pyramid, cull, pass 2
    EXPECT_GT(s.pass1Ms, 0.0);
    EXPECT_GT(s.pyramidMs, 0.0);
    EXPECT_GT(s.cullMs, 0.0);
    EXPECT_GT(s.pass2Ms, 0.0);
  }
}

TEST_F(CullFrameRecordTest, EveryFrameCarriesPerStageGpuTimesFromItsOneSubmission) {
  if (!vulkan::TimestampQuery::unavailableReason(context()).empty())
    GTEST_SKIP() << vulkan::TimestampQuery::unavailableReason(context());
  frame::RenderTarget target(context(), kW, kH);
  const frame::CullMesh meshes[] = {{gpu_.get(), &scene_.patches}};
  for (bool aggressive : {false, true}) {
    frame::CullFrame cull(context(), *renderer_, target, meshes, options(aggressive));
    for (int f = 0; f < 3; ++f) {
      const frame::CullFrameStats s = cull.render(camera(12.0 * f), occluders_);
      const frame::CullStageTimes& t = s.gpu;
      ASSERT_TRUE(t.measured()) << s.gpuNote;
      EXPECT_TRUE(s.gpuNote.empty());
      EXPECT_GT(t.pass1, 0.0);
      EXPECT_GT(t.pyramid, 0.0);
      EXPECT_GT(t.cull, 0.0);
      EXPECT_GE(t.pass2, 0.0);
      EXPECT_NEAR(t.pass1 + t.pyramid + t.cull + t.pass2, t.total, 1e-6 * t.total);
      // The device's clock runs inside the host's: the GPU span of the frame fits in the
      // wall time of its recording, submission and wait.
      EXPECT_LE(t.total, s.frameMs * 1.01 + 0.05) << "frame " << f;
      if (aggressive) {
        EXPECT_LT(t.pass2, t.pass1) << "no second pass";
      }
    }
  }
}

TEST_F(CullFrameRecordTest, WithoutTimestampsTheStageTimesAreNaNWithAReason) {
  frame::RenderTarget target(context(), kW, kH);
  const frame::CullMesh meshes[] = {{gpu_.get(), &scene_.patches}};
  frame::CullFrameOptions o = options(false);
  o.gpuTimes = false;
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  const frame::CullFrameStats s = cull.render(camera(5.0), occluders_);
  EXPECT_FALSE(s.gpu.measured());
  EXPECT_TRUE(std::isnan(s.gpu.pass1) && std::isnan(s.gpu.pyramid) && std::isnan(s.gpu.cull) &&
              std::isnan(s.gpu.pass2));
  EXPECT_NE(s.gpuNote.find("gpuTimes"), std::string::npos) << s.gpuNote;
  EXPECT_GT(s.pass1.tessEvaluationInvocations, 0u);  // the rest of the statistics as always
}

TEST_F(CullFrameRecordTest, DelayedStatisticsEqualTheImmediateOnes) {
  // Two frames of the same view: one rendered and read at once, one recorded into our
  // command buffers and read two frames later.
  for (bool aggressive : {false, true}) {
    frame::RenderTarget a(context(), kW, kH), b(context(), kW, kH);
    const frame::CullMesh meshes[] = {{gpu_.get(), &scene_.patches}};
    frame::CullFrame immediate(context(), *renderer_, a, meshes, options(aggressive));
    frame::CullFrame delayed(context(), *renderer_, b, meshes, options(aggressive));
    constexpr int kFrames = 6, kDelay = 2;
    std::vector<frame::CullFrameStats> now;
    std::vector<uint64_t> ids;
    for (int f = 0; f < kFrames + kDelay; ++f) {
      if (f < kFrames) {
        const frame::Camera cam = camera(8.0 * f);
        now.push_back(immediate.render(cam, occluders_));
        context().submit([&](VkCommandBuffer cmd) {
          ids.push_back(delayed.record(cmd, cam, occluders_));
          // Recorded, not submitted: nothing to read yet, and asking does not wait.
          EXPECT_FALSE(delayed.stats(ids.back()).has_value());
        });
      }
      if (f >= kDelay) {
        const int n = f - kDelay;
        const std::optional<frame::CullFrameStats> late = delayed.stats(ids[n]);
        ASSERT_TRUE(late.has_value()) << "frame " << n;
        EXPECT_EQ(late->frame, ids[n]);
        expectEqualStats(*late, now[n], n);
        EXPECT_EQ(late->gpu.measured(), now[n].gpu.measured()) << late->gpuNote;
      }
    }
    EXPECT_GT(now.back().culledOcclusion + now.back().culledBackPatch, 0u);
    // Slots are reused after statsSlots (3) frames.
    EXPECT_FALSE(delayed.stats(ids[0]).has_value());
    EXPECT_FALSE(delayed.stats(ids.back() + 1).has_value());
  }
}

TEST_F(CullFrameRecordTest, RecordingOverAnUnfinishedFrameIsAnError) {
  frame::RenderTarget target(context(), kW, kH);
  const frame::CullMesh meshes[] = {{gpu_.get(), &scene_.patches}};
  frame::CullFrameOptions o = options(false);
  o.statsSlots = 1;
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  cull.render(camera(0.0), occluders_);
  context().submit([&](VkCommandBuffer cmd) {
    cull.record(cmd, camera(5.0), occluders_);
    // Frame 1 is recorded, not finished: its slot cannot take frame 2.
    EXPECT_THROW(cull.record(cmd, camera(10.0), occluders_), Error);
  });
  o.statsSlots = 0;
  EXPECT_THROW(frame::CullFrame(context(), *renderer_, target, meshes, o), Error);
}

}  // namespace
}  // namespace osd_cull
