// Triangle-mesh occluders from OBJ files (adapters::loadTriangleMesh).
#include "adapters/load_occluder.h"
#include "osd_cull/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

fs::path writeFile(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "occluder_loader";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

TEST(OccluderLoader, PolygonsBecomeTriangleFans) {
  // A quad, a pentagon and two triangles; edge 1-2 is shared by three faces (non-manifold:
  // fine for an occluder, refused for a cage).
  const fs::path p = writeFile("walls.obj",
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nv 3 0.5 0\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\n"
                               "f 1 2 3 4\nf 2 5 7 6 3\nf 1/1 2/2 3/3\nf 1 2 4\n");
  const frame::TriangleMesh m = adapters::loadTriangleMesh(p);
  EXPECT_EQ(m.positions.size(), 7u);
  ASSERT_EQ(m.indices.size(), 3u * (2 + 3 + 1 + 1));
  EXPECT_EQ(std::vector<uint32_t>(m.indices.begin(), m.indices.begin() + 6),
            (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(std::vector<uint32_t>(m.indices.begin() + 6, m.indices.begin() + 15),
            (std::vector<uint32_t>{1, 4, 6, 1, 6, 5, 1, 5, 2}));
}

TEST(OccluderLoader, HoleTagsDropFaces) {
  const fs::path p = writeFile(
      "hole.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nt hole 1/0/0 1\n");
  const frame::TriangleMesh m = adapters::loadTriangleMesh(p);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(OccluderLoader, BadFilesAreRefusedWithFileAndLine) {
  try {
    adapters::loadTriangleMesh(writeFile("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n"));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj:3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(adapters::loadTriangleMesh(writeFile("mesh.off", "OFF\n")), Error);
  EXPECT_THROW(adapters::loadTriangleMesh(writeFile("empty.obj", "v 0 0 0\n")), Error);
}

}  // namespace
}  // namespace osd_cull
