// What the loaders report reaches every command: info, render and verify print the notes
// (e.g. a dropped `vertexedit` tag) and refuse coordinates fp32 drawing cannot represent.
#include "support/run_command.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

#define REQUIRE_PROGRAM() \
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built"

const std::string kCube =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

test::CommandResult osdCull(const std::string& arguments) {
  return test::runCommand(test::osdCullProgram().string() + " " + arguments);
}

TEST(CommandNotes, RenderAndVerifySayWhatTheLoaderDropped) {
  REQUIRE_PROGRAM();
  test::TempDir dir("osd_cull_cli_notes_");
  const std::string mesh = dir.write("cube.obj", kCube +
                                                     "t vertexedit 2/1/0 1 2 0.5\n"
                                                     "t interpolateboundary 1/0/0 1\n"
                                                     "t interpolateboundary 1/0/0 2\n"
                                                     "t crease 2/1/0 1 2 -3\n")
                               .string();
  const std::string dropped = "note: ignored 1 tag line(s) with unknown tag 'vertexedit'";
  const std::string conflict = "tag 'interpolateboundary' conflicts with line 16";
  const std::string negative = "negative sharpness value(s) clamped to 0";  // issue 23
  const auto info = osdCull("info " + mesh);
  ASSERT_EQ(info.exitCode(), 0) << info.output;
  EXPECT_NE(info.output.find(dropped.substr(6)), std::string::npos) << info.output;
  EXPECT_NE(info.output.find(negative), std::string::npos) << info.output;
  const auto render = osdCull("render " + mesh + " --width 32 --height 32 --out " +
                              (dir.path() / "cube.png").string());
  ASSERT_EQ(render.exitCode(), 0) << render.output;
  EXPECT_NE(render.output.find(dropped), std::string::npos) << render.output;
  EXPECT_NE(render.output.find(conflict), std::string::npos) << render.output;
  EXPECT_NE(render.output.find(negative), std::string::npos) << render.output;
  const auto verify =
      osdCull("verify " + mesh + " --views 1 --width 32 --height 32 --methods frustum");
  ASSERT_EQ(verify.exitCode(), 0) << verify.output;
  EXPECT_NE(verify.output.find(dropped), std::string::npos) << verify.output;
  EXPECT_NE(verify.output.find(conflict), std::string::npos) << verify.output;
  EXPECT_NE(verify.output.find(negative), std::string::npos) << verify.output;
}

TEST(CommandNotes, EveryCommandRefusesCoordinatesBeyondTheFp32Range) {
  REQUIRE_PROGRAM();
  test::TempDir dir("osd_cull_cli_range_");
  for (const char* value : {"1e308", "1e38"}) {
    std::string text = kCube;
    text.replace(text.find("v 1 1 1"), 7, std::string("v 1 1 ") + value);
    const std::string mesh = dir.write("huge.obj", text).string();
    const std::string where = mesh + ":7: vertex 7 coordinate";
    for (const std::string& command :
         {"info " + mesh, "render " + mesh + " --out " + (dir.path() / "h.png").string(),
          "verify " + mesh + " --views 1"}) {
      const auto r = osdCull(command);
      EXPECT_EQ(r.exitCode(), 1) << command << "\n" << r.output;
      EXPECT_NE(r.output.find(where), std::string::npos) << command << "\n" << r.output;
      EXPECT_NE(r.output.find("beyond ±1e18"), std::string::npos) << command << "\n" << r.output;
      EXPECT_EQ(r.output.find("device:"), std::string::npos) << command << "\n" << r.output;
    }
  }
}

TEST(CommandNotes, InfoCountsUnusedVerticesWithoutRefiningThem) {
  REQUIRE_PROGRAM();
  test::TempDir dir("osd_cull_cli_unused_");
  std::string text;
  for (int i = 0; i < 200000; ++i) text += "v 0 0 0\n";
  const std::string mesh =
      dir.write("unused.obj", text + "v 1 0 0\nv 0 1 0\nf 200000 200001 200002\n").string();
  const auto r = osdCull("info --json " + mesh);
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  // As in the file, though only the triangle's 3 vertices reach OpenSubdiv.
  EXPECT_NE(r.output.find("\"vertices\": 200002"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"unused_vertices\": 199999"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"non_manifold_vertices\": 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("dropped the 199999 unused vertices"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
