#include "osd_cull/error.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace osd_cull {
namespace {

using scene::cube;

TEST(Refiner, CubeIsClosedWithEightValenceThreeVertices) {
  auto refiner = makeTopologyRefiner(cube());
  const TopologySummary s = summarize(*refiner);
  EXPECT_EQ(s.vertices, 8);
  EXPECT_EQ(s.faces, 6);
  EXPECT_EQ(s.edges, 12);
  EXPECT_EQ(s.quads, 6);
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.maxValence, 3);
  EXPECT_EQ(s.extraordinaryVertices, 8);
  EXPECT_TRUE(s.closed);
}

TEST(Refiner, RemovingAFaceOpensTheCube) {
  CageMesh m = cube();
  m.faceSizes.pop_back();
  m.faceVertices.resize(m.faceVertices.size() - 4);
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_EQ(s.boundaryEdges, 4);
  EXPECT_FALSE(s.closed);
}

TEST(Refiner, CreasesCornersAndHolesReachOpenSubdiv) {
  CageMesh m = cube();
  m.creases = {{0, 1, 2.5f}};
  m.corners = {{6, 10.0f}};
  m.holes = {1};
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_EQ(s.creasedEdges, 1);
  EXPECT_EQ(s.cornerVertices, 1);
  EXPECT_EQ(s.holes, 1);
  EXPECT_FALSE(s.closed);
}

TEST(Refiner, RejectsNaNCoordinatesNamingTheVertex) {
  CageMesh m = cube();
  m.positions[5].y = std::numeric_limits<double>::quiet_NaN();
  try {
    makeTopologyRefiner(m);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 5"), std::string::npos) << e.what();
  }
}

TEST(Refiner, RejectsOutOfRangeIndexAndShortFace) {
  CageMesh m = cube();
  m.faceVertices[3] = 8;
  EXPECT_THROW(makeTopologyRefiner(m), Error);
  m = cube();
  m.faceSizes = {2};
  m.faceVertices = {0, 1};
  EXPECT_THROW(makeTopologyRefiner(m), Error);
  m = cube();
  m.faceSizes.clear();
  m.faceVertices.clear();
  EXPECT_THROW(makeTopologyRefiner(m), Error);
}

TEST(Refiner, RejectsNegativeSharpness) {
  CageMesh m = cube();
  m.creases = {{0, 1, -1.0f}};
  EXPECT_THROW(makeTopologyRefiner(m), Error);
}

}  // namespace
}  // namespace osd_cull
