// `osd-cull info`: the report of the built-in mesh, of data files, and its errors.
#include "support/run_command.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using test::osdCullProgram;
using test::runCommand;

#define REQUIRE_PROGRAM() \
  if (!fs::exists(osdCullProgram())) GTEST_SKIP() << "osd-cull not built"

nlohmann::json infoJson(const std::string& arguments) {
  const auto r =
      runCommand(osdCullProgram().string() + " info --json " + arguments + " 2>/dev/null");
  EXPECT_EQ(r.exitCode(), 0) << r.output;
  return nlohmann::json::parse(r.output);
}

TEST(InfoCommand, DescribesTheBuiltInMeshWithoutAnyFile) {
  REQUIRE_PROGRAM();
  const auto j = infoJson("");
  EXPECT_EQ(j["mesh"], "built-in:default");
  EXPECT_EQ(j["scheme"], "catmark");
  EXPECT_EQ(j["vertices"], 98);
  EXPECT_EQ(j["faces"], 96);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["creased_edges"], 16);
  const int total = j["patches"]["total"];
  EXPECT_EQ(total, j["patches"]["bezier"].get<int>() + j["patches"]["gregory"].get<int>());
  EXPECT_EQ(j["control_points"].get<int>(),
            16 * j["patches"]["bezier"].get<int>() + 20 * j["patches"]["gregory"].get<int>());
  EXPECT_GT(j["patches"]["gregory"].get<int>(), 0);  // 8 valence-3 vertices
}

TEST(InfoCommand, BigGuyAtLevelTwoHasTheKnownPatchCounts) {
  REQUIRE_PROGRAM();
  OSD_CULL_REQUIRE_DATA();
  const auto j = infoJson((test::dataDir() / "characters" / "bigguy.obj").string());
  EXPECT_EQ(j["vertices"], 1452);
  EXPECT_EQ(j["faces"], 1450);
  EXPECT_EQ(j["closed"], true);
  // shared/PLATFORM.md: 5554 patches = 4778 regular + 776 Gregory at level 2.
  EXPECT_EQ(j["patches"]["total"], 5554);
  EXPECT_EQ(j["patches"]["bezier"], 4778);
  EXPECT_EQ(j["patches"]["gregory"], 776);
  EXPECT_EQ(j["control_points"], 4778 * 16 + 776 * 20);
  const auto j3 = infoJson((test::dataDir() / "characters" / "bigguy.obj").string() + " --level 3");
  EXPECT_EQ(j3["patches"]["total"], 7882);
  const auto b =
      infoJson((test::dataDir() / "characters" / "bigguy.obj").string() + " --endcap bspline");
  EXPECT_EQ(b["patches"]["gregory"], 0);
  EXPECT_EQ(b["patches"]["bspline_end_caps"], 776);
}

TEST(InfoCommand, ReportsOpenAndNonManifoldShapes) {
  REQUIRE_PROGRAM();
  OSD_CULL_REQUIRE_DATA();
  const auto hole = infoJson((test::dataDir() / "shapes" / "catmark_hole_test1.obj").string());
  EXPECT_EQ(hole["closed"], false);
  EXPECT_GT(hole["holes"].get<int>(), 0);
  const auto nonman = infoJson((test::dataDir() / "shapes" / "catmark_nonman_edges.obj").string());
  EXPECT_GT(nonman["non_manifold_edges"].get<int>(), 0);
  EXPECT_FALSE(nonman["notes"].empty());
}

TEST(InfoCommand, LoopMeshLoadsButSaysItsPatchesAreNotExtracted) {
  REQUIRE_PROGRAM();
  OSD_CULL_REQUIRE_DATA();
  const auto j = infoJson((test::dataDir() / "shapes" / "loop_cube.obj").string());
  EXPECT_EQ(j["scheme"], "loop");
  EXPECT_TRUE(j["patches"].is_null());
  EXPECT_NE(j["patches_error"].get<std::string>().find("Loop patches are not extracted"),
            std::string::npos);
}

TEST(InfoCommand, BezierPatchFileIsUsedAsIs) {
  REQUIRE_PROGRAM();
  OSD_CULL_REQUIRE_DATA();
  const auto j = infoJson((test::dataDir() / "bezier" / "teapot.bpt").string());
  EXPECT_EQ(j["patches"]["total"], 32);
  EXPECT_EQ(j["patches"]["bezier"], 32);
  EXPECT_EQ(j["control_points"], 512);
}

TEST(InfoCommand, TextReportNamesEveryFigure) {
  REQUIRE_PROGRAM();
  const auto r = runCommand(osdCullProgram().string() + " info --level 1");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* key : {"vertices", "faces", "surface", "non-manifold", "patches",
                          "control points", "time (ms)", "adaptive level 1"})
    EXPECT_NE(r.output.find(key), std::string::npos) << key << " missing in\n" << r.output;
}

TEST(InfoCommand, ErrorsNameTheProblemAndExitNonZero) {
  REQUIRE_PROGRAM();
  const fs::path missing = fs::temp_directory_path() / "osd_cull_no_such_mesh.obj";
  struct Case {
    std::string args;
    std::string expected;
  };
  const Case cases[] = {
      {missing.string(), "osd_cull_no_such_mesh.obj"},
      {"--level 11", "--level"},
      {"--level two", "not an integer"},
      {"--endcap round", "--endcap"},
      {"--scheme hexagonal", "--scheme"},
      {"--frobnicate 1", "unknown option --frobnicate"},
      {"a.obj b.obj", "at most one MESH"},
  };
  for (const Case& c : cases) {
    const auto r = runCommand(osdCullProgram().string() + " info " + c.args);
    // A file that cannot be read exits 1; a bad command line is a usage error, 2.
    EXPECT_EQ(r.exitCode(), c.args == missing.string() ? 1 : 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
  }
}

TEST(InfoCommand, EmptyFileIsAClearError) {
  REQUIRE_PROGRAM();
  const fs::path empty = fs::temp_directory_path() / "osd_cull_empty_mesh.obj";
  std::ofstream(empty).close();
  const auto r = runCommand(osdCullProgram().string() + " info " + empty.string());
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("osd_cull_empty_mesh.obj"), std::string::npos) << r.output;
  fs::remove(empty);
}

}  // namespace
}  // namespace osd_cull
