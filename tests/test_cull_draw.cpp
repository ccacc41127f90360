// Drawing the survivors of a cull pass (frame/cull_pass.h renderCulled): the same image as
// the full draw, fewer tessellated vertices, indirect draws within lavapipe's batch limits;
// and the command-line front ends (`osd-cull render --cull`, `osd-cull verify`).
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/scene/default_scene.h"
#include "support/run_command.h"
#include "support/vk_test_context.h"
#include "support/vk_test_images.h"

#include <osd_cull/shared/draw_layout.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

class CullDrawTest : public test::VkTest {};

TEST_F(CullDrawTest, CulledFrameDrawsTheSameImageWithFewerTessellatedVertices) {
  const scene::Scene scene = scene::defaultScene();
  frame::GpuPatchSet gpu(context(), scene.patches);
  std::vector<frame::GpuTriangleMesh> walls;
  for (const auto& m : scene.occluders) walls.emplace_back(context(), m);
  std::vector<const frame::GpuTriangleMesh*> occluders;
  for (const auto& w : walls) occluders.push_back(&w);
  frame::CullSettings settings;
  settings.backPatch = "tangent-plane";
  settings.backPatchValidity = {true, "closed tori and sphere"};
  frame::CullPass pass(context(), gpu, scene.patches, settings);
  frame::Renderer renderer(context());
  frame::RenderTarget full(context(), 160, 120), culled(context(), 160, 120);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 6;
  const frame::Bounds bounds = frame::boundsOf(scene.patches.points);
  for (double angle : {0.0, 70.0, 160.0, 250.0}) {
    const frame::Camera camera =
        frame::orbit(frame::frameBounds(bounds, scene.viewDirection, scene.up, 35.0, 160, 120),
                     bounds.center() + glm::dvec3(0.8, 0.0, 0.0), scene.up, angle);
    const frame::PatchDraw draw{&gpu, &scene.patches, 0};
    const auto a = renderer.render(full, camera, {&draw, 1}, occluders, options);
    const auto b = frame::renderCulled(renderer, culled, camera, pass, occluders, options);
    EXPECT_LT(b.patchesDrawn, a.patchesDrawn) << angle;
    EXPECT_LT(b.statistics.tessEvaluationInvocations, a.statistics.tessEvaluationInvocations);
    const auto itemsA = full.readItems(context()), itemsB = culled.readItems(context());
    const auto colorA = full.readColor(context()), colorB = culled.readColor(context());
    size_t lost = 0, differentColor = 0;
    for (size_t i = 0; i < itemsA.size(); ++i) {
      lost += itemsA[i] != shader::kItemBackground && itemsB[i] == shader::kItemBackground;
      for (int c = 0; c < 3; ++c)
        differentColor += std::abs(int(colorA[4 * i + c]) - int(colorB[4 * i + c])) > 2;
    }
    EXPECT_EQ(lost, 0u) << angle;
    EXPECT_LE(differentColor, 3u) << angle;  // a silhouette pixel at most (cull-kernel.md)
  }
}

TEST_F(CullDrawTest, IndirectDrawsOfSurvivorsStayWithinTheBatchLimitsAtHighLevels) {
  // 864 patches at level 24 (transition bound (48+1)^2 vertices): lavapipe would drop runs
  // of patches from a draw of more than 27 of them (shared/PLATFORM.md).
  const PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 12);
  frame::GpuPatchSet gpu(context(), set);
  frame::CullSettings settings;  // frustum only: every patch of the sphere survives
  frame::CullPass pass(context(), gpu, set, settings);
  frame::Renderer renderer(context());
  frame::RenderTarget full(context(), 128, 128), culled(context(), 128, 128);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 24;
  const auto camera =
      frame::frameBounds(frame::boundsOf(set.points), {0.3, -1, 0.6}, {0, 0, 1}, 40.0, 128, 128);
  renderer.render(full, camera, gpu, &set, options);
  const auto stats = frame::renderCulled(renderer, culled, camera, pass, {}, options);
  EXPECT_EQ(stats.patchesDrawn, set.patchCount());
  EXPECT_EQ(frame::indirectDrawChunk(options.tessellation, kBezierPoints, set.bezierCount), 27u);
  EXPECT_EQ(pass.counts().drawsBezier, (set.patchCount() + 26) / 27);
  EXPECT_EQ(test::itemHistogram(full.readItems(context())),
            test::itemHistogram(culled.readItems(context())));
}

TEST_F(CullDrawTest, DrawsNeedTheTessellationTheCommandsWereWrittenFor) {
  const PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 6);
  frame::GpuPatchSet gpu(context(), set);
  frame::CullPass pass(context(), gpu, set, {});
  frame::Renderer renderer(context());
  frame::RenderTarget target(context(), 32, 32);
  const auto camera =
      frame::frameBounds(frame::boundsOf(set.points), {1, 0, 0}, {0, 0, 1}, 40.0, 32, 32);
  frame::TessellationOptions low;
  low.uniformLevel = 2;
  pass.run(camera, low);
  frame::RenderOptions high;
  high.tessellation.uniformLevel = 32;
  bool threw = false;
  context().submit([&](VkCommandBuffer cmd) {
    renderer.beginPass(cmd, target, high);
    try {
      pass.recordDraws(cmd, renderer, camera, high);
    } catch (const Error& e) {
      threw = std::string(e.what()).find("same options") != std::string::npos;
    }
    renderer.endPass(cmd);
  });
  EXPECT_TRUE(threw);
}

#define REQUIRE_PROGRAM() \
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built"

TEST(CullCommands, RenderWithCullingDrawsFewerPatchesAndSaysWhy) {
  REQUIRE_PROGRAM();
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "cull_cli";
  fs::create_directories(dir);
  const auto r = test::runCommand(test::osdCullProgram().string() + " render --out " +
                                  (dir / "culled.png").string() +
                                  " --width 96 --height 64 --tess 2 --cull all "
                                  "--backpatch-method tcone --validate");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("cull: all (frustum, tcone, hiz)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("culled "), std::string::npos) << r.output;
  const auto bad = test::runCommand(test::osdCullProgram().string() +
                                    " render --out x.png --cull all --backpatch-method frustum");
  EXPECT_NE(bad.exitCode(), 0);
  EXPECT_NE(bad.output.find("not a back-patch method"), std::string::npos) << bad.output;
}

TEST(CullCommands, VerifyWritesJsonWithEveryApplicableMethod) {
  REQUIRE_PROGRAM();
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "cull_cli";
  fs::create_directories(dir);
  const fs::path json = dir / "verify.json";
  const auto r = test::runCommand(test::osdCullProgram().string() +
                                  " verify --views 6 --width 64 --height 64 --tess 3 --sample 4 "
                                  "--image-check --json " +
                                  json.string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("verify: 6/6 views"), std::string::npos) << r.output;  // progress
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["mesh"], "built-in:default");
  EXPECT_EQ(j["views"], 6);
  EXPECT_EQ(j["back_patch"]["enabled"], true);
  ASSERT_EQ(j["methods"].size(), 8u);  // frustum, 4 back-patch methods and 2 fp64 ones, hiz
  for (const auto& m : j["methods"]) {
    EXPECT_EQ(m["culled_not_in_reference"], 0) << m["name"];
    EXPECT_EQ(m["sampling_violations"], 0) << m["name"];
    EXPECT_EQ(m["pixels_lost"], 0) << m["name"];
    EXPECT_GE(m["oracle_invisible_rate"].get<double>(), m["cull_rate"].get<double>());
    EXPECT_GT(m["ns_per_patch"].get<double>(), 0.0);
  }
  EXPECT_GT(j["methods"][3]["cull_rate"].get<double>(), 0.3);  // tangent plane
  bool strict = true;
  for (const auto& m : j["methods"]) strict = strict && m["false_culls"] == 0;
  EXPECT_EQ(j["ok"].get<bool>(), strict);
}

TEST(CullCommands, VerifySkipsBackPatchMethodsOnOpenMeshesWithTheReason) {
  REQUIRE_PROGRAM();
  const fs::path obj = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "cull_cli" / "open.obj";
  fs::create_directories(obj.parent_path());
  std::ofstream(obj)
      << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n";
  const auto r = test::runCommand(test::osdCullProgram().string() + " verify " + obj.string() +
                                  " --views 3 --width 32 --height 32 --methods frustum,ncone");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("skipped ncone: back-patch culling is off"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("open"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
