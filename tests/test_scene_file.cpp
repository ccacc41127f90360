// Scene files (adapters/scene_file.h, docs/scene-format.md): a file using every field reads
// into the description it says; instance matrices, parents and camera paths evaluate as
// documented; every kind of bad input is an error naming the JSON path and the problem;
// meshes authored far from the origin are recentred without moving them.
#include "adapters/scene_assets.h"
#include "adapters/scene_file.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/scene_eval.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using scene::SceneDescription;

const fs::path kBase = "/scenes";

SceneDescription parse(const std::string& text) {
  return adapters::parseScene(text, "test.json", kBase);
}

// The message of the error parse() throws, or "" when it does not throw.
std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kFull = R"({
  "version": 1,
  "settings": {"frameStart": 2, "frameCount": 10, "framesPerSecond": 30, "width": 320, "height": 200},
  "meshes": [
    {"name": "blob", "builtIn": "default", "level": 1, "endCaps": "bspline"},
    {"name": "cage", "file": "cages/box.obj", "scheme": "catmark", "recentre": false},
    {"name": "wavy", "builtIn": "torus", "animation": {"deformer": "wave", "axis": 2, "amount": 0.2, "frequency": 1}}
  ],
  "instances": [
    {"name": "a", "mesh": "blob", "transform": {"translate": [1, 2, 3], "rotate": [0, 0, 90], "scale": 2}},
    {"name": "b", "mesh": "cage", "parent": "a",
     "transform": [1, 0, 0, 10,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1], "frameOffset": 15},
    {"name": "c", "mesh": "wavy", "animation": {"spin": {"axis": [0, 0, 1], "degreesPerSecond": 90},
                                             "keys": [{"time": 0, "translate": [0, 0, 0]},
                                                      {"time": 2, "translate": [4, 0, 0]}]}}
  ],
  "occluders": [{"box": {"min": [-1, -1, -1], "max": [1, 1, 0]}}, {"file": "/abs/wall.obj"}],
  "views": [
    {"name": "main", "camera": {"eye": [0, -10, 0], "target": [0, 0, 0], "fovy": 50},
     "path": {"keys": [{"time": 0, "eye": [0, -10, 0], "target": [0, 0, 0]},
                       {"time": 1, "eye": [0, -20, 0], "target": [0, 0, 0]}]}},
    {"name": "orbit", "camera": {"eye": [10, 0, 0], "target": [0, 0, 0], "near": 1, "far": 100},
     "path": {"orbit": {"degreesPerFrame": 3}}},
    {"name": "sun", "shadow": {"direction": [0, 0, -1], "up": [0, 1, 0]}, "width": 128, "height": 128}
  ]
})";

TEST(SceneFile, ReadsEveryField) {
  const SceneDescription s = parse(kFull);
  EXPECT_EQ(s.settings.frameStart, 2u);
  EXPECT_EQ(s.settings.frameCount, 10u);
  EXPECT_DOUBLE_EQ(s.settings.framesPerSecond, 30.0);
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].builtIn, "default");
  EXPECT_EQ(s.meshes[0].patches.isolationLevel, 1);
  EXPECT_EQ(s.meshes[0].patches.endCaps, EndCap::BSplineBasis);
  EXPECT_EQ(s.meshes[1].file, (kBase / "cages/box.obj").string());
  EXPECT_FALSE(s.meshes[1].recentre);
  EXPECT_EQ(s.meshes[2].animation.kind, scene::AnimationSource::Kind::Wave);
  EXPECT_EQ(s.meshes[2].animation.deformer.axis, 2);
  EXPECT_DOUBLE_EQ(s.meshes[2].animation.deformer.amount, 0.2);
  ASSERT_EQ(s.instances.size(), 3u);
  EXPECT_EQ(s.instances[1].mesh, 1u);
  EXPECT_EQ(s.instances[1].parent, 0u);
  EXPECT_DOUBLE_EQ(s.instances[1].timeOffsetSeconds, 0.5);  // 15 frames at 30 fps
  EXPECT_DOUBLE_EQ(s.instances[1].transform[3][0], 10.0);   // row-major text, column-major GLM
  ASSERT_EQ(s.occluders.size(), 2u);
  EXPECT_EQ(s.occluders[1].file, "/abs/wall.obj");
  ASSERT_EQ(s.views.size(), 3u);
  EXPECT_EQ(s.views[0].keys.size(), 2u);
  EXPECT_DOUBLE_EQ(s.views[1].orbitDegreesPerSecond, 90.0);  // 3 degrees x 30 fps
  EXPECT_EQ(s.views[2].kind, scene::ViewDescription::Kind::Shadow);
  EXPECT_EQ(s.views[2].width, 128u);
}

TEST(SceneFile, InstanceMatricesComposeParentsSpinsAndKeys) {
  const SceneDescription s = parse(kFull);
  // a: T(1,2,3) Rz(90) S(2): object x axis goes to world +y, doubled.
  const glm::dvec3 ax = glm::dvec3(scene::instanceMatrix(s, 0, 0.0) * glm::dvec4(1, 0, 0, 1));
  EXPECT_NEAR(ax.x, 1.0, 1e-12);
  EXPECT_NEAR(ax.y, 4.0, 1e-12);
  EXPECT_NEAR(ax.z, 3.0, 1e-12);
  // b: 10 along a's x axis, inside a: (1, 2 + 2 * 10, 3).
  const glm::dvec3 b = glm::dvec3(scene::instanceMatrix(s, 1, 0.0) * glm::dvec4(0, 0, 0, 1));
  EXPECT_NEAR(b.x, 1.0, 1e-12);
  EXPECT_NEAR(b.y, 22.0, 1e-12);
  // c at t = 1: spun 90 degrees, translated halfway to (4, 0, 0).
  const glm::dvec3 c = glm::dvec3(scene::instanceMatrix(s, 2, 1.0) * glm::dvec4(1, 0, 0, 1));
  EXPECT_NEAR(c.x, 2.0, 1e-12);
  EXPECT_NEAR(c.y, 1.0, 1e-12);
  // Clamped after the last key.
  const glm::dvec3 late = glm::dvec3(scene::instanceMatrix(s, 2, 8.0) * glm::dvec4(0, 0, 0, 1));
  EXPECT_NEAR(late.x, 4.0, 1e-12);
}

TEST(SceneFile, CameraPathsInterpolateOrbitAndFrameTheScene) {
  const SceneDescription s = parse(kFull);
  const frame::Bounds bounds{{-1, -1, -1}, {1, 1, 1}};
  const frame::Camera mid = scene::viewCamera(s.views[0], s.settings, bounds, 0.5);
  EXPECT_NEAR(mid.eye().y, -15.0, 1e-9);
  EXPECT_EQ(mid.width, 320u);
  const frame::Camera turned = scene::viewCamera(s.views[1], s.settings, bounds, 1.0);
  EXPECT_NEAR(turned.eye().x, 0.0, 1e-9);  // 90 degrees about z from (10, 0, 0)
  EXPECT_NEAR(turned.eye().y, 10.0, 1e-9);
  // The shadow view sees every corner of the bounds inside its clip volume.
  const frame::Camera sun = scene::viewCamera(s.views[2], s.settings, bounds, 0.0);
  EXPECT_EQ(sun.width, 128u);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec4 p =
        sun.viewProjection() * glm::dvec4(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1, 1.0);
    EXPECT_LE(std::abs(p.x / p.w), 1.0);
    EXPECT_LE(std::abs(p.y / p.w), 1.0);
    EXPECT_GE(p.z / p.w, 0.0);
    EXPECT_LE(p.z / p.w, 1.0);
  }
}

TEST(SceneFile, SkinningReadsItsRig) {
  const SceneDescription s = parse(R"({"version": 1,
    "meshes": [{"name": "guy", "builtIn": "character",
                "animation": {"deformer": "skin", "rig": "limbs", "swingDegrees": 40}}],
    "views": [{"name": "v", "camera": {"eye": [0, -5, 1], "target": [0, 0, 1]}}]})");
  EXPECT_EQ(s.meshes[0].animation.kind, scene::AnimationSource::Kind::Skin);
  EXPECT_EQ(s.meshes[0].animation.skinning.rig, scene::SkinningRig::Limbs);
  EXPECT_DOUBLE_EQ(s.meshes[0].animation.skinning.swingDegrees, 40.0);
  // Loaded, the character deforms: its cage moves between two times.
  const scene::LoadedScene loaded = adapters::loadScene(s);
  ASSERT_NE(loaded.meshes[0].animation, nullptr);
  std::vector<glm::dvec3> a(loaded.meshes[0].animation->vertexCount()), b = a;
  loaded.meshes[0].animation->positions(0.0, a);
  loaded.meshes[0].animation->positions(0.4, b);
  EXPECT_NE(a, b);
}

TEST(SceneFile, MissingInstancesMeanOneInstancePerMesh) {
  const SceneDescription s = parse(R"({"version": 1,
    "meshes": [{"name": "m", "builtIn": "cube"}, {"name": "n", "builtIn": "torus"}],
    "views": [{"name": "v", "camera": {"eye": [0, -5, 0], "target": [0, 0, 0]}}]})");
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[1].mesh, 1u);
}

struct BadCase {
  const char* what;
  std::string text;
  std::string expected;  // a substring of the error
};

std::string withInstances(const std::string& instances) {
  return R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube"}],
    "views": [{"name": "v", "camera": {"eye": [0, -5, 0], "target": [0, 0, 0]}}],
    "instances": )" +
         instances + "}";
}

TEST(SceneFile, BadInputNamesThePathAndTheProblem) {
  const std::vector<BadCase> cases = {
      {"malformed", R"({"version": 1, )", "test.json: /: malformed JSON"},
      {"unknown top-level key", R"({"version": 1, "model": []})", "/model: unknown key"},
      {"wrong version", R"({"version": 2, "meshes": [], "views": []})",
       "/version: version 2 is not supported"},
      {"matrix of 12", withInstances(R"([{"mesh": "m"}, {"mesh": "m"},
        {"mesh": "m", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0]}])"),
       "/instances/2/transform: expected 16 numbers, got 12"},
      {"projective matrix", withInstances(R"([{"mesh": "m",
        "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}])"),
       "/instances/0/transform: the last row must be 0 0 0 1"},
      {"unknown mesh", withInstances(R"([{"mesh": "nope"}])"),
       "/instances/0/mesh: unknown mesh 'nope'"},
      {"unknown transform key", withInstances(R"([{"mesh": "m", "transform": {"move": [1,2,3]}}])"),
       "/instances/0/transform/move: unknown key"},
      {"zero scale", withInstances(R"([{"mesh": "m", "transform": {"scale": [1, 0, 1]}}])"),
       "/instances/0/transform/scale: a scale factor of 0"},
      {"scale beyond a double",
       withInstances(R"([{"mesh": "m"}, {"mesh": "m", "transform": {"scale": 1e400}}])"),
       "test.json: /instances/1/transform/scale: malformed JSON: number overflow parsing '1e400'"},
      {"scale component beyond a double",
       withInstances(R"([{"mesh": "m", "transform": {"scale": [1, 1e400, 1]}}])"),
       "test.json: /instances/0/transform/scale/1: malformed JSON: number overflow"},
      {"parent cycle", withInstances(R"([{"name": "a", "mesh": "m", "parent": "b"},
        {"name": "b", "mesh": "m", "parent": "a"}])"),
       "/instances/0/parent: parent cycle"},
      {"self parent", withInstances(R"([{"name": "a", "mesh": "m", "parent": "a"}])"),
       "parent cycle"},
      {"duplicate instance",
       withInstances(R"([{"name": "a", "mesh": "m"}, {"name": "a", "mesh": "m"}])"),
       "/instances/1/name: a second instance named 'a'"},
      {"keys back in time", withInstances(R"([{"mesh": "m", "animation": {"keys": [
        {"time": 0, "translate": [0,0,0]}, {"time": 1, "translate": [1,0,0]},
        {"time": 1, "translate": [2,0,0]}]}}])"),
       "/instances/0/animation/keys/2/time: key frame times must increase"},
      {"displaced box", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube",
        "displacement": {"map": "d.png", "box": "sphere"}}], "views": []})",
       "/meshes/0/displacement/box: unknown displaced box 'sphere' (expected oobb or caf)"},
      {"displaced bound", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube",
        "animation": {"deformer": "wave"}, "displacement": {"map": "d.png", "bound": 2}}],
        "views": []})",
       "/meshes/0/displacement/bound: expected a string"},
      {"unknown built-in",
       R"({"version": 1, "meshes": [{"name": "m", "builtIn": "teapot"}], "views": []})",
       "/meshes/0/builtIn: unknown built-in mesh 'teapot'"},
      {"file and built-in",
       R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube", "file": "a.obj"}], "views": []})",
       "/meshes/0: give exactly one of 'file' and 'builtIn'"},
      {"unknown deformer", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube",
        "animation": {"deformer": "melt"}}], "views": []})",
       "/meshes/0/animation/deformer: unknown deformer 'melt'"},
      {"unknown rig", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "character",
        "animation": {"deformer": "skin", "rig": "octopus"}}], "views": []})",
       "/meshes/0/animation/rig: unknown rig 'octopus'"},
      {"level out of range",
       R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube", "level": 11}], "views": []})",
       "/meshes/0/level: expected an integer in [0, 10], got 11"},
      {"no views", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube"}], "views": []})",
       "/views: a scene needs at least one view"},
      {"eye on target", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube"}],
        "views": [{"name": "v", "camera": {"eye": [1, 1, 1], "target": [1, 1, 1]}}]})",
       "/views/0/camera/target: the target equals the eye"},
      {"string for number",
       R"({"version": 1, "settings": {"width": "wide"}, "meshes": [], "views": []})",
       "/settings/width: expected an integer"},
      {"camera and shadow", R"({"version": 1, "meshes": [{"name": "m", "builtIn": "cube"}],
        "views": [{"name": "v", "shadow": {"direction": [0,0,-1]}, "camera": {"eye": [0,-5,0], "target": [0,0,0]}}]})",
       "/views/0: give exactly one of 'camera' and 'shadow'"},
  };
  for (const BadCase& c : cases) {
    const std::string message = errorOf(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << c.what << ": expected '" << c.expected << "' in '" << message << "'";
  }
}

TEST(SceneFile, AnInstanceScaledToNoSizeNamesItsDegenerateExtent) {
  const SceneDescription s = parse(withInstances(
      R"([{"name": "big", "mesh": "m"}, {"name": "speck", "mesh": "m",
          "transform": {"scale": 1e-300}}])"));
  try {
    adapters::loadScene(s);
    FAIL() << "loaded an instance of extent 1e-300";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test.json: instance 'speck' of mesh 'm': degenerate extent"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("below 1e-18"), std::string::npos) << what;
    EXPECT_NE(what.find("check the instance's transform and scale"), std::string::npos) << what;
    EXPECT_EQ(what.find("camera"), std::string::npos) << what;
  }
}

TEST(SceneFile, TheLoadersNotesOnAMeshAreKept) {
  test::TempDir dir("osd_cull_scene_notes_");
  dir.write("tagged.obj",
            "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\n"
            "v -1 1 1\nf 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nf 5 6 7 8\n"
            "t crease 2/1/0 0 1 -2\nt foo 0/0/0\n");
  const SceneDescription s = adapters::parseScene(R"({"version": 1,
    "meshes": [{"name": "box", "file": "tagged.obj"}],
    "views": [{"name": "v", "camera": {"eye": [0, -5, 0], "target": [0, 0, 0]}}]})",
                                                  "notes.json", dir.path());
  const scene::LoadedScene loaded = adapters::loadScene(s);
  std::string notes;
  for (const std::string& n : loaded.meshes[0].notes) notes += n + "\n";
  EXPECT_NE(notes.find("unknown tag 'foo'"), std::string::npos) << notes;
  EXPECT_NE(notes.find("negative sharpness value(s) clamped to 0"), std::string::npos) << notes;
}

TEST(SceneFile, UnreadableFileIsAnError) {
  EXPECT_THROW(adapters::loadSceneFile("/nonexistent/scene.json"), Error);
}

TEST(SceneFile, FarAwayCageIsRecentredWithoutMoving) {
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "scene_file";
  fs::create_directories(dir);
  {
    std::ofstream obj(dir / "far_cube.obj");
    const double o = 1e5;
    for (int i = 0; i < 8; ++i)
      obj << "v " << o + (i & 1 ? 1 : -1) << " " << (i & 2 ? 1 : -1) << " " << (i & 4 ? 1 : -1)
          << "\n";
    obj << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    std::ofstream(dir / "far.json") << R"({"version": 1,
      "meshes": [{"name": "far", "file": "far_cube.obj", "level": 1}],
      "instances": [{"mesh": "far", "transform": {"translate": [0, 0, 5]}}],
      "views": [{"name": "v", "camera": {"eye": [100000, -8, 5], "target": [100000, 0, 5]}}]})";
  }
  const scene::LoadedScene s = adapters::loadScene(dir / "far.json");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_NEAR(s.meshes[0].recentreOffset.x, 1e5, 1e-9);
  EXPECT_LT(glm::length(s.meshes[0].restBounds.center()), 1e-9);
  EXPECT_LT(s.meshes[0].restBounds.radius(), 2.0);
  // The instance's patches land where the file put them, moved by the instance transform.
  const glm::dvec3 c = glm::dvec3(scene::patchModel(s, 0, 0.0) * glm::dvec4(0, 0, 0, 1));
  EXPECT_NEAR(c.x, 1e5, 1e-9);
  EXPECT_NEAR(c.z, 5.0, 1e-9);
}

}  // namespace
}  // namespace osd_cull
