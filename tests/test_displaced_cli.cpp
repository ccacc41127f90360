// `osd-cull render` and `verify` with --displacement: the six kernels as methods, the
// displaced draw, and clear errors.
#include "support/run_command.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace osd_cull {
namespace {

std::string program() { return test::osdCullProgram().string(); }

TEST(DisplacedCommands, VerifyReportsAllSixKernelsWithoutFalseCulls) {
  OSD_CULL_REQUIRE_DATA();
  test::TempDir dir("osd_cull_disp_cli_");
  const auto json = dir.path() / "v.json";
  const auto r = test::runCommand(
      program() + " verify " + (test::dataDir() / "shapes/catmark_single_crease.obj").string() +
      " --displacement procedural --displacement-scale 0.4 --displaced-bound all --views 3" +
      " --view-set whole-object --width 64 --height 64 --json " + json.string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("back-patch culling off"), std::string::npos) << r.output;
  std::ifstream in(json);
  const nlohmann::json doc = nlohmann::json::parse(in);
  std::vector<std::string> names;
  for (const auto& m : doc["methods"]) {
    names.push_back(m["name"]);
    EXPECT_EQ(m["false_culls"], 0) << m["name"];
    EXPECT_EQ(m["culled_not_in_reference"], 0) << m["name"];
  }
  for (const char* k : {"full-oobb", "acon-oobb", "con-oobb", "full-caf", "acon-caf", "con-caf"})
    EXPECT_NE(std::find(names.begin(), names.end(), k), names.end()) << k;
  EXPECT_EQ(std::find(names.begin(), names.end(), "tcone"), names.end());
}

TEST(DisplacedCommands, RenderDrawsTheDisplacedSurfaceAndCountsSeams) {
  OSD_CULL_REQUIRE_DATA();
  test::TempDir dir("osd_cull_disp_cli_");
  const auto r = test::runCommand(
      program() + " render " + (test::dataDir() / "shapes/catmark_cube.obj").string() +
      " --displacement procedural --displacement-scale 0.2 --displaced-bound con" +
      " --displaced-box oobb --cull all --width 64 --height 64 --out " +
      (dir.path() / "c.png").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("bound con-oobb; UV seam edges 28"), std::string::npos) << r.output;
}

// The number in "cracks: N pixels" of render's output (-1 when missing).
long crackPixels(const std::string& output) {
  const auto at = output.find("cracks: ");
  return at == std::string::npos ? -1 : std::stol(output.substr(at + 8));
}

TEST(DisplacedCommands, SeamCracksAreCountedAndNeverFalselyCulled) {
  OSD_CULL_REQUIRE_DATA();
  // catmark_cube's texture coordinates are an unfolded cross: its 28 seam edges join
  // different places of the procedural map, so the displacement is discontinuous there and
  // the surface opens. verify counts those pixels and still finds no false cull: the oracle
  // draws back faces, so the inside seen through a seam counts as visible.
  test::TempDir dir("osd_cull_disp_cli_");
  const std::string cube = (test::dataDir() / "shapes/catmark_cube.obj").string();
  const std::string map = " --displacement procedural --displacement-scale 0.3";
  const auto json = dir.path() / "v.json";
  const auto v = test::runCommand(
      program() + " verify " + cube + map +
      " --displaced-bound all --views 6 --width 96 --height 96 --json " + json.string());
  ASSERT_EQ(v.exitCode(), 0) << v.output;
  EXPECT_NE(v.output.find("cracks (displaced surface open at UV seams"), std::string::npos)
      << v.output;
  std::ifstream in(json);
  const nlohmann::json doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["cracks"]["views"], 6);
  EXPECT_GT(doc["cracks"]["pixels"].get<long>(), 0) << "seams should open the surface";
  EXPECT_GT(doc["cracks"]["views_with_cracks"].get<long>(), 0);
  ASSERT_GE(doc["methods"].size(), 7u);  // frustum, hiz and the six kernels
  for (const auto& m : doc["methods"]) {
    EXPECT_EQ(m["false_culls"], 0) << m["name"];
    EXPECT_EQ(m["culled_not_in_reference"], 0) << m["name"];
    if (m["name"] != "frustum") {
      EXPECT_GT(m["culled_per_view"].get<double>(), 0.0) << m["name"];
    }
  }
  // render reports the last view's crack pixels, with displacement-aware levels or not.
  for (const char* tess : {"edge", "none"}) {
    const auto r = test::runCommand(program() + " render " + cube + map + " --adaptive 4" +
                                    " --displaced-tess " + tess + " --width 96 --height 96" +
                                    " --out " + (dir.path() / "c.png").string());
    ASSERT_EQ(r.exitCode(), 0) << r.output;
    EXPECT_GT(crackPixels(r.output), 0) << tess << "\n" << r.output;
  }
}

TEST(DisplacedCommands, BadDisplacementOptionsAreNamed) {
  OSD_CULL_REQUIRE_DATA();
  const std::string pole = (test::dataDir() / "shapes/catmark_pole8.obj").string();
  auto r = test::runCommand(program() + " render " + pole +
                            " --displacement procedural --out /tmp/never.png");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("texture coordinates"), std::string::npos) << r.output;
  r = test::runCommand(program() + " render --displaced-bound con --out /tmp/never.png");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("--displacement"), std::string::npos) << r.output;
  r = test::runCommand(program() + " render " + pole +
                       " --displacement procedural --displaced-bound all --out /tmp/never.png");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("--displaced-bound"), std::string::npos) << r.output;
  r = test::runCommand(program() + " render " + pole +
                       " --displacement procedural --displaced-tess most --out /tmp/never.png");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("--displaced-tess"), std::string::npos) << r.output;
  r = test::runCommand(program() + " verify " + pole + " --displacement nosuch.png");
  EXPECT_NE(r.exitCode(), 0);
  EXPECT_NE(r.output.find("nosuch.png"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
