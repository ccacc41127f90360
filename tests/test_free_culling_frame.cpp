// The free-culling frame draws, in one pass, exactly the patches a culled frame drew: the
// same tessellation work and the same image, without any cull, pyramid or status work.
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/free_culling_frame.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/context.h"
#include "support/vk_test_context.h"

#include <osd_cull/shared/visibility_layout.h>

#include <gtest/gtest.h>

namespace osd_cull {
namespace {

using shader::kStatusNewlyVisible;
using shader::kStatusVisible;

TEST(PatchesDrawnByFrame, AreThoseVisibleBeforeAndTheNewlyVisibleOnes) {
  const uint32_t culled = shader::kStageOcclusion << shader::kStatusStageShift;
  const std::vector<uint32_t> before = {kStatusVisible, kStatusVisible, culled, culled};
  const std::vector<uint32_t> after = {kStatusVisible, culled, kStatusVisible | kStatusNewlyVisible,
                                       culled};
  EXPECT_EQ(frame::patchesDrawnByFrame(before, after, false), (std::vector<uint32_t>{0, 1, 2}));
  // Aggressive: no second pass; the newly visible patch waits for the next frame.
  EXPECT_EQ(frame::patchesDrawnByFrame(before, after, true), (std::vector<uint32_t>{0, 1}));
  EXPECT_THROW(frame::patchesDrawnByFrame(before, std::span(after).first(3), false), Error);
}

class FreeCullingFrameTest : public test::VkTest {};

TEST_F(FreeCullingFrameTest, DrawsTheCulledFramesPatchesWithItsWorkAndImage) {
  constexpr uint32_t kW = 160, kH = 120;
  scene::Scene s = scene::defaultScene();
  frame::GpuPatchSet gpu(context(), s.patches);
  std::vector<frame::GpuTriangleMesh> meshes;
  for (const auto& m : s.occluders) meshes.emplace_back(context(), m);
  std::vector<const frame::GpuTriangleMesh*> occluders;
  for (const auto& m : meshes) occluders.push_back(&m);
  frame::Renderer renderer(context());
  frame::RenderTarget culledTarget(context(), kW, kH), freeTarget(context(), kW, kH);
  frame::CullFrameOptions o;
  o.render.tessellation.uniformLevel = 3;
  o.render.cullBackFaces = true;
  o.cull = {true, "tangent-plane", "hiz", {true, "built-in scene: closed, outward cages"}};
  o.firstFrame = frame::FirstFrame::HalfVisible;  // the second pass has work in frame 0
  const frame::CullMesh cullMeshes[] = {{&gpu, &s.patches}};
  frame::CullFrame culled(context(), renderer, culledTarget, cullMeshes, o);
  const frame::PatchDraw draw{&gpu, &s.patches, 0};
  frame::FreeCullingFrame freeFrame(context(), renderer, {&draw, 1});
  const frame::Bounds b = frame::boundsOf(s.patches.points);
  const frame::Camera base = frame::frameBounds(b, s.viewDirection, s.up, 40.0, kW, kH);
  for (int f = 0; f < 3; ++f) {
    const frame::Camera cam = frame::orbit(base, b.center(), s.up, 25.0 * f);
    const std::vector<uint32_t> before = culled.visibility(0).readStatus(context());
    const frame::CullFrameStats cs = culled.render(cam, occluders);
    const std::vector<uint32_t> drawn =
        frame::patchesDrawnByFrame(before, culled.visibility(0).readStatus(context()), false);
    ASSERT_EQ(drawn.size(), size_t{cs.drawnPass1} + cs.drawnPass2) << "frame " << f;
    ASSERT_LT(drawn.size(), s.patches.patchCount()) << "something is culled";
    freeFrame.setPatches(0, drawn);
    const frame::FrameStats fs = freeFrame.render(freeTarget, cam, occluders, o.render);
    EXPECT_EQ(fs.patchesDrawn, drawn.size());
    EXPECT_EQ(fs.statistics.tessEvaluationInvocations,
              cs.pass1.tessEvaluationInvocations + cs.pass2.tessEvaluationInvocations)
        << "frame " << f;
    EXPECT_EQ(fs.statistics.tessControlPatches,
              cs.pass1.tessControlPatches + cs.pass2.tessControlPatches);
    EXPECT_EQ(freeTarget.readColor(context()), culledTarget.readColor(context())) << "frame " << f;
  }
  EXPECT_THROW(freeFrame.setPatches(0, std::vector<uint32_t>{s.patches.patchCount()}), Error);
  EXPECT_THROW(freeFrame.setPatches(1, {}), Error);
}

}  // namespace
}  // namespace osd_cull
