// `osd-cull view`: the key bindings and the --script language as plain logic, and the real
// window under Xvfb (status colors appear after "s", fewer patches are drawn after culling
// is switched on, the HUD is drawn, validation stays silent).
#include "osd_cull/frame/draw/png_io.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#if OSD_CULL_HAVE_VIEWER
#include "viewer/view_state.h"
#endif

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

#if OSD_CULL_HAVE_VIEWER
using viewer::pressKey;
using viewer::ViewState;

TEST(ViewerKeys, TogglesCullStagesColorsAndTessellation) {
  ViewState s;
  EXPECT_FALSE(s.anyCull());
  EXPECT_EQ(*pressKey(s, "c"), "culling frustum+backpatch(tcone)+hiz");
  EXPECT_TRUE(s.frustum && s.backPatch && s.occlusion);
  pressKey(s, "2");
  EXPECT_FALSE(s.backPatch);
  EXPECT_EQ(s.cullLabel(), "frustum+hiz");
  pressKey(s, "c");  // some stage on: c switches all off
  EXPECT_FALSE(s.anyCull());
  EXPECT_EQ(s.cullLabel(), "none");
  pressKey(s, "m");
  EXPECT_EQ(s.backPatchMethod, "ncone");
  pressKey(s, "m");
  pressKey(s, "m");
  EXPECT_EQ(s.backPatchMethod, "tcone");
  const uint32_t level = s.tessLevel;
  pressKey(s, "plus");
  EXPECT_EQ(s.tessLevel, level + 1);
  for (int i = 0; i < 100; ++i) pressKey(s, "-");
  EXPECT_EQ(s.tessLevel, 1u);
  pressKey(s, "s");
  pressKey(s, "t");
  pressKey(s, "w");
  pressKey(s, "z");
  EXPECT_TRUE(s.statusColors && s.typeColors && s.wireframe && s.freezeCull);
  EXPECT_FALSE(pressKey(s, "%").has_value());
  pressKey(s, "esc");
  EXPECT_TRUE(s.quit);
}

TEST(ViewerScript, AppliesStepsBeforeTheirFrame) {
  viewer::ScriptPlayer player(viewer::parseScript("t @2 c orbit:30,100 @4 zoom:0.5 s"));
  ViewState s;
  EXPECT_EQ(player.beforeFrame(0, s).size(), 1u);
  EXPECT_TRUE(s.typeColors);
  EXPECT_FALSE(s.anyCull());
  EXPECT_TRUE(player.beforeFrame(1, s).empty());
  EXPECT_EQ(player.beforeFrame(2, s).size(), 2u);
  EXPECT_TRUE(s.anyCull());
  EXPECT_DOUBLE_EQ(s.yawDegrees, 30.0);
  EXPECT_DOUBLE_EQ(s.pitchDegrees, 85.0);  // clamped
  EXPECT_FALSE(s.statusColors);
  player.beforeFrame(4, s);
  EXPECT_TRUE(s.statusColors);
  EXPECT_DOUBLE_EQ(s.zoom, 0.5);
  EXPECT_TRUE(player.done());
}

TEST(ViewerScript, RejectsBadTokensWithTheirName) {
  for (const char* bad : {"@x", "@3 @1", "orbit:1", "zoom:0", "zoom:abc", "bogus", "@-1"}) {
    try {
      viewer::parseScript(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("--script"), std::string::npos) << e.what();
    }
  }
}
#endif

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

struct ViewRun {
  test::CommandResult result;
  frame::PngImage image;
};

// Runs the viewer under Xvfb for `frames` frames with `script`, keeping the last frame.
ViewRun view(const std::string& name, uint32_t frames, const std::string& script,
             const std::string& extra = "--no-hud") {
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "viewer";
  fs::create_directories(dir);
  const fs::path shot = dir / (name + ".png");
  fs::remove(shot);
  ViewRun run;
  run.result = test::runCommand(
      "xvfb-run -a -s '-screen 0 800x600x24' " + test::osdCullProgram().string() +
      " view --width 320 --height 240 --tess 2 --validate --frames " + std::to_string(frames) +
      " --screenshot " + shot.string() + " --script '" + script + "' " + extra);
  if (run.result.exitCode() == 0 && fs::exists(shot)) run.image = frame::readPng(shot);
  return run;
}

// Pixels of the status view's "visible" green (shaded): green clearly above red and blue.
size_t greenPixels(const frame::PngImage& image) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < image.samples8.size(); i += size_t(image.channels)) {
    const int r = image.samples8[i], g = image.samples8[i + 1], b = image.samples8[i + 2];
    n += g > r + 40 && g > b + 40;
  }
  return n;
}

struct FrameLine {
  uint32_t drawn = 0, total = 0;
  unsigned long long tes = 0;
};

std::vector<FrameLine> frameLines(const std::string& output) {
  std::vector<FrameLine> lines;
  const std::regex re(
      R"(frame \d+: cull [^,]*, drawn (\d+) of (\d+) patches.*TES invocations (\d+))");
  for (std::sregex_iterator it(output.begin(), output.end(), re), end; it != end; ++it)
    lines.push_back({static_cast<uint32_t>(std::stoul((*it)[1])),
                     static_cast<uint32_t>(std::stoul((*it)[2])), std::stoull((*it)[3])});
  return lines;
}

class ViewerWindow : public ::testing::Test {
 protected:
  void SetUp() override {
#if !OSD_CULL_HAVE_VIEWER
    GTEST_SKIP() << "osd-cull built without the viewer (libglfw3-dev, libimgui-dev)";
#endif
    if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  }
};

TEST_F(ViewerWindow, StatusColorsAppearAfterTheStatusKey) {
  const ViewRun plain = view("culled", 3, "@1 c");
  const ViewRun status = view("status", 3, "@1 c s");
  ASSERT_EQ(plain.result.exitCode(), 0) << plain.result.output;
  ASSERT_EQ(status.result.exitCode(), 0) << status.result.output;
  ASSERT_EQ(status.image.width, 320u);
  EXPECT_EQ(greenPixels(plain.image), 0u);
  EXPECT_GT(greenPixels(status.image), 500u);  // the visible patches, shaded green
}

TEST_F(ViewerWindow, DrawsFewerPatchesOnceCullingIsSwitchedOn) {
  const ViewRun run = view("cull_on", 4, "@2 c");
  ASSERT_EQ(run.result.exitCode(), 0) << run.result.output;
  const std::vector<FrameLine> lines = frameLines(run.result.output);
  ASSERT_EQ(lines.size(), 4u) << run.result.output;
  EXPECT_EQ(lines[0].drawn, lines[0].total);  // culling off: every patch
  EXPECT_EQ(lines[1].drawn, lines[1].total);
  EXPECT_LT(lines[3].drawn, lines[3].total);  // after the first culled frame
  EXPECT_LT(lines[3].tes, lines[1].tes);
}

TEST_F(ViewerWindow, HudIsDrawnOverTheView) {
  const ViewRun bare = view("no_hud", 2, "", "--no-hud");
  const ViewRun hud = view("hud", 2, "", "");
  ASSERT_EQ(bare.result.exitCode(), 0) << bare.result.output;
  ASSERT_EQ(hud.result.exitCode(), 0) << hud.result.output;
  ASSERT_EQ(bare.image.samples8.size(), hud.image.samples8.size());
  size_t differ = 0;  // in the top-left corner, where the HUD sits
  for (uint32_t y = 0; y < 60; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      const size_t i = (size_t(y) * bare.image.width + x) * size_t(bare.image.channels);
      differ += bare.image.samples8[i] != hud.image.samples8[i];
    }
  EXPECT_GT(differ, 1000u);
}

TEST_F(ViewerWindow, BadScriptIsAUsageErrorBeforeAnyWindow) {
  const auto r =
      test::runCommand(test::osdCullProgram().string() + " view --frames 2 --script '@3 @1'");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("frames must not decrease"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
