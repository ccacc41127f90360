// Input that reads but cannot be drawn or is probably a mistake: coordinates beyond what
// fp32 drawing represents, BPT patches of other degrees, texture-coordinate indices past
// the end, conflicting duplicate tags. Errors name FILE:LINE; mistakes become notes.
#include "adapters/coordinate_limit.h"
#include "adapters/load_mesh.h"
#include "adapters/unused_vertices.h"
#include "osd_cull/error.h"
#include "support/load_errors.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("osd_cull_limits_") {}
};

using test::expectLoadError;

bool hasNote(const CageMesh& mesh, const std::string& phrase) {
  return std::any_of(mesh.notes.begin(), mesh.notes.end(),
                     [&](const std::string& n) { return n.find(phrase) != std::string::npos; });
}

std::string allNotes(const CageMesh& mesh) {
  std::string s;
  for (const auto& n : mesh.notes) s += n + "\n";
  return s;
}

const std::string kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(MeshLimits, CoordinatesBeyondTheFp32DrawingRangeAreErrors) {
  TempDir dir;
  expectLoadError(dir.write("a.obj", "v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n"), 2,
                  {"vertex 2 coordinate 1e+308", "beyond ±1e18", "fp32"});
  expectLoadError(dir.write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 -1e38 0\nf 1 2 3\n"), 3,
                  {"coordinate -1e+38", "beyond ±1e18"});
  expectLoadError(dir.write("c.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 0 1e30\n3 0 1 2\n"), 0,
                  {"vertex 3 has coordinate 1e+30", "beyond ±1e18"});
  std::string points;
  for (int i = 0; i < 16; ++i) points += i == 5 ? "0 2e19 0\n" : "0 0 0\n";
  expectLoadError(dir.write("d.bpt", "1\n3 3\n" + points), 8,
                  {"point 5 of patch 0", "beyond ±1e18"});
  // The limit itself still loads: it is a range, not a sentinel.
  const CageMesh edge =
      adapters::loadCage(dir.write("e.obj", "v 0 0 0\nv 1e18 0 0\nv 0 -1e18 0\nf 1 2 3\n"));
  EXPECT_EQ(edge.positions[1].x, adapters::kMaxCoordinate);
}

TEST(MeshLimits, BptPatchesOfOtherDegreesAreUnsupportedNotTruncated) {
  TempDir dir;
  std::string nine;
  for (int i = 0; i < 9; ++i) nine += "0 0 0\n";
  // Two biquadratic patches: 10 lines each, fewer than the 17 a bicubic patch takes.
  expectLoadError(dir.write("q.bpt", "2\n2 2\n" + nine + "2 2\n" + nine), 2,
                  {"patch 0 has degrees 2 2", "unsupported degrees", "'3 3'"});
  std::string sixteen;
  for (int i = 0; i < 16; ++i) sixteen += "0 0 0\n";
  expectLoadError(dir.write("r.bpt", "2\n3 3\n" + sixteen + "3 1\n" + sixteen), 19,
                  {"patch 1 of 2 has degrees 3 1", "unsupported degrees"});
  expectLoadError(dir.write("s.bpt", "1\n3 x\n" + sixteen), 2, {"expected the degrees '3 3'"});
}

TEST(MeshLimits, TextureCoordinateAndNormalIndicesAreChecked) {
  TempDir dir;
  expectLoadError(dir.write("a.obj", kQuad + "f 1 2 3 4\nf 1/99999999/1 2 3\n"), 6,
                  {"'1/99999999/1'", "texture-coordinate index", "(0 defined so far)"});
  expectLoadError(dir.write("b.obj", kQuad + "vt 0 0\nf 1/1/3 2/1 3/1\n"), 6,
                  {"normal 3", "defines only 0 ('vn' lines)"});
  expectLoadError(dir.write("c.obj", kQuad + "vt 0 0\nf 1/-2 2/1 3/1\n"), 6,
                  {"texture-coordinate index", "(1 defined so far)"});
  expectLoadError(dir.write("d.obj", kQuad + "f 1/0 2 3\n"), 5, {"texture-coordinate index"});
  expectLoadError(dir.write("f.obj", kQuad + "vn 0 0 1\nf 1//-2 2//1 3//1\n"), 6,
                  {"relative normal index -2"});
  // Normals defined after use are accepted (as vertices are): only the final count matters.
  const CageMesh ok =
      adapters::loadCage(dir.write("e.obj", kQuad + "f 1//1 2//1 3//1 4//1\nvn 0 0 1\n"));
  EXPECT_EQ(ok.faceCount(), 1);
}

TEST(MeshLimits, ConflictingDuplicateTagsGetANote) {
  TempDir dir;
  const fs::path file =
      dir.write("a.obj", kQuad +
                             "f 1 2 3 4\n"
                             "t interpolateboundary 1/0/0 1\n"   // line 6
                             "t interpolateboundary 1/0/0 2\n"   // line 7
                             "t crease 2/1/0 0 1 2\n"            // line 8
                             "t crease 2/1/0 1 0 5\n"            // line 9
                             "t crease 2/1/0 2 3 1\n"            // line 10: unique
                             "t corner 1/1/0 2 3\n"              // line 11
                             "t corner 1/1/0 2 3\n"              // line 12: same value
                             "t creasemethod 0/0/1 chaikin\n"    // line 13
                             "t creasemethod 0/0/1 chaikin\n");  // line 14: same value
  const CageMesh mesh = adapters::loadCage(file);
  const std::string at = file.string() + ":";
  EXPECT_TRUE(hasNote(mesh, at + "7: tag 'interpolateboundary' conflicts with line 6"))
      << allNotes(mesh);
  EXPECT_TRUE(
      hasNote(mesh, at + "9: edge (1, 0) is creased again with sharpness 5 (line 8 gave 2)"))
      << allNotes(mesh);
  EXPECT_EQ(mesh.boundary, BoundaryInterpolation::EdgeOnly);  // the last one, 2
  EXPECT_FALSE(hasNote(mesh, "corner sharpness")) << allNotes(mesh);
  EXPECT_FALSE(hasNote(mesh, "creasemethod")) << allNotes(mesh);
  EXPECT_EQ(mesh.notes.size(), 2u) << allNotes(mesh);
}

TEST(MeshLimits, UnusedVerticesAreDroppedAndTheRestRenumberedInOrder) {
  TempDir dir;
  // Vertices 1, 3 and 6 (1-based) are unused; vertex 3 carries a corner tag.
  CageMesh mesh =
      adapters::loadCage(dir.write("a.obj",
                                   "v 9 9 9\nv 0 0 0\nv 8 8 8\nv 1 0 0\nv 1 1 0\nv 7 7 7\nv 0 1 0\n"
                                   "f 2 4 5 7\nt crease 2/1/0 3 4 2\nt corner 2/1/0 2 6 3\n"));
  ASSERT_EQ(mesh.vertexCount(), 7);
  EXPECT_EQ(adapters::dropUnusedVertices(mesh), 3u);
  ASSERT_EQ(mesh.vertexCount(), 4);
  EXPECT_EQ(mesh.positions[0], glm::dvec3(0, 0, 0));
  EXPECT_EQ(mesh.positions[3], glm::dvec3(0, 1, 0));
  EXPECT_EQ(mesh.faceVertices, (std::vector<int>{0, 1, 2, 3}));
  ASSERT_EQ(mesh.creases.size(), 1u);
  EXPECT_EQ(mesh.creases[0].v0, 1);  // 0-based 3 and 4 in the file
  EXPECT_EQ(mesh.creases[0].v1, 2);
  ASSERT_EQ(mesh.corners.size(), 1u);  // the corner on unused vertex 2 (0-based) is gone
  EXPECT_EQ(mesh.corners[0].vertex, 3);
  EXPECT_TRUE(hasNote(mesh, "dropped the 3 unused vertices")) << allNotes(mesh);
  EXPECT_NO_THROW(validate(mesh));
  EXPECT_EQ(adapters::dropUnusedVertices(mesh), 0u);  // nothing left to drop
}

}  // namespace
}  // namespace osd_cull
