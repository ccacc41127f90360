// BPT Bézier patch files: the Utah teapot from the shared data and small inline files.
#include "adapters/load_mesh.h"
#include "osd_cull/error.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using adapters::loadBezierPatches;

// A temp folder whose name says which suite wrote it.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("osd_cull_bpt_") {}
};

// The "x y z" lines of a BPT file, read naively (every line with three numbers).
std::vector<glm::dvec3> pointLines(const fs::path& file) {
  std::vector<glm::dvec3> points;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::stringstream ss(line);
    glm::dvec3 p;
    if (ss >> p.x >> p.y >> p.z) points.push_back(p);
  }
  return points;
}

TEST(BptTeapot, ThirtyTwoBicubicPatchesInFileOrder) {
  OSD_CULL_REQUIRE_DATA();
  const fs::path file = test::dataDir() / "bezier" / "teapot.bpt";
  const PatchSet set = loadBezierPatches(file);
  EXPECT_EQ(set.source, file.string());
  EXPECT_EQ(set.patchCount(), 32u);
  EXPECT_EQ(set.bezierCount, 32u);
  EXPECT_EQ(set.gregoryCount, 0u);
  ASSERT_EQ(set.points.size(), 512u);
  ASSERT_EQ(set.params.size(), 32u);
  ASSERT_EQ(set.origins.size(), 32u);
  // The first point of the file, "1.4 0.0 2.4", and the second (u = 1/3 along the first row).
  EXPECT_EQ(set.points[0], glm::dvec3(1.4, 0.0, 2.4));
  EXPECT_EQ(set.controlPoints(0)[1], glm::dvec3(1.4, -0.784, 2.4));
  // Every point equals the file's point lines in order (u fastest, as PatchSet lays out).
  const std::vector<glm::dvec3> lines = pointLines(file);
  ASSERT_EQ(lines.size(), 512u);
  for (size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(set.points[i], lines[i]) << "point " << i;
  for (uint32_t p = 0; p < 32; ++p) {
    EXPECT_EQ(set.type(p), PatchType::Bezier);
    EXPECT_EQ(set.origins[p], PatchOrigin::Input);
    EXPECT_EQ(set.params[p].GetFaceId(), static_cast<int>(p));
    EXPECT_EQ(set.params[p].GetDepth(), 0);
    EXPECT_EQ(set.params[p].GetU(), 0);
    EXPECT_EQ(set.params[p].GetV(), 0);
    EXPECT_TRUE(set.params[p].IsRegular());
    EXPECT_EQ(set.params[p].GetBoundary(), 0);
  }
}

TEST(BptTeapot, LidTopAndBottomPatchesHaveACollapsedEdge) {
  OSD_CULL_REQUIRE_DATA();
  const PatchSet set = loadBezierPatches(test::dataDir() / "bezier" / "teapot.bpt");
  // SOURCES.md: patches 20-23 (lid top) and 28-31 (bottom) have one edge collapsed to a
  // point; find, for each, a boundary row or column of four equal points.
  auto hasCollapsedEdge = [&](uint32_t patch) {
    const auto cp = set.controlPoints(patch);
    auto same = [&](int a, int b, int c, int d) {
      return cp[a] == cp[b] && cp[b] == cp[c] && cp[c] == cp[d];
    };
    return same(0, 1, 2, 3) || same(12, 13, 14, 15) || same(0, 4, 8, 12) || same(3, 7, 11, 15);
  };
  for (uint32_t p : {20u, 21u, 22u, 23u, 28u, 29u, 30u, 31u})
    EXPECT_TRUE(hasCollapsedEdge(p)) << "patch " << p;
  for (uint32_t p : {0u, 4u, 12u, 16u}) EXPECT_FALSE(hasCollapsedEdge(p)) << "patch " << p;
}

TEST(BptFile, PointsKeepRowMajorOrderWithUFastest) {
  TempDir dir;
  std::string text = "# two patches\n2\n";
  for (int p = 0; p < 2; ++p) {
    text += "3 3\n";
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        text += std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(p) + "\r\n";
  }
  const PatchSet set = loadBezierPatches(dir.write("two.bpt", text + "\n"));
  ASSERT_EQ(set.patchCount(), 2u);
  for (uint32_t p = 0; p < 2; ++p)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        EXPECT_EQ(set.points[set.firstPoint(p) + 4 * j + i], glm::dvec3(i, j, p))
            << p << " " << i << " " << j;
  EXPECT_EQ(set.params[1].GetFaceId(), 1);
}

}  // namespace
}  // namespace osd_cull
