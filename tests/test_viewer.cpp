// `osd-cull view`: the key bindings, the --script language, the animation clock and the
// per-pass timing schedule as plain logic, and the real window under Xvfb (status colors
// appear after "s", fewer patches are drawn after culling is switched on, the HUD is drawn,
// an animated scene moves while playing and stands still while paused, timed frames come
// at the chosen interval with non-zero figures, scene files open, validation stays silent).
#include "adapters/image_legend.h"
#include "adapters/image_png.h"
#include "osd_cull/plan/calibration.h"
#include "osd_cull/scene/loaded_scene.h"
#include "osd_cull/scene/procedural.h"
#include "support/obj_file.h"
#include "support/plan_calibration.h"
#include "support/run_command.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#if OSD_CULL_HAVE_VIEWER
#include "viewer/view_state.h"
#include "viewer/viewer.h"
#endif

#include <algorithm>
#include <array>
#include <cmath>
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

TEST(ViewerKeys, PTogglesThePlanAndAStageKeyTakesOverByHand) {
  ViewState s;
  s.plan = true;
  EXPECT_EQ(s.cullLabel(), "plan");
  EXPECT_EQ(pressKey(s, "p"), "effect plan off");
  EXPECT_EQ(pressKey(s, "p"), "effect plan on");
  // A stage key: the plan is off, the stage on, and the line says so.
  EXPECT_EQ(pressKey(s, "2"), "back-patch culling on (plan off: stages by hand)");
  EXPECT_FALSE(s.plan);
  EXPECT_EQ(s.cullLabel(), "backpatch(tcone)");
  EXPECT_EQ(pressKey(s, "1"), "frustum culling on");  // already by hand: nothing to say
  EXPECT_NE(viewer::keyHelp().find("  p "), std::string::npos);
  // Where the keys differ from OpenSubdiv's glViewer, the help says why.
  EXPECT_NE(viewer::keyHelp().find("Esc  quit (as glViewer)"), std::string::npos);
  EXPECT_NE(viewer::keyHelp().find("its number keys set the refinement level"), std::string::npos);
  EXPECT_NE(viewer::keyHelp().find("middle drag: pan (as glViewer)"), std::string::npos);
}

TEST(ViewerKeys, SpacePlaysTheAnimationAndRTurnsTheTable) {
  ViewState s;
  EXPECT_FALSE(s.playing || s.turntable || s.sceneCamera);
  EXPECT_EQ(*pressKey(s, "space"), "animation playing");
  EXPECT_TRUE(s.playing);
  EXPECT_FALSE(s.turntable);  // the camera no longer turns with space
  EXPECT_EQ(*pressKey(s, "r"), "turntable on");
  EXPECT_TRUE(s.turntable);
  EXPECT_EQ(*pressKey(s, "v"), "camera of the scene");
  EXPECT_TRUE(s.sceneCamera);
  EXPECT_EQ(*pressKey(s, "space"), "animation paused");
  EXPECT_FALSE(s.playing);
}

TEST(ViewerAnimation, AdvancesOnlyWhilePlayingAndWraps) {
  ViewState s;
  viewer::advanceAnimation(s, 3);
  EXPECT_EQ(s.sceneFrame, 0u);  // paused
  s.playing = true;
  viewer::advanceAnimation(s, 3);
  viewer::advanceAnimation(s, 3);
  EXPECT_EQ(s.sceneFrame, 2u);
  viewer::advanceAnimation(s, 3);
  EXPECT_EQ(s.sceneFrame, 0u);  // wrapped after three frames
  viewer::advanceAnimation(s, 1);
  EXPECT_EQ(s.sceneFrame, 0u);  // a one-frame scene does not move
}

TEST(ViewerPassTiming, TimesTheFirstFrameThenEveryInterval) {
  viewer::PassTiming t(4);
  EXPECT_TRUE(t.due(2));  // nothing timed yet
  t.record(2, 1.5, 0.25, 0.5, 0.75);
  EXPECT_FALSE(t.due(3));
  EXPECT_FALSE(t.due(5));
  EXPECT_TRUE(t.due(6));
  EXPECT_EQ(t.lastTimed(), 2u);
  EXPECT_DOUBLE_EQ(t.pass1Ms(), 1.5);
  EXPECT_DOUBLE_EQ(t.pyramidMs(), 0.25);
  EXPECT_DOUBLE_EQ(t.cullMs(), 0.5);
  EXPECT_DOUBLE_EQ(t.pass2Ms(), 0.75);
  EXPECT_NE(t.describe(5).find("timed frame 2 (3 frames ago"), std::string::npos) << t.describe(5);
  t.forget(3);             // a new cull frame made at frame 3: its pipelines are built then, so the
  EXPECT_FALSE(t.due(3));  // per-pass times start at the frame after (no one-off work)
  EXPECT_TRUE(t.due(4));
  viewer::PassTiming never(0);
  EXPECT_FALSE(never.due(0));
  EXPECT_FALSE(never.due(1000));
}

TEST(ViewerScenes, ASceneWithoutInstancesOrPerspectiveViewIsRefusedByName) {
  auto message = [](scene::LoadedScene loaded) -> std::string {
    try {
      viewer::playedScene(std::move(loaded));
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  };
  scene::LoadedScene empty;
  empty.description.source = "empty.json";
  EXPECT_EQ(message(std::move(empty)), "scene empty.json: no instances to view");
  scene::LoadedScene shadowOnly;
  shadowOnly.description.source = "shadow.json";
  shadowOnly.description.instances.emplace_back();
  shadowOnly.description.views.emplace_back();
  shadowOnly.description.views.back().kind = scene::ViewDescription::Kind::Shadow;
  EXPECT_EQ(message(std::move(shadowOnly)),
            "scene shadow.json: no perspective view to start the viewer from");
}

TEST(ViewerScenes, PlayedSceneKeepsItsFirstPerspectiveViewForTheSceneCamera) {
  scene::LoadedScene loaded;
  loaded.description.instances.emplace_back();
  loaded.description.views.resize(3);
  loaded.description.views[0].kind = scene::ViewDescription::Kind::Shadow;
  loaded.description.views[1].name = "main";
  loaded.description.views[1].eye = {0, -5, 0};
  loaded.description.views[1].target = {0, 0, 0};
  loaded.description.views[1].up = {0, 0, 1};
  loaded.description.views[2].name = "second";
  const viewer::ViewerScene v = viewer::playedScene(std::move(loaded));
  ASSERT_EQ(v.scene.description.views.size(), 1u);
  EXPECT_EQ(v.scene.description.views[0].name, "main");
  EXPECT_EQ(v.viewDirection, glm::dvec3(0, -5, 0));  // from the target towards the eye
  EXPECT_EQ(v.up, glm::dvec3(0, 0, 1));
}

TEST(ViewerScript, ShotStepsAreNamedAfterTheScreenshot) {
  viewer::ScriptPlayer player(viewer::parseScript("@1 shot @2"));
  EXPECT_TRUE(player.hasShots());
  ViewState s;
  player.beforeFrame(0, s);
  EXPECT_FALSE(player.takeShot());
  player.beforeFrame(1, s);
  EXPECT_TRUE(player.takeShot());
  EXPECT_FALSE(player.takeShot());  // once
  EXPECT_FALSE(viewer::ScriptPlayer(viewer::parseScript("@1 c")).hasShots());
  EXPECT_EQ(viewer::screenshotPath("out/view.png", 7), "out/view-frame7.png");
  EXPECT_EQ(viewer::screenshotPath("a.b/view", 3), "a.b/view-frame3");
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

TEST(ViewerScript, PanMovesTheOrbitPivotWithinItsLimitsAndFResetsIt) {
  // Middle drag pans, as in OpenSubdiv's glViewer; the script's pan:RIGHT,UP does the same.
  viewer::ScriptPlayer player(viewer::parseScript("pan:0.5,-0.25 @1 pan:10,0"));
  ViewState s;
  EXPECT_EQ(player.beforeFrame(0, s).size(), 1u);
  EXPECT_DOUBLE_EQ(s.panX, 0.5);
  EXPECT_DOUBLE_EQ(s.panY, -0.25);
  player.beforeFrame(1, s);
  EXPECT_DOUBLE_EQ(s.panX, 4.0);  // clamped to 4 bounding radii
  viewer::panCamera(s, std::nan(""), 1.0);
  EXPECT_DOUBLE_EQ(s.panY, -0.25);  // a non-finite drag is ignored
  EXPECT_EQ(pressKey(s, "f"), "camera reset");
  EXPECT_DOUBLE_EQ(s.panX, 0.0);
  EXPECT_DOUBLE_EQ(s.panY, 0.0);
}

TEST(ViewerScript, RejectsBadTokensWithTheirName) {
  for (const char* bad :
       {"@x", "@3 @1", "orbit:1", "pan:1", "pan:a,1", "zoom:0", "zoom:abc", "bogus", "@-1"}) {
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
  adapters::PngImage image;
};

// Runs `view OPTIONS` under an Xvfb screen SCREEN with `script`, keeping the last frame.
ViewRun viewOn(const std::string& name, const std::string& screen, const std::string& options,
               const std::string& script, const std::string& extra) {
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "viewer";
  fs::create_directories(dir);
  const fs::path shot = dir / (name + ".png");
  fs::remove(shot);
  ViewRun run;
  run.result = test::runCommand(
      "xvfb-run -a -s '-screen 0 " + screen + "x24' " + test::osdCullProgram().string() + " view " +
      options + " --screenshot " + shot.string() + " --script '" + script + "' " + extra);
  if (run.result.exitCode() == 0 && fs::exists(shot)) run.image = adapters::readPng(shot);
  return run;
}

// Runs the viewer at 320 x 240 for `frames` frames with `script`, keeping the last frame.
ViewRun view(const std::string& name, uint32_t frames, const std::string& script,
             const std::string& extra = "--no-hud") {
  return viewOn(name, "800x600",
                "--width 320 --height 240 --tess 2 --validate --frames " + std::to_string(frames),
                script, extra);
}

// Pixels of the status view's "visible" green (shaded): green clearly above red and blue.
size_t greenPixels(const adapters::PngImage& image) {
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

// A run at 960 x 540, the size the HUD must leave the model room in.
ViewRun view960(const std::string& name, const std::string& script, const std::string& extra) {
  return viewOn(name, "1024x768", "--width 960 --height 540 --tess 2 --frames 3", script, extra);
}

size_t pixelsOfColor(const adapters::PngImage& image, const std::array<uint8_t, 3>& rgb) {
  size_t n = 0;
  for (size_t i = 0; i + 3 <= image.samples8.size(); i += size_t(image.channels))
    n += std::equal(rgb.begin(), rgb.end(), image.samples8.begin() + i);
  return n;
}

TEST_F(ViewerWindow, CompactHudLeavesTheModelRoomShowsTheKeysAndTheStatusLegend) {
  const ViewRun bare = view960("hud960_bare", "@1 c s", "--no-hud");
  const ViewRun hud = view960("hud960", "@1 c s", "");
  ASSERT_EQ(bare.result.exitCode(), 0) << bare.result.output;
  ASSERT_EQ(hud.result.exitCode(), 0) << hud.result.output;
  ASSERT_EQ(hud.image.width, 960u);
  ASSERT_EQ(bare.image.samples8.size(), hud.image.samples8.size());
  size_t covered = 0;
  uint32_t right = 0, bottom = 0;
  const size_t c = size_t(hud.image.channels);
  for (uint32_t y = 0; y < 540; ++y)
    for (uint32_t x = 0; x < 960; ++x) {
      const size_t i = (size_t(y) * 960 + x) * c;
      if (std::equal(bare.image.samples8.begin() + i, bare.image.samples8.begin() + i + 3,
                     hud.image.samples8.begin() + i))
        continue;
      ++covered, right = std::max(right, x), bottom = std::max(bottom, y);
    }
  std::printf("HUD: %zu pixels (%.1f%% of the window), up to x %u, y %u\n", covered,
              100.0 * covered / (960.0 * 540.0), right, bottom);
  EXPECT_LT(covered, 960u * 540u / 4);  // was about half
  EXPECT_LT(right, 480u);               // the left half of the window
  EXPECT_GT(bottom, 240u);              // the keys section below the figures, open
  // The legend of the status colours: a swatch of each (exact colours, unshaded).
  for (const auto& e : adapters::statusLegend()) {
    EXPECT_GE(pixelsOfColor(hud.image, e.rgb), 60u) << e.label;
    EXPECT_LT(pixelsOfColor(bare.image, e.rgb), pixelsOfColor(hud.image, e.rgb)) << e.label;
  }
}

TEST_F(ViewerWindow, ThePlansCurrentChoiceAndReasonAreShownEachFrame) {
  test::TempDir dir("viewer_plan_");
  const fs::path calibration = dir.path() / "synthetic.txt";
  plan::storeCalibration(test::syntheticCalibration(), calibration);
  const ViewRun run = view("plan", 2, "", "--no-hud --plan-calibration " + calibration.string());
  ASSERT_EQ(run.result.exitCode(), 0) << run.result.output;
  // The line the HUD shows under the cull stages: the instance's stages and the reasons
  // of its back-patch and occlusion effects (the viewer shows one mesh: no "+N instances").
  const std::regex re(R"(  plan: [^\n]*: (ncone|tcone|tangent-plane)[^\n]*; back-patch on: )"
                      R"([^\n]*; occlusion (on|off): [^\n]+)");
  EXPECT_TRUE(std::regex_search(run.result.output, re)) << run.result.output;
}

TEST_F(ViewerWindow, PanShiftsTheModelOnScreen) {
  const ViewRun still = view("pan_still", 2, "");
  const ViewRun panned = view("pan_right", 2, "@0 pan:0.5,0");
  ASSERT_EQ(still.result.exitCode(), 0) << still.result.output;
  ASSERT_EQ(panned.result.exitCode(), 0) << panned.result.output;
  // The centroid of the model's pixels (differing from the corner's background) moves left
  // when the pivot moves right.
  const auto centroidX = [](const adapters::PngImage& image) {
    double sum = 0.0, n = 0.0;
    const size_t c = size_t(image.channels);
    for (uint32_t y = 0; y < image.height; ++y)
      for (uint32_t x = 0; x < image.width; ++x) {
        const size_t i = (size_t(y) * image.width + x) * c;
        if (!std::equal(image.samples8.begin(), image.samples8.begin() + 3,
                        image.samples8.begin() + i))
          sum += x, n += 1.0;
      }
    return n > 0.0 ? sum / n : 0.0;
  };
  EXPECT_LT(centroidX(panned.image), centroidX(still.image) - 20.0);
}

// The frame lines' animation and per-pass timing figures.
struct FrameClock {
  uint32_t sceneFrame = 0, frameCount = 0;
  bool playing = false;
  double pass1 = 0, pyramid = 0, cull = 0, pass2 = 0;
  int timedAt = -1;  ///< the frame the per-pass figures come from; -1: none yet
  uint32_t drawn = 0, total = 0, culled = 0;
};

std::vector<FrameClock> frameClocks(const std::string& output) {
  std::vector<FrameClock> lines;
  const std::regex re(
      R"(drawn (\d+) of (\d+) patches.*culled frustum (\d+) back-patch (\d+) occlusion (\d+).*)"
      R"(scene frame (\d+) of (\d+) (playing|paused), ms per pass ([\d.]+) ([\d.]+) ([\d.]+) )"
      R"(([\d.]+) (none|from frame (\d+)))");
  for (std::sregex_iterator it(output.begin(), output.end(), re), end; it != end; ++it) {
    const std::smatch& m = *it;
    FrameClock c;
    c.drawn = static_cast<uint32_t>(std::stoul(m[1]));
    c.total = static_cast<uint32_t>(std::stoul(m[2]));
    c.culled = static_cast<uint32_t>(std::stoul(m[3]) + std::stoul(m[4]) + std::stoul(m[5]));
    c.sceneFrame = static_cast<uint32_t>(std::stoul(m[6]));
    c.frameCount = static_cast<uint32_t>(std::stoul(m[7]));
    c.playing = m[8] == "playing";
    c.pass1 = std::stod(m[9]);
    c.pyramid = std::stod(m[10]);
    c.cull = std::stod(m[11]);
    c.pass2 = std::stod(m[12]);
    c.timedAt = m[14].matched ? std::stoi(m[14]) : -1;
    lines.push_back(c);
  }
  return lines;
}

// Pixels whose color differs between two images of the same size.
size_t differingPixels(const adapters::PngImage& a, const adapters::PngImage& b) {
  EXPECT_EQ(a.samples8.size(), b.samples8.size());
  size_t n = 0;
  const size_t c = size_t(a.channels);
  for (size_t i = 0; i + c <= std::min(a.samples8.size(), b.samples8.size()); i += c)
    n += !std::equal(a.samples8.begin() + i, a.samples8.begin() + i + 3, b.samples8.begin() + i);
  return n;
}

// The images a view() run's `shot` steps wrote.
adapters::PngImage shotOf(const std::string& run, int frame) {
  return adapters::readPng(fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "viewer" /
                           (run + "-frame" + std::to_string(frame) + ".png"));
}

TEST_F(ViewerWindow, AnimatedSceneMovesWhilePlayingAndStandsStillWhenPaused) {
  // Culling on from the start; shots of two paused frames, then of two playing ones; a
  // timed diagnostic frame every 3 frames.
  const ViewRun run = view("anim", 8, "@2 shot @3 shot @4 space @5 shot @6 shot",
                           "--no-hud --cull all --time-passes 3 built-in:scene");
  ASSERT_EQ(run.result.exitCode(), 0) << run.result.output;  // 1 on validation messages
  EXPECT_EQ(run.result.output.find("validation"), std::string::npos) << run.result.output;
  std::vector<adapters::PngImage> shots;
  for (int f : {2, 3, 5, 6}) shots.push_back(shotOf("anim", f));
  EXPECT_EQ(differingPixels(shots[0], shots[1]), 0u);   // paused: the same image
  EXPECT_GT(differingPixels(shots[2], shots[3]), 50u);  // playing: the character moves

  const std::vector<FrameClock> clocks = frameClocks(run.result.output);
  ASSERT_EQ(clocks.size(), 8u) << run.result.output;
  for (uint32_t f = 0; f < 4; ++f) {
    EXPECT_FALSE(clocks[f].playing);
    EXPECT_EQ(clocks[f].sceneFrame, 0u);
  }
  for (uint32_t f = 4; f < 8; ++f) {
    EXPECT_TRUE(clocks[f].playing);
    EXPECT_EQ(clocks[f].sceneFrame, f - 3);  // one animation frame per frame drawn
    EXPECT_EQ(clocks[f].frameCount, 48u);
    EXPECT_GT(clocks[f].culled, 0u) << "frame " << f;  // culling stays on while playing
    EXPECT_LT(clocks[f].drawn, clocks[f].total) << "frame " << f;
  }
  // The cull frame is made at frame 0 (its pipelines built then): no per-pass figures
  // there. Timed frames at 1, 4 and 7; every later frame shows the figures of the last one,
  // all non-zero.
  EXPECT_EQ(clocks[0].timedAt, -1);
  for (uint32_t f = 1; f < 8; ++f) {
    EXPECT_EQ(clocks[f].timedAt, int(1 + (f - 1) / 3 * 3)) << "frame " << f;
    EXPECT_GT(clocks[f].pass1, 0.0) << "frame " << f;
    EXPECT_GT(clocks[f].pyramid, 0.0) << "frame " << f;
    EXPECT_GT(clocks[f].cull, 0.0) << "frame " << f;
    EXPECT_GT(clocks[f].pass2, 0.0) << "frame " << f;
  }
}

// A scene file of one creased cube seen from (4, -6, 3) with `frames` frames; `extra`
// is added to the instance (an animation) and `path` to the view (a camera path).
fs::path cubeScene(const test::TempDir& dir, uint32_t frames, const std::string& extra,
                   const std::string& path) {
  return dir.write("scene.json", R"({"version": 1,
  "settings": {"frameCount": )" + std::to_string(frames) +
                                     R"(, "framesPerSecond": 24},
  "meshes": [{"name": "cube", "builtIn": "creased-cube", "level": 1}],
  "instances": [{"name": "cube", "mesh": "cube")" +
                                     extra + R"(}],
  "views": [{"name": "main", "camera": {"eye": [4, -6, 3], "target": [0, 0, 0]})" +
                                     path + "}]}");
}

TEST_F(ViewerWindow, OpensASceneFileAndPlaysItsInstanceMotion) {
  test::TempDir dir("viewer_scene_");
  const fs::path scene = cubeScene(
      dir, 4, R"(, "animation": {"spin": {"axis": [0, 0, 1], "degreesPerSecond": 240}})", "");
  const ViewRun run =
      view("scene_file", 4, "@1 space @2 shot @3 shot", "--no-hud " + scene.string());
  ASSERT_EQ(run.result.exitCode(), 0) << run.result.output;
  const std::vector<FrameClock> clocks = frameClocks(run.result.output);
  ASSERT_EQ(clocks.size(), 4u) << run.result.output;
  EXPECT_EQ(clocks[3].sceneFrame, 3u);
  EXPECT_EQ(clocks[3].frameCount, 4u);
  EXPECT_EQ(clocks[3].drawn, clocks[3].total);  // no culling asked for
  EXPECT_GT(differingPixels(shotOf("scene_file", 2), shotOf("scene_file", 3)), 50u);  // it spins
}

TEST_F(ViewerWindow, SceneCameraFollowsItsPathOnlyWhilePlaying) {
  test::TempDir dir("viewer_camera_");
  const fs::path scene = cubeScene(dir, 8, "", R"(, "path": {"orbit": {"degreesPerFrame": 10}})");
  // v: look through the scene's camera; paused it stands still, playing it orbits.
  const ViewRun run = view("camera_path", 7, "@1 v @2 shot @3 shot @4 space @5 shot @6 shot",
                           "--no-hud --cull all " + scene.string());
  ASSERT_EQ(run.result.exitCode(), 0) << run.result.output;
  EXPECT_EQ(differingPixels(shotOf("camera_path", 2), shotOf("camera_path", 3)), 0u);
  EXPECT_GT(differingPixels(shotOf("camera_path", 5), shotOf("camera_path", 6)), 50u);
  // frame 6 (the last image): the path has turned 30 degrees since frame 2
  EXPECT_GT(differingPixels(run.image, shotOf("camera_path", 2)), 50u);
}

TEST_F(ViewerWindow, OpensAMeshFile) {
  const fs::path mesh = test::dataDir() / "shapes" / "catmark_cube.obj";
  if (!fs::exists(mesh)) GTEST_SKIP() << mesh << " not found";
  const ViewRun run = view("mesh_file", 3, "@1 space", "--no-hud --cull all " + mesh.string());
  ASSERT_EQ(run.result.exitCode(), 0) << run.result.output;
  const std::vector<FrameClock> clocks = frameClocks(run.result.output);
  ASSERT_EQ(clocks.size(), 3u) << run.result.output;
  EXPECT_GT(clocks[2].total, 0u);
  EXPECT_GT(clocks[2].drawn, 0u);
  EXPECT_EQ(clocks[2].frameCount, 1u);  // a mesh file is one static frame
  EXPECT_EQ(clocks[2].sceneFrame, 0u);  // playing moves nothing
  EXPECT_GT(clocks[2].culled, 0u);      // back patches of the closed cube
  EXPECT_EQ(run.image.width, 320u);
}

// Issue 23: a mesh file authored far from the origin is recentred at load by the viewer
// too (cmd_view.cpp, meshPatches), so it culls and draws as the same mesh at the origin.
TEST_F(ViewerWindow, AMeshFileFarFromTheOriginCullsAndDrawsAsAtTheOrigin) {
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "viewer_far_mesh";
  fs::create_directories(dir);
  CageMesh cage = scene::character();
  scene::recentre(cage.positions);
  test::writeObj(cage, dir / "origin.obj");
  scene::translate(cage, glm::dvec3(1e5));
  test::writeObj(cage, dir / "far.obj");
  const ViewRun origin = view("far_mesh_origin", 3, "@1 space",
                              "--no-hud --cull all " + (dir / "origin.obj").string());
  const ViewRun far =
      view("far_mesh_far", 3, "@1 space", "--no-hud --cull all " + (dir / "far.obj").string());
  ASSERT_EQ(origin.result.exitCode(), 0) << origin.result.output;
  ASSERT_EQ(far.result.exitCode(), 0) << far.result.output;
  EXPECT_NE(far.result.output.find("note: the mesh lies far from the origin: recentred by"),
            std::string::npos)
      << far.result.output;
  const std::vector<FrameClock> a = frameClocks(origin.result.output);
  const std::vector<FrameClock> b = frameClocks(far.result.output);
  ASSERT_EQ(a.size(), 3u) << origin.result.output;
  ASSERT_EQ(b.size(), 3u) << far.result.output;
  ASSERT_EQ(a[2].total, b[2].total);
  EXPECT_GT(a[2].culled, a[2].total / 50);  // the comparison means something
  EXPECT_NEAR(double(b[2].culled), double(a[2].culled), 0.01 * a[2].total);  // within one point
  EXPECT_EQ(differingPixels(origin.image, far.image), 0u);
}

TEST(ViewerCommand, UnknownScriptKeyIsAUsageErrorWithAShortMessage) {
#if !OSD_CULL_HAVE_VIEWER
  GTEST_SKIP() << "osd-cull was built without the viewer";
#endif
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  const auto r =
      test::runCommand(test::osdCullProgram().string() + " view --frames 2 --script 'c bogus'");
  EXPECT_EQ(r.exitCode(), 2) << r.output;  // a bad command line, as CLI11's errors
  EXPECT_NE(r.output.find("--script: 'bogus' is not a key"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("`osd-cull view --help` lists the keys"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("tessellation level up"), std::string::npos) << r.output;  // no key list
  EXPECT_LT(r.output.size(), 400u) << r.output;
}

TEST_F(ViewerWindow, BadScriptIsAUsageErrorBeforeAnyWindow) {
  const auto r =
      test::runCommand(test::osdCullProgram().string() + " view --frames 2 --script '@3 @1'");
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("frames must not decrease"), std::string::npos) << r.output;
  const auto shot =
      test::runCommand(test::osdCullProgram().string() + " view --frames 2 --script '@1 shot'");
  EXPECT_EQ(shot.exitCode(), 2) << shot.output;
  EXPECT_NE(shot.output.find("'shot' needs --screenshot"), std::string::npos) << shot.output;
}

}  // namespace
}  // namespace osd_cull
