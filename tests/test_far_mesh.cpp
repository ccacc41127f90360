// A mesh file authored far from the origin: the mesh form of the commands recentres it at
// load (scene::farMeshOffset), as scenes do, so that it is drawn and culled with the fp32
// precision of the same mesh at the origin (issue 23).
#include "adapters/image_png.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/plan/calibration.h"
#include "osd_cull/scene/loaded_scene.h"
#include "osd_cull/scene/procedural.h"
#include "support/obj_file.h"
#include "support/plan_calibration.h"
#include "support/run_command.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

TEST(FarMeshOffset, IsTheBoundingBoxCentreOnlyWhenTheOriginLiesOutsideTheBoundingSphere) {
  CageMesh cage = scene::cube();  // the unit cube about the origin
  EXPECT_EQ(scene::farMeshOffset(cage.positions), glm::dvec3(0.0));
  scene::translate(cage, {0.3, 0.0, 0.0});  // off centre, the origin still inside
  EXPECT_EQ(scene::farMeshOffset(cage.positions), glm::dvec3(0.0));
  const glm::dvec3 centre = frame::boundsOf(cage.positions).center();
  scene::translate(cage, {1e5, -2e5, 3e5});
  const glm::dvec3 offset = scene::farMeshOffset(cage.positions);
  EXPECT_DOUBLE_EQ(offset.x, centre.x + 1e5);
  EXPECT_DOUBLE_EQ(offset.y, centre.y - 2e5);
  EXPECT_DOUBLE_EQ(offset.z, centre.z + 3e5);
  EXPECT_EQ(scene::farMeshOffset({}), glm::dvec3(0.0));
}

TEST(FarMeshOffset, RecentreMovesTheBoundingBoxCentreToTheOrigin) {
  CageMesh cage = scene::torus();
  scene::translate(cage, {1e6, 2.0, -3.0});
  const glm::dvec3 offset = scene::recentre(cage.positions);
  EXPECT_NEAR(offset.x, 1e6, 1e-6);
  const frame::Bounds b = frame::boundsOf(cage.positions);
  EXPECT_NEAR(glm::length(b.center()), 0.0, 1e-9);
}

TEST(FarMeshOffset, RecentreFarMovesOnlyAMeshWhoseBoundingSphereMissesTheOrigin) {
  CageMesh cage = scene::cube();
  scene::translate(cage, {0.3, 0.0, 0.0});
  const std::vector<glm::dvec3> near = cage.positions;
  EXPECT_EQ(scene::recentreFar(cage.positions), glm::dvec3(0.0));
  EXPECT_EQ(cage.positions, near);  // left as authored
  scene::translate(cage, glm::dvec3(1e5));
  const glm::dvec3 offset = scene::recentreFar(cage.positions);
  EXPECT_NEAR(offset.x, 1e5 + 0.3, 1e-9);
  EXPECT_NEAR(offset.y, 1e5, 1e-9);
  EXPECT_NEAR(glm::length(frame::boundsOf(cage.positions).center()), 0.0, 1e-9);
  EXPECT_NEAR(cage.positions[0].x, near[0].x - 0.3, 1e-9);  // the same shape, about the origin
}

// The character cage about the origin (origin/mesh.obj) and moved by +1e5 on every axis
// (far/mesh.obj): the same file name, so that the commands print the same mesh name.
struct FarPair {
  fs::path origin, far;
};

FarPair writeFarPair(const fs::path& dir) {
  fs::create_directories(dir / "origin");
  fs::create_directories(dir / "far");
  CageMesh cage = scene::character();
  scene::recentre(cage.positions);
  test::writeObj(cage, dir / "origin" / "mesh.obj");
  scene::translate(cage, glm::dvec3(1e5));
  test::writeObj(cage, dir / "far" / "mesh.obj");
  return {dir / "origin" / "mesh.obj", dir / "far" / "mesh.obj"};
}

// The frame's statistics and image of `mesh` culled with every stage.
struct Rendered {
  nlohmann::json frame;
  adapters::PngImage image;
  std::string output;
};

Rendered renderAll(const fs::path& mesh, const fs::path& dir, const std::string& name) {
  const test::CommandResult r = test::runCommand(
      test::osdCullProgram().string() + " render " + mesh.string() +
      " --level 1 --tess 2 --width 96 --height 96 --cull all --validate --out " +
      (dir / (name + ".png")).string() + " --stats " + (dir / (name + ".json")).string());
  EXPECT_EQ(r.exitCode(), 0) << r.output;
  std::ifstream in(dir / (name + ".json"));
  const nlohmann::json doc = nlohmann::json::parse(in);
  return {doc["frames"][0], adapters::readPng(dir / (name + ".png")), r.output};
}

TEST(FarMeshRender, CullsAndDrawsAsTheSameMeshAtTheOrigin) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "far_mesh";
  fs::create_directories(dir);
  const FarPair files = writeFarPair(dir);
  const Rendered origin = renderAll(files.origin, dir, "origin");
  const Rendered far = renderAll(files.far, dir, "far");
  EXPECT_EQ(origin.output.find("recentred"), std::string::npos) << origin.output;
  EXPECT_NE(far.output.find("note: the mesh lies far from the origin: recentred by (100000"),
            std::string::npos)
      << far.output;
  const double patches = origin.frame["patches"].get<double>();
  ASSERT_GT(patches, 0.0);
  for (const char* stage : {"backPatch", "occlusion"}) {
    const double atOrigin = origin.frame["culled"][stage].get<double>() / patches;
    const double atFar = far.frame["culled"][stage].get<double>() / patches;
    EXPECT_GT(atOrigin, 0.02) << stage;           // the comparison means something
    EXPECT_NEAR(atFar, atOrigin, 0.01) << stage;  // within one point
  }
  // verify (random views framed on the recentred bounds) says so too, and finds no false cull.
  const test::CommandResult v =
      test::runCommand(test::osdCullProgram().string() + " verify " + files.far.string() +
                       " --level 1 --views 3 --width 64 --height 64 --tess 2");
  EXPECT_EQ(v.exitCode(), 0) << v.output;
  EXPECT_NE(v.output.find("note: the mesh lies far from the origin"), std::string::npos)
      << v.output;
  ASSERT_EQ(far.image.samples8.size(), origin.image.samples8.size());
  size_t differing = 0;
  for (size_t i = 0; i < origin.image.samples8.size(); ++i)
    differing += far.image.samples8[i] != origin.image.samples8[i];
  EXPECT_EQ(differing, 0u);
}

// The printed plan without its header (which names the file) and the loader's notes.
std::string planWithoutHeaderAndNotes(const std::string& output) {
  std::string kept;
  size_t start = 0;
  while (start < output.size()) {
    const size_t end = std::min(output.find('\n', start), output.size());
    const std::string line = output.substr(start, end - start);
    if (line.rfind("note: ", 0) != 0 && line.rfind("plan of ", 0) != 0) kept += line + "\n";
    start = end + 1;
  }
  return kept;
}

TEST(FarMeshPlan, PlansAsTheSameMeshAtTheOrigin) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "far_mesh_plan";
  const FarPair files = writeFarPair(dir);
  const fs::path calibration = dir / "synthetic.txt";
  plan::storeCalibration(test::syntheticCalibration(), calibration);
  auto plan = [&](const fs::path& mesh) {
    const test::CommandResult r = test::runCommand(
        "OSD_CULL_CALIBRATION_CACHE=off " + test::osdCullProgram().string() + " plan " +
        mesh.string() + " --level 1 --calibration " + calibration.string());
    EXPECT_EQ(r.exitCode(), 0) << r.output;
    return r.output;
  };
  const std::string origin = plan(files.origin), far = plan(files.far);
  EXPECT_EQ(origin.find("recentred"), std::string::npos) << origin;
  EXPECT_NE(far.find("note: the mesh lies far from the origin: recentred by (100000"),
            std::string::npos)
      << far;
  ASSERT_NE(planWithoutHeaderAndNotes(origin).find("predicted:"), std::string::npos) << origin;
  EXPECT_EQ(planWithoutHeaderAndNotes(far), planWithoutHeaderAndNotes(origin));
}

}  // namespace
}  // namespace osd_cull
