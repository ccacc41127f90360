// `osd-cull plan`, `calibrate` and `render --plan`: the printed plan, its reasons and its
// errors, with a synthetic calibration file (support/plan_calibration.h); ctest runs with
// the calibration cache off (tests/CMakeLists.txt), so nothing depends on this machine's.
#include "osd_cull/measure/calibrate.h"
#include "osd_cull/plan/calibration.h"
#include "osd_cull/version.h"
#include "osd_cull/vk/shader_compiler.h"
#include "support/plan_calibration.h"
#include "support/run_command.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

class PlanCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
    calibration_ = dir_.path() / "synthetic.txt";
    plan::storeCalibration(test::syntheticCalibration(), calibration_);
  }
  test::CommandResult run(const std::string& arguments) const {
    return test::runCommand("OSD_CULL_CALIBRATION_CACHE=off " + test::osdCullProgram().string() +
                            " " + arguments);
  }
  test::TempDir dir_{"osd_cull_plan_cli_"};
  fs::path calibration_;
};

TEST_F(PlanCommand, PrintsEachInstancesEffectsWithReasons) {
  const auto r = run("plan built-in:scene --tess 16 --calibration " + calibration_.string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  // The static default mesh: no update, no bounds pass; the skinned character: both.
  EXPECT_NE(r.output.find("| default | main | 0 | inside | update | off | - | +0.00 | static mesh"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("| character | main | 0 | inside | update | on | gpu |"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("| character | main | 0 | inside | bounds | on | ncone |"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("no displacement map: no displacement kernel compiled or bound"),
            std::string::npos);
  EXPECT_NE(r.output.find("predicted:"), std::string::npos);
}

TEST_F(PlanCommand, PrintsTheBackPatchAccuracyAndSurfaceOnlyWhenAsked) {
  const std::string mesh = (test::dataDir() / "characters" / "bigguy.obj").string();
  // Auto on the synthetic calibration without listed costs: the bound, and why.
  auto r = run("plan " + mesh + " --tess 8 --calibration " + calibration_.string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("| accuracy | on | bound |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("listed test of"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("| accuracy | on | surface |"), std::string::npos) << r.output;
  // Asked for: surface-exact, with what it loses. (The synthetic calibration has no
  // surface costs: add them.)
  plan::Calibration c = test::syntheticCalibration();
  c.surfaceCullMsPerPatch = {{"tcone", 0.00003}, {"ncone", 0.00004}, {"tangent-plane", 0.002}};
  const fs::path withSurface = dir_.path() / "surface.txt";
  plan::storeCalibration(c, withSurface);
  r = run("plan " + mesh + " --tess 8 --plan-accuracy surface --calibration " +
          withSurface.string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("| accuracy | on | surface |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("NOT conservative for the drawn chord triangles"), std::string::npos)
      << r.output;
  // A bad accuracy is a usage error naming the option.
  r = run("plan " + mesh + " --plan-accuracy exact --calibration " + calibration_.string());
  EXPECT_NE(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("--plan-accuracy"), std::string::npos) << r.output;
}

TEST_F(PlanCommand, WithoutACalibrationSaysHowToMakeOne) {
  const auto r = run("plan built-in:scene");
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("the calibration cache is off"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("osd-cull calibrate --quick"), std::string::npos) << r.output;
  const fs::path bad = dir_.write("bad.txt", "osd_cull-calibration 7\ndevice x\ndraw 1 fast\n");
  const auto b = run("plan --calibration " + bad.string());
  EXPECT_EQ(b.exitCode(), 1) << b.output;
  EXPECT_NE(b.output.find("bad.txt:3: 'draw' needs ms per patch, got '1 fast'"), std::string::npos)
      << b.output;
  // A calibration of the previous format (no displaced kernels, one bounds pass) is refused
  // with the way to measure it again.
  const fs::path old = dir_.write("old.txt", "osd_cull-calibration 2\ndevice x\n");
  const auto o = run("plan --calibration " + old.string());
  EXPECT_EQ(o.exitCode(), 1) << o.output;
  EXPECT_NE(o.output.find("old.txt:1: calibration file format 2, this library reads format 7"),
            std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("osd-cull calibrate --force"), std::string::npos) << o.output;
}

TEST_F(PlanCommand, RenderPlansWithoutCullAndPrintsThePlan) {
  const fs::path out = dir_.path() / "r.png";
  auto r = run("render --out " + out.string() + " --tess 8 --verbose --plan-calibration " +
               calibration_.string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  // The built-in scene at 640x480, tess 8: its box is inside the view (no frustum stage);
  // the first frames explore: every other stage runs to measure its rate, the cheapest
  // predicted method and kernel (NCONE, hiz).
  EXPECT_NE(r.output.find("plan, frame 0: ncone + hiz (two-pass, half) [re-probe]"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("frustum off: object box inside the view (Sathe pre-test)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("back-patch on (ncone): re-probe: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("culled frustum 0, back-patch "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("summary: 1 frames, mean "), std::string::npos) << r.output;
  // An explicit --cull, --plan off, or no calibration: a fixed choice, said so.
  r = run("render --out " + out.string() + " --cull none --plan-calibration " +
          calibration_.string());
  EXPECT_NE(r.output.find("plan: off (--cull given: a fixed choice)"), std::string::npos)
      << r.output;
  r = run("render --out " + out.string() + " --plan off");
  EXPECT_NE(r.output.find("plan: off (--plan off)"), std::string::npos) << r.output;
  r = run("render --out " + out.string());
  EXPECT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("no calibration of this device cached"), std::string::npos) << r.output;
  r = run("render --out " + out.string() + " --plan sometimes");
  EXPECT_EQ(r.exitCode(), 2) << r.output;
}

// Lines of `output` that start with `prefix`.
size_t linesStartingWith(const std::string& output, const std::string& prefix) {
  size_t n = 0;
  for (size_t at = 0; at < output.size();) {
    n += output.compare(at, prefix.size(), prefix) == 0;
    const size_t end = output.find('\n', at);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return n;
}

TEST_F(PlanCommand, RenderPrintsOneLinePerFrameThePlansHeadlineAndAClosingSummary) {
  const fs::path out = dir_.path() / "r.png", stats = dir_.path() / "r.json";
  const std::string base = "render --out " + out.string() + " --width 160 --height 90 --frames 3" +
                           " --stats " + stats.string() + " --plan-calibration " +
                           calibration_.string();
  const auto r = run(base);
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_EQ(linesStartingWith(r.output, "frame "), 3u) << r.output;
  EXPECT_EQ(linesStartingWith(r.output, "plan, frame 0: "), 1u) << r.output;
  EXPECT_EQ(linesStartingWith(r.output, "  "), 0u) << r.output;  // no per-stage reasons
  EXPECT_EQ(linesStartingWith(r.output, "summary: 3 frames, mean "), 1u) << r.output;
  EXPECT_NE(r.output.find(" ms, median "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" saved)"), std::string::npos) << r.output;
  EXPECT_EQ(linesStartingWith(r.output, "summary: plan changes "), 1u) << r.output;
  std::ifstream in(stats);
  const nlohmann::json summary = nlohmann::json::parse(in)["summary"];
  EXPECT_EQ(summary["frames"], 3);
  EXPECT_GT(summary["ms"]["mean"].get<double>(), 0.0);
  EXPECT_GT(summary["ms"]["median"].get<double>(), 0.0);
  EXPECT_EQ(summary["patches"], 3 * 880);
  EXPECT_LT(summary["drawn"].get<uint64_t>(), summary["patches"].get<uint64_t>());
  EXPECT_GT(summary["tes"]["saved"].get<uint64_t>(), 0u);
  EXPECT_TRUE(summary["plan"].contains("changes"));
  // --verbose: the whole plan, every stage with its reason.
  const auto v = run(base + " --verbose");
  ASSERT_EQ(v.exitCode(), 0) << v.output;
  EXPECT_EQ(linesStartingWith(v.output, "frame "), 3u) << v.output;
  // The whole plan each time it is printed: at frame 0 and at a change (the plan is timing-
  // driven, so a change within 3 frames can happen).
  const auto plans = linesStartingWith(v.output, "plan, frame ");
  EXPECT_GE(plans, 1u) << v.output;
  for (const char* stage : {"  frustum ", "  back-patch ", "  occlusion ", "  update off: "})
    EXPECT_EQ(linesStartingWith(v.output, stage), plans) << stage << "\n" << v.output;
}

class PlanCommandCache : public test::VkTest {};

// The costs are the embedded kernels': a build whose kernels changed (same library version)
// has another key, so its cache file is another one and a stale calibration is not used.
TEST_F(PlanCommandCache, TheKeyNamesTheLibraryVersionAndItsKernels) {
  const plan::CalibrationKey key = measure::calibrationKey(context());
  char kernels[32];
  std::snprintf(kernels, sizeof(kernels), "%016llx",
                static_cast<unsigned long long>(vulkan::embeddedSpirvWordsHash()));
  EXPECT_EQ(key.library, std::string(libraryVersion()) + " kernels " + kernels);
  plan::CalibrationKey other = key;
  other.library = libraryVersion();  // a cache written before the kernels were in the key
  test::TempDir cache("osd_cull_plan_key_");
  setenv("OSD_CULL_CALIBRATION_CACHE", cache.path().c_str(), 1);
  const fs::path file = plan::calibrationCacheFile(key);
  const fs::path otherFile = plan::calibrationCacheFile(other);
  unsetenv("OSD_CULL_CALIBRATION_CACHE");
  EXPECT_FALSE(file.empty());
  EXPECT_NE(file, otherFile);
}

TEST_F(PlanCommandCache, AnOutdatedCachedCalibrationIsSaidAndMeasuredAgainByPlanAndRenderAlike) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  // This device's cache file, written in the previous format (before the displaced kernels).
  test::TempDir cache("osd_cull_plan_cache_");
  setenv("OSD_CULL_CALIBRATION_CACHE", cache.path().c_str(), 1);
  const fs::path file = plan::calibrationCacheFile(measure::calibrationKey(context()));
  unsetenv("OSD_CULL_CALIBRATION_CACHE");
  plan::Calibration c = test::syntheticCalibration();
  c.key = measure::calibrationKey(context());
  std::string text = plan::toText(c);
  text.replace(0, text.find('\n'), "osd_cull-calibration 2");
  plan::storeCalibration(c, file);
  std::ofstream(file, std::ios::binary) << text;
  const std::string program = "OSD_CULL_CALIBRATION_CACHE=" + cache.path().string() + " " +
                              test::osdCullProgram().string() + " ";
  // plan says why and measures a quick calibration into the cache, as render does, then
  // plans with it (before, plan refused it and render measured it again).
  const auto p = test::runCommand(program + "plan");
  EXPECT_EQ(p.exitCode(), 0) << p.output;
  EXPECT_NE(p.output.find(file.string() + ": calibration file format 2, this library reads format"),
            std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("measuring a quick calibration of this device"), std::string::npos)
      << p.output;
  const plan::Calibration stored = plan::loadCalibration(file);
  EXPECT_TRUE(stored.quick);
  EXPECT_EQ(stored.key, measure::calibrationKey(context()));
  EXPECT_GT(stored.drawMs(4.0), 0.0);
  // A damaged cache file (cut short) is said and measured again the same way, by render.
  text = plan::toText(stored);
  std::ofstream(file, std::ios::binary) << text.substr(0, text.rfind("end\n"));
  const auto r = test::runCommand(program + "render --width 64 --height 64 --out " +
                                  (cache.path() / "r.png").string());
  EXPECT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find(file.string() + ": no 'end' line"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("measuring a quick calibration of this device"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("plan: auto, calibration of "), std::string::npos) << r.output;
  // ... and both now use the stored one without measuring.
  const auto p2 = test::runCommand(program + "plan");
  EXPECT_EQ(p2.exitCode(), 0) << p2.output;
  EXPECT_EQ(p2.output.find("measuring"), std::string::npos) << p2.output;
}

TEST_F(PlanCommand, ADamagedCalibrationFileIsRefusedAlikeByPlanAndRender) {
  std::string text = plan::toText(test::syntheticCalibration());
  const fs::path cut = dir_.write("cut.txt", text.substr(0, text.find("\nhiz ") + 1));
  std::string huge = text;
  huge.replace(huge.find("submit "), huge.find('\n', huge.find("submit ")) - huge.find("submit "),
               "submit 1e308");
  const fs::path big = dir_.write("huge.txt", huge);
  const fs::path old = dir_.write("old.txt", "osd_cull-calibration 2\ndevice x\n");
  for (const auto& [file, expected] :
       {std::pair{cut, "cut.txt: no 'bounds' line"},
        std::pair{big, "huge.txt:15: 'submit': ms 1e308 is out of range"},
        std::pair{old, "old.txt:1: calibration file format 2, this library reads format"}}) {
    const auto p = run("plan --calibration " + file.string());
    EXPECT_EQ(p.exitCode(), 1) << p.output;
    EXPECT_NE(p.output.find(expected), std::string::npos) << expected << "\n" << p.output;
    const auto r = run("render --width 64 --height 64 --out " + (dir_.path() / "r.png").string() +
                       " --plan-calibration " + file.string());
    EXPECT_EQ(r.exitCode(), 1) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
  }
}

TEST_F(PlanCommand, CalibrateChecksItsOutputBeforeMeasuring) {
  const auto r = run("calibrate --quick --out " + (dir_.path() / "cal.json").string());
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(".txt"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
