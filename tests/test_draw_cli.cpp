// `osd-cull render`: the built-in scene renders with validation on, writes the images and
// prints a line per frame.
#include "adapters/image_png.h"
#include "support/run_command.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

using test::runCommand;

fs::path program() { return test::osdCullProgram(); }

TEST(RenderCommand, DrawsTheBuiltInSceneAndWritesImages) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built (OSD_CULL_BUILD_SAMPLES=OFF?)";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = runCommand(
      program().string() + " render --out " + (dir / "scene.png").string() +
      " --width 96 --height 64 --tess 2 --frames 2 --orbit 30 --ids --validate --out-dir " +
      (dir / "frames").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frame 0:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frame 1:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("TES invocations"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("wrote "), std::string::npos) << r.output;
  for (const char* f : {"scene.png", "scene_ids.png", "scene_depth.png", "frames/frame_0000.png",
                        "frames/frame_0001.png"}) {
    ASSERT_TRUE(fs::exists(dir / f)) << f;
    const auto image = adapters::readPng(dir / f);
    EXPECT_EQ(image.width, 96u) << f;
    EXPECT_EQ(image.height, 64u) << f;
  }
  // The two frames differ (the camera orbits); the last frame is the one in --out.
  const auto a = adapters::readPng(dir / "frames/frame_0000.png");
  const auto b = adapters::readPng(dir / "frames/frame_0001.png");
  EXPECT_NE(a.samples8, b.samples8);
  EXPECT_EQ(adapters::readPng(dir / "scene.png").samples8, b.samples8);
}

TEST(RenderCommand, DrawsTheTeapotBezierPatchFile) {
  OSD_CULL_REQUIRE_DATA();
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_teapot";
  fs::create_directories(dir);
  const auto r = runCommand(program().string() + " render " +
                              (test::dataDir() / "bezier" / "teapot.bpt").string() + " --out " +
                              (dir / "teapot.png").string() +
                              " --width 96 --height 64 --adaptive 4 --ids --validate");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("32 Bezier + 0 Gregory"), std::string::npos) << r.output;
  const auto ids = adapters::readPng(dir / "teapot_ids.png");
  std::set<uint32_t> patches;
  for (size_t i = 0; i + 2 < ids.samples8.size(); i += 3) {
    const uint32_t v = ids.samples8[i] | ids.samples8[i + 1] << 8 | ids.samples8[i + 2] << 16;
    ASSERT_LE(v, 32u);
    if (v) patches.insert(v - 1);
  }
  EXPECT_GE(patches.size(), 16u);  // rim, body, handle, spout and lid seen from above
}

TEST(RenderCommand, RejectsBadOptionsWithAClearMessage) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  auto r = runCommand(program().string() + " render --width 64");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
  r = runCommand(program().string() + " render --out x.png --tess 3 --adaptive 4");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("exclude"), std::string::npos) << r.output;
  r = runCommand(program().string() + " render --out x.png --camera 1,2,3");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("10 comma-separated"), std::string::npos) << r.output;
  r = runCommand(program().string() + " render --out x.png --device no-such-device-name");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("no Vulkan device name contains"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
