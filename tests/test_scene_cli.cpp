// `osd-cull render SCENE.json`: plays a scene with two views under validation, writes every
// frame of every view and the JSON figures with the frame count; an unwritable output folder
// fails before rendering; a bad scene file fails with the JSON path of the problem.
#include "adapters/image_png.h"
#include "support/run_command.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

const char* kScene = R"({
  "version": 1,
  "settings": {"frameCount": 2, "framesPerSecond": 24, "width": 96, "height": 64},
  "meshes": [{"name": "cube", "builtIn": "creased-cube", "level": 1},
             {"name": "torus", "builtIn": "torus", "level": 1}],
  "instances": [
    {"name": "cube", "mesh": "cube", "transform": {"translate": [100000, 0, 0]}},
    {"name": "mirrored", "mesh": "cube", "parent": "cube",
     "transform": {"translate": [2.5, 0, 0], "scale": [-1, 1, 1]}},
    {"name": "ring", "mesh": "torus", "parent": "cube", "transform": {"translate": [0, 3, 0]},
     "animation": {"spin": {"axis": [0, 0, 1], "degreesPerSecond": 45}}}
  ],
  "occluders": [{"box": {"min": [99996, -3, -1.5], "max": [100004, 6, -1.2]}}],
  "views": [
    {"name": "main", "camera": {"eye": [100001, -8, 4], "target": [100001, 1, 0]},
     "path": {"orbit": {"degreesPerFrame": 10}}},
    {"name": "sun", "shadow": {"direction": [0.3, 0.2, -1]}, "width": 64, "height": 64}
  ]
})";

TEST(SceneCommand, RendersEveryViewOfEveryFrame) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const fs::path scene = dir.write("scene.json", kScene);
  const auto r = test::runCommand(test::osdCullProgram().string() + " render " + scene.string() +
                                  " --validate --compare --tess 2 --out-dir " +
                                  (dir.path() / "frames").string() + " --stats " +
                                  (dir.path() / "stats.json").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* line :
       {"view main frame 1:", "view sun frame 1:", "vs unculled", "2 instance(s) share its points"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  for (const char* f : {"main_0000.png", "main_0001.png", "sun_0000.png", "sun_0001.png"})
    EXPECT_TRUE(fs::exists(dir.path() / "frames" / f)) << f;
  std::ifstream in(dir.path() / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats.at("frameCount"), 2);
  ASSERT_EQ(stats.at("frames").size(), 4u);
  EXPECT_EQ(stats.at("frames")[3].at("view"), "sun");
  EXPECT_TRUE(stats.at("frames")[0].contains("unculled"));
}

TEST(SceneCommand, VerifiesEveryInstanceOnEveryFrame) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const fs::path scene = dir.write("scene.json", kScene);
  const auto r = test::runCommand(test::osdCullProgram().string() + " verify " + scene.string() +
                                  " --frames 2 --views 1 --width 64 --height 64 --image-check "
                                  "--validate --json " +
                                  (dir.path() / "verify.json").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  std::ifstream in(dir.path() / "verify.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("frames"), 2);
  EXPECT_EQ(j.at("instances"), 3);
  EXPECT_EQ(j.at("views"), 2 * 3);  // per frame: the two scene views and one random view
  EXPECT_TRUE(j.at("ok").get<bool>());
  ASSERT_EQ(j.at("methods").size(), 4u);
  for (const auto& m : j.at("methods")) {
    EXPECT_EQ(m.at("false_culls"), 0) << m.at("name");
    EXPECT_EQ(m.at("culled_not_in_reference"), 0) << m.at("name");
    EXPECT_EQ(m.at("pixels_lost"), 0) << m.at("name");
  }
  EXPECT_GT(j.at("methods")[3].at("cull_rate").get<double>(), 0.05);  // tangent plane
}

// A cube cage whose top rises frame by frame, as frame_NN.obj files.
std::string cubeFrame(double top, bool extraFace = false) {
  std::string text;
  for (int i = 0; i < 8; ++i)
    text += "v " + std::to_string(i & 1 ? 1 : -1) + " " + std::to_string(i & 2 ? 1 : -1) + " " +
            std::to_string(i & 4 ? top : -1.0) + "\n";
  text += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  if (extraFace) text += "f 1 2 3\n";
  return text;
}

TEST(SceneCommand, PlaysAndVerifiesAnObjSequence) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  for (int f = 0; f < 3; ++f)
    dir.write("frame_0" + std::to_string(f) + ".obj", cubeFrame(1.0 + 0.5 * f));
  const std::string pattern = (dir.path() / "frame_##.obj").string();
  const auto r = test::runCommand(test::osdCullProgram().string() + " render " + pattern +
                                  " --frames 3 --width 64 --height 48 --validate --out-dir " +
                                  (dir.path() / "out").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("deforms (sequence"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "main_0002.png"));
  const auto v = test::runCommand(test::osdCullProgram().string() + " verify " + pattern +
                                  " --frames 3 --views 2 --width 64 --height 64 --validate");
  EXPECT_EQ(v.exitCode(), 0) << v.output;
  EXPECT_NE(v.output.find("tangent-plane"), std::string::npos) << v.output;
}

TEST(SceneCommand, SequenceWithChangedTopologyNamesTheFile) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  dir.write("frame_00.obj", cubeFrame(1.0));
  dir.write("frame_01.obj", cubeFrame(1.5, true));
  const auto r = test::runCommand(test::osdCullProgram().string() + " render " +
                                  (dir.path() / "frame_##.obj").string() + " --frames 2");
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("frame_01.obj"), std::string::npos) << r.output;
}

TEST(SceneCommand, UnwritableOutputFolderFailsBeforeRendering) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const fs::path scene = dir.write("scene.json", kScene);
  const fs::path blocker = dir.write("blocker", "a file, not a folder");
  const auto r = test::runCommand(test::osdCullProgram().string() + " render " + scene.string() +
                                  " --out-dir " + (blocker / "frames").string());
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("cannot write there"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("device:"), std::string::npos) << r.output;
}

TEST(SceneCommand, BadSceneFileNamesThePath) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const fs::path scene = dir.write("bad.json", R"({"version": 1,
    "meshes": [{"name": "m", "builtIn": "cube"}],
    "instances": [{"mesh": "m"}, {"mesh": "nothing"}],
    "views": [{"name": "v", "camera": {"eye": [0, -5, 0], "target": [0, 0, 0]}}]})");
  const auto r = test::runCommand(test::osdCullProgram().string() + " render " + scene.string());
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("/instances/1/mesh: unknown mesh 'nothing'"), std::string::npos)
      << r.output;
}

// An animated displaced mesh (the users' case): `verify SCENE` culls its displaced kernel
// with the cones the GPU bounds pass computed for each frame, as `render` does
// (scene_verify.cpp), and finds no false cull and no GPU cull outside the double reference.
TEST(SceneCommand, AnimatedDisplacedMeshVerifiesWithTheGpuBoundsPass) {
  OSD_CULL_REQUIRE_DATA();
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const std::string obj = (test::dataDir() / "shapes/catmark_cube.obj").string();
  const fs::path scene = dir.write("scene.json", R"({"version": 1,
  "settings": {"frameCount": 2, "width": 64, "height": 64},
  "meshes": [{"name": "bumpy", "file": ")" + obj + R"(", "level": 2,
              "displacement": {"map": "procedural", "scale": 0.1, "bound": "acon", "box": "caf"},
              "animation": {"deformer": "twist", "axis": 2, "amount": 0.4}}],
  "instances": [{"name": "bumpy", "mesh": "bumpy"}],
  "views": [{"name": "main", "camera": {"eye": [0.5, -2.6, 0.9], "target": [0.5, 0, 0]}}]})");
  const auto v = test::runCommand(test::osdCullProgram().string() + " verify " + scene.string() +
                                  " --frames 2 --views 2 --width 64 --height 64 --tess 2"
                                  " --methods frustum --validate --json " +
                                  (dir.path() / "verify.json").string());
  ASSERT_EQ(v.exitCode(), 0) << v.output;
  EXPECT_NE(v.output.find("bumpy: acon-caf reads the cones of the GPU bounds pass"),
            std::string::npos)
      << v.output;
  std::ifstream in(dir.path() / "verify.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j.at("ok").get<bool>());
  bool kernel = false;
  for (const auto& m : j.at("methods")) {
    EXPECT_EQ(m.at("false_culls"), 0) << m.at("name");
    EXPECT_EQ(m.at("culled_not_in_reference"), 0) << m.at("name");
    if (m.at("name") == "acon-caf") {
      kernel = true;
      EXPECT_GT(m.at("cull_rate").get<double>(), 0.0) << v.output;
    }
  }
  EXPECT_TRUE(kernel) << v.output;
}

// Issue 11 in scene files: a static displaced mesh (procedural map, con-oobb bound) beside a
// twisting undisplaced one; every frame renders like the unculled draw and verifies with no
// false cull, the displaced instance also with its own kernel.
TEST(SceneCommand, DisplacedStaticAndAnimatedMeshesRenderAndVerifyWithoutFalseCulls) {
  OSD_CULL_REQUIRE_DATA();
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const fs::path scene = dir.write("scene.json", test::displacedScene());
  const auto r = test::runCommand(test::osdCullProgram().string() + " render " + scene.string() +
                                  " --validate --compare --tess 2 --out-dir " +
                                  (dir.path() / "frames").string());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* line : {"displaced (procedural", "con-oobb; back-patch culling off",
                           "deforms (twist", "view main frame 1:"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  const auto v = test::runCommand(test::osdCullProgram().string() + " verify " + scene.string() +
                                  " --frames 2 --views 1 --width 64 --height 64 --tess 2"
                                  " --image-check --validate --json " +
                                  (dir.path() / "verify.json").string());
  ASSERT_EQ(v.exitCode(), 0) << v.output;
  std::ifstream in(dir.path() / "verify.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j.at("ok").get<bool>());
  std::vector<std::string> names;
  for (const auto& m : j.at("methods")) {
    names.push_back(m.at("name"));
    EXPECT_EQ(m.at("false_culls"), 0) << m.at("name");
    EXPECT_EQ(m.at("culled_not_in_reference"), 0) << m.at("name");
    EXPECT_EQ(m.at("pixels_lost"), 0) << m.at("name");
  }
  for (const char* n : {"frustum", "tcone", "ncone", "con-oobb"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n << "\n" << v.output;
  // The twisting mesh is back-patch culled with the cones of the GPU bounds pass.
  for (const auto& m : j.at("methods")) {
    if (m.at("name") == "tcone" || m.at("name") == "ncone") {
      EXPECT_GT(m.at("cull_rate").get<double>(), 0.02) << m.at("name") << "\n" << v.output;
    }
  }
  // Back-patch methods are skipped on the displaced mesh only.
  EXPECT_NE(v.output.find("skipped tcone on bumpy"), std::string::npos) << v.output;
  EXPECT_EQ(v.output.find("skipped tcone on twister"), std::string::npos) << v.output;

  // A map that cannot be read: the error names the mesh, the JSON path and the file.
  std::string missing = test::displacedScene();
  missing.replace(missing.find("\"procedural\""), 12, "\"missing.png\"");
  const fs::path bad = dir.write("missing.json", missing);
  const auto m = test::runCommand(test::osdCullProgram().string() + " render " + bad.string());
  EXPECT_EQ(m.exitCode(), 1) << m.output;
  EXPECT_NE(m.output.find("mesh 'bumpy': /meshes/0/displacement: "), std::string::npos) << m.output;
  EXPECT_NE(m.output.find("missing.png"), std::string::npos) << m.output;
}

TEST(SceneCommand, BadDisplacementNamesThePath) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_");
  const std::string head = R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube", )";
  const std::string tail =
      R"(}], "views": [{"name": "v", "camera": {"eye": [0, -5, 0], "target": [0, 0, 0]}}]})";
  const std::pair<std::string, std::string> cases[] = {
      {R"("displacement": {"map": "procedural", "bound": "cone"})",
       "/meshes/0/displacement/bound: unknown displaced bound 'cone'"},
      {R"("displacement": {"map": "procedural", "channel": "x"})",
       "/meshes/0/displacement/channel: unknown channel 'x'"},
      {R"("displacement": {"scale": 2})", "/meshes/0/displacement: missing key 'map'"},
      {R"("displacement": {"map": "procedural"})",
       "/meshes/0/displacement: the mesh has no texture coordinates"},
  };
  for (const auto& [mesh, expected] : cases) {
    const fs::path scene = dir.write("bad.json", head + mesh + tail);
    const auto r = test::runCommand(test::osdCullProgram().string() + " render " + scene.string());
    EXPECT_EQ(r.exitCode(), 1) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
  }
}

// A box without its top face (open: back-patch culling off, its inside seen through the
// opening) beside a closed torus.
const char* kOpenBox =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nt sharpness 0/0/0\n";

const char* kOpenBoxScene = R"({
  "version": 1,
  "settings": {"frameCount": 2, "framesPerSecond": 24, "width": 96, "height": 64},
  "meshes": [{"name": "box", "file": "open_box.obj", "level": 1},
             {"name": "torus", "builtIn": "torus", "level": 1}],
  "instances": [{"name": "box", "mesh": "box"},
                {"name": "ring", "mesh": "torus", "transform": {"translate": [0, 3, 0]}}],
  "views": [{"name": "main", "camera": {"eye": [1, -6, 6], "target": [0, 1, 0]},
             "path": {"orbit": {"degreesPerFrame": 10}}}]
})";

TEST(SceneCommand, EveryCullModeCullsBackFacesPerMeshSoTheImagesAreIdentical) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_cli_back_faces_");
  dir.write("open_box.obj", kOpenBox);
  const fs::path scene = dir.write("scene.json", kOpenBoxScene);
  auto frame = [&](const std::string& mode, const std::string& name) {
    return adapters::readPng(dir.path() / mode / (name + ".png")).samples8;
  };
  for (const std::string mode : {"none", "frustum", "occlusion", "backpatch", "all"}) {
    const auto r = test::runCommand(test::osdCullProgram().string() + " render " + scene.string() +
                                    " --validate --tess 2 --cull " + mode + " --out-dir " +
                                    (dir.path() / mode).string());
    ASSERT_EQ(r.exitCode(), 0) << r.output;
    // The loader's notes on a mesh of the scene are printed, as for a mesh file.
    EXPECT_NE(r.output.find("note: mesh 'box': ignored 1 tag line(s) with unknown tag 'sharpness'"),
              std::string::npos)
        << r.output;
  }
  // The open box draws its back faces (its inside) in every mode and the torus culls its
  // own in every mode: the baseline is like for like, and culling changes no pixel.
  for (const std::string mode : {"none", "frustum", "occlusion", "backpatch"})
    for (const char* f : {"main_0000", "main_0001"}) {
      const std::vector<uint8_t> a = frame(mode, f), b = frame("all", f);
      ASSERT_EQ(a.size(), b.size());
      size_t differing = 0;
      for (size_t i = 0; i < a.size(); ++i) differing += a[i] != b[i];
      EXPECT_EQ(differing, 0u) << mode << " " << f;
    }
}

}  // namespace
}  // namespace osd_cull
