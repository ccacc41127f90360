// `osd-cull render --cull occlusion`: the two-pass frame from the command line, with the
// per-frame report, JSON statistics, the status debug view and the pyramid levels.
#include "adapters/image_legend.h"
#include "adapters/image_png.h"
#include "support/run_command.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

using test::runCommand;

fs::path program() { return test::osdCullProgram(); }

// An empty folder test_output/NAME in the build tree.
fs::path freshOutputDir(const char* name) {
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(RenderCullCommand, OcclusionFramesReportPassesAndWriteStatsStatusViewAndPyramid) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = freshOutputDir("render_cull_cli");
  const test::CommandResult r =
      runCommand(program().string() + " render --out " + (dir / "s.png").string() +
                 " --width 120 --height 90 --frames 3 --orbit 20 --cull occlusion "
                 "--validate --status-view --stats " +
                 (dir / "s.json").string() + " --pyramid-dir " + (dir / "hiz").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* line : {"frame 0:", "frame 2:", "drawn pass 1", "pass 2", "occlusion",
                           "TES invocations", "pyramid", "wrote "})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  // 120 x 90 pads to 128 x 128; level 0 at half resolution is 64 x 64: 7 levels.
  for (int l = 0; l < 7; ++l) {
    char name[32];
    std::snprintf(name, sizeof(name), "hiz_level_%02d.png", l);
    ASSERT_TRUE(fs::exists(dir / "hiz" / name)) << name;
    EXPECT_EQ(adapters::readPng(dir / "hiz" / name).width, 64u >> l);
  }
  EXPECT_FALSE(fs::exists(dir / "hiz" / "hiz_level_07.png"));
  for (const char* f : {"s.png", "s_status.png", "s_status_side.png"})
    EXPECT_EQ(adapters::readPng(dir / f).width, 120u) << f;
  std::ifstream in(dir / "s.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  ASSERT_EQ(doc["frames"].size(), 3u);
  const auto& f0 = doc["frames"][0];
  EXPECT_EQ(f0["patches"], f0["drawnPass1"]);  // first frame: everything visible before
  EXPECT_EQ(f0["drawnPass2"], 0);
  const auto& f1 = doc["frames"][1];
  const uint32_t survivors0 = f0["survivors"];
  EXPECT_EQ(f1["drawnPass1"], survivors0);
  const uint32_t patches = f1["patches"], survivors = f1["survivors"];
  const uint32_t culled = f1["culled"]["occlusion"];
  EXPECT_EQ(survivors + culled, patches);
  EXPECT_GT(f1["pass1"]["tessEvaluationInvocations"].get<uint64_t>(), 0u);
  EXPECT_GT(f1["ms"]["total"].get<double>(), 0.0);
  // The per-stage GPU times of the one submission, or null with the reason.
  for (const char* stage : {"pass1", "pyramid", "cull", "pass2", "gpu"}) {
    ASSERT_TRUE(f1["ms"].contains(stage)) << stage;
    if (f1["ms"][stage].is_null())
      EXPECT_TRUE(f1["ms"].contains("note")) << stage;
    else
      EXPECT_GE(f1["ms"][stage].get<double>(), 0.0) << stage;
  }
  if (!f1["ms"]["gpu"].is_null()) {
    EXPECT_GT(f1["ms"]["pyramid"].get<double>(), 0.0);
    EXPECT_LE(f1["ms"]["gpu"].get<double>(), f1["ms"]["total"].get<double>() * 1.01 + 0.05);
  }
  EXPECT_EQ(doc["options"]["drawMode"], "filtered");
}

// The first pixel of each swatch of a legend strip under an image `imageHeight` tall.
std::vector<std::array<uint8_t, 3>> swatchColors(const adapters::PngImage& png,
                                                 uint32_t imageHeight,
                                                 std::span<const adapters::LegendEntry> entries) {
  std::vector<std::array<uint8_t, 3>> colors;
  for (const adapters::LegendSwatch& s : adapters::legendLayout(png.width, entries)) {
    const size_t i = 4 * ((size_t(imageHeight) + s.y + s.size / 2) * png.width + s.x + s.size / 2);
    colors.push_back({png.samples8[i], png.samples8[i + 1], png.samples8[i + 2]});
  }
  return colors;
}

TEST(RenderCullCommand, StatusViewsAndDebugColorsCarryALegendStripOfTheirColours) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = freshOutputDir("render_legend_cli");
  const test::CommandResult r =
      runCommand(program().string() + " render --out " + (dir / "s.png").string() +
                 " --width 400 --height 90 --frames 2 --cull all --status-view --debug-colors");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  const std::vector<std::array<uint8_t, 3>> status{
      {89, 191, 89}, {242, 217, 64}, {89, 140, 242}, {179, 102, 230}, {242, 89, 77}};
  for (const char* f : {"s_status.png", "s_status_side.png"}) {
    const adapters::PngImage png = adapters::readPng(dir / f);
    ASSERT_EQ(png.height, 90u + adapters::kLegendRowHeight) << f;
    EXPECT_EQ(swatchColors(png, 90, adapters::statusLegend()), status) << f;
  }
  const adapters::PngImage debug = adapters::readPng(dir / "s.png");
  ASSERT_EQ(debug.height, 90u + adapters::kLegendRowHeight);
  const auto colors = swatchColors(debug, 90, adapters::patchIndexLegend());
  for (size_t i = 0; i < colors.size(); ++i)
    EXPECT_EQ(colors[i], adapters::patchIndexLegend()[i].rgb) << i;
}

// The share of the image's width and height that the pixels differing from the corner
// (background) pixel span, in the top `imageHeight` rows.
std::pair<double, double> objectSpan(const adapters::PngImage& png, uint32_t imageHeight) {
  uint32_t x0 = png.width, x1 = 0, y0 = imageHeight, y1 = 0;
  for (uint32_t y = 0; y < imageHeight; ++y)
    for (uint32_t x = 0; x < png.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (png.samples8[4 * (size_t(y) * png.width + x) + c] != png.samples8[c]) {
          x0 = std::min(x0, x), x1 = std::max(x1, x + 1), y0 = std::min(y0, y),
          y1 = std::max(y1, y + 1);
        }
  if (x1 <= x0) return {0.0, 0.0};
  return {double(x1 - x0) / png.width, double(y1 - y0) / imageHeight};
}

TEST(RenderCullCommand, StatusViewsOfTheDefaultFramingFrameTheMesh) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = freshOutputDir("render_status_framing");
  const test::CommandResult r =
      runCommand(program().string() + " render --out " + (dir / "s.png").string() +
                 " --width 320 --height 180 --cull all --status-view");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* f : {"s_status.png", "s_status_side.png"}) {
    const auto [w, h] = objectSpan(adapters::readPng(dir / f), 180);
    std::printf("%s: the object spans %.0f%% of the width, %.0f%% of the height\n", f, 100 * w,
                100 * h);
    EXPECT_GE(std::max(w, h), 0.8) << f;  // fits one side: at most 92% plus perspective
    EXPECT_GE(w * h, 0.3) << f;
  }
}

TEST(RenderCullCommand, CullOptionsAreCheckedWithAClearMessage) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  test::CommandResult r = runCommand(program().string() + " render --out x.png --cull sometimes");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("is not one of none"), std::string::npos) << r.output;
  r = runCommand(program().string() + " render --out x.png --aggressive");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("need --cull"), std::string::npos) << r.output;
  r = runCommand(program().string() + " render --out x.png --cull frustum --surface-exact");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("--surface-exact needs --cull backpatch"), std::string::npos) << r.output;
  r = runCommand(program().string() + " render --out x.png --cull occlusion --first-frame most");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("all, half, none"), std::string::npos) << r.output;
}

TEST(RenderCullCommand, AggressiveTessFactorZeroRunsWithoutSecondPass) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_cull_cli_tf0";
  fs::create_directories(dir);
  const test::CommandResult r =
      runCommand(program().string() + " render --out " + (dir / "a.png").string() +
                 " --width 64 --height 48 --frames 2 --cull occlusion --aggressive "
                 "--draw-mode tf0 --first-frame none --hiz-full --hiz-tight "
                 "--hiz-reduction fourtap --validate --stats " +
                 (dir / "a.json").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("aggressive"), std::string::npos) << r.output;
  std::ifstream in(dir / "a.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  for (const auto& f : doc["frames"]) EXPECT_EQ(f["drawnPass2"], 0);
  EXPECT_EQ(doc["frames"][0]["drawnPass1"], 0);  // nothing visible before the first frame
  EXPECT_GT(doc["frames"][1]["drawnPass1"].get<uint32_t>(), 0u);
  EXPECT_EQ(doc["options"]["hizLookup"], "tight");
  EXPECT_EQ(doc["options"]["hizSampler"], false);
}

TEST(RenderCullCommand, MeshWithAnObjOccluderWallIsCulledBehindTheWall) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  OSD_CULL_REQUIRE_DATA();
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_cull_cli_mesh";
  fs::create_directories(dir);
  // A wall in front of BigGuy's lower half (the default view looks from +z).
  std::ofstream(dir / "wall.obj")
      << "v -30 -30 20\nv 30 -30 20\nv 30 0 20\nv -30 0 20\nf 1 2 3 4\n";
  const std::string base = program().string() + " render " +
                           (test::dataDir() / "characters" / "bigguy.obj").string() +
                           " --level 1 --width 96 --height 96 --frames 2 --cull occlusion --stats ";
  const test::CommandResult with =
      runCommand(base + (dir / "wall.json").string() + " --out " + (dir / "wall.png").string() +
                 " --occluders " + (dir / "wall.obj").string());
  ASSERT_EQ(with.exitCode(), 0) << with.output;
  EXPECT_NE(with.output.find("1 triangle occluders"), std::string::npos) << with.output;
  const test::CommandResult without =
      runCommand(base + (dir / "open.json").string() + " --out " + (dir / "open.png").string());
  ASSERT_EQ(without.exitCode(), 0) << without.output;
  std::ifstream a(dir / "wall.json"), b(dir / "open.json");
  const nlohmann::json wall = nlohmann::json::parse(a), open = nlohmann::json::parse(b);
  const uint32_t culledWall = wall["frames"][1]["culled"]["occlusion"];
  const uint32_t culledOpen = open["frames"][1]["culled"]["occlusion"];
  EXPECT_GT(culledOpen, 0u);                // the back of the body
  EXPECT_GT(culledWall, culledOpen + 100);  // and the legs behind the wall
}

TEST(RenderCullCommand, AllRunsEveryStageOfTheKernelInTheTwoPassFrame) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_cull_cli_all";
  fs::create_directories(dir);
  const auto r = runCommand(program().string() + " render --out " + (dir / "all.png").string() +
                            " --width 128 --height 96 --frames 2 --orbit 10 --cull all "
                            "--validate --stats " +
                            (dir / "all.json").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("cull: all (frustum, tangent-plane, hiz)"), std::string::npos)
      << r.output;
  std::ifstream in(dir / "all.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  const auto& f1 = doc["frames"][1];
  EXPECT_GT(f1["culled"]["backPatch"].get<uint32_t>(), 0u);
  EXPECT_GT(f1["culled"]["occlusion"].get<uint32_t>(), 0u);
  const uint32_t patches = f1["patches"], survivors = f1["survivors"];
  const uint32_t culled = f1["culled"]["frustum"].get<uint32_t>() +
                          f1["culled"]["backPatch"].get<uint32_t>() +
                          f1["culled"]["occlusion"].get<uint32_t>();
  EXPECT_EQ(survivors + culled, patches);
}

TEST(RenderCullCommand, UnculledFramesHaveTheSameMsLayoutAsCulledOnes) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_plain_stats";
  fs::create_directories(dir);
  const auto r = runCommand(program().string() + " render --out " + (dir / "p.png").string() +
                            " --width 64 --height 48 --frames 1 --stats " +
                            (dir / "p.json").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  std::ifstream in(dir / "p.json");
  const nlohmann::json ms = nlohmann::json::parse(in)["frames"][0]["ms"];
  EXPECT_FALSE(ms.contains("wall"));
  EXPECT_GT(ms["total"].get<double>(), 0.0);
  for (const char* stage : {"pass1", "pyramid", "cull", "pass2", "gpu"})
    ASSERT_TRUE(ms.contains(stage)) << stage;
  if (!ms["gpu"].is_null()) {  // one pass: no pyramid, cull or second pass
    EXPECT_EQ(ms["pyramid"].get<double>(), 0.0);
    EXPECT_EQ(ms["pass2"].get<double>(), 0.0);
    EXPECT_EQ(ms["pass1"].get<double>(), ms["gpu"].get<double>());
  }
}

TEST(VerifyCullCommand, HizIsCheckedAgainstItsReferenceTheOracleAndTheImage) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "verify_hiz";
  fs::create_directories(dir);
  const auto r = runCommand(program().string() +
                            " verify --methods hiz --views 6 --width 96 --height 96 "
                            "--view-set whole-object --image-check --json " +
                            (dir / "hiz.json").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  std::ifstream in(dir / "hiz.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  ASSERT_EQ(doc["methods"].size(), 1u);
  const auto& m = doc["methods"][0];
  EXPECT_EQ(m["name"], "hiz");
  EXPECT_EQ(m["culled_not_in_reference"], 0);
  EXPECT_EQ(m["false_culls"], 0);
  EXPECT_EQ(m["pixels_lost"], 0);
  EXPECT_GT(m["cull_rate"].get<double>(), 0.05);
  EXPECT_GE(m["oracle_invisible_rate"].get<double>(), m["cull_rate"].get<double>());
}

// The default back-patch tests respect the drawn triangles; --surface-exact runs the
// papers' surface tests, which cull more.
TEST(VerifyCullCommand, SurfaceExactCullsMoreThanTheDrawnTriangleBound) {
  if (!fs::exists(program())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "verify_drawn";
  fs::create_directories(dir);
  nlohmann::json docs[2];
  for (int exact = 0; exact < 2; ++exact) {
    const fs::path json = dir / (exact ? "surface.json" : "drawn.json");
    const auto r = runCommand(program().string() +
                              " verify --methods tangent-plane --views 8 --width 96 --height 96 " +
                              (exact ? "--surface-exact " : "") + "--json " + json.string());
    ASSERT_EQ(r.exitCode(), 0) << r.output;
    std::ifstream in(json);
    docs[exact] = nlohmann::json::parse(in);
    ASSERT_TRUE(docs[exact]["back_patch"]["enabled"].get<bool>());
    EXPECT_EQ(docs[exact]["back_patch"]["drawn_triangles"].get<bool>(), exact == 0);
    // A closed mesh: the oracle draws as a renderer culling back faces does.
    EXPECT_TRUE(docs[exact]["back_patch"]["oracle_culls_back_faces"].get<bool>());
  }
  const auto& drawn = docs[0]["methods"][0];
  const auto& surface = docs[1]["methods"][0];
  EXPECT_EQ(drawn["false_culls"], 0);
  EXPECT_EQ(drawn["culled_not_in_reference"], 0);
  EXPECT_GT(drawn["cull_rate"].get<double>(), 0.0);
  EXPECT_GT(surface["cull_rate"].get<double>(), drawn["cull_rate"].get<double>());
  EXPECT_GT(drawn["kept_for_drawn_triangles_rate"].get<double>(), 0.0);
  EXPECT_EQ(surface["kept_for_drawn_triangles_rate"].get<double>(), 0.0);
}

}  // namespace
}  // namespace osd_cull
