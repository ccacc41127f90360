// Generated cages: counts, valences, closedness and orientation as OpenSubdiv sees them.
#include "adapters/topology_notes.h"
#include "osd_cull/error.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

namespace osd_cull {
namespace {

// Volume enclosed by the faces (fan-triangulated); positive when faces wind outward.
double signedVolume(const CageMesh& m) {
  double volume = 0.0;
  size_t o = 0;
  for (int n : m.faceSizes) {
    const glm::dvec3& p0 = m.positions[static_cast<size_t>(m.faceVertices[o])];
    for (int k = 1; k + 1 < n; ++k)
      volume +=
          glm::dot(p0, glm::cross(m.positions[static_cast<size_t>(m.faceVertices[o + k])],
                                  m.positions[static_cast<size_t>(m.faceVertices[o + k + 1])])) /
          6.0;
    o += static_cast<size_t>(n);
  }
  return volume;
}

// A closed, manifold, consistently oriented cage with no notes from the loader's checks.
TopologySummary expectClosedManifold(const CageMesh& m) {
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_TRUE(s.closed) << m.source;
  EXPECT_EQ(s.boundaryEdges, 0) << m.source;
  EXPECT_EQ(s.nonManifoldEdges, 0) << m.source;
  EXPECT_EQ(s.nonManifoldVertices, 0) << m.source;
  EXPECT_EQ(s.unusedVertices, 0) << m.source;
  EXPECT_EQ(s.degenerateFaces, 0) << m.source;
  EXPECT_EQ(s.vertices - s.edges + s.faces, 2 - 2 * (m.source == "built-in:torus"))
      << m.source;  // genus 0 or 1
  CageMesh copy = m;
  const adapters::TopologyFindings found = adapters::noteTopology(copy);
  EXPECT_EQ(found.orientationConflicts, 0) << m.source;
  EXPECT_GT(signedVolume(m), 0.0) << m.source
                                  << ": faces must wind counter-clockwise seen from outside";
  return s;
}

TEST(Procedural, CubeHasEightValenceThreeCorners) {
  const CageMesh m = scene::cube();
  EXPECT_EQ(m.source, "built-in:cube");
  const TopologySummary s = expectClosedManifold(m);
  EXPECT_EQ(s.vertices, 8);
  EXPECT_EQ(s.faces, 6);
  EXPECT_EQ(s.edges, 12);
  EXPECT_EQ(s.maxValence, 3);
  EXPECT_EQ(s.extraordinaryVertices, 8);
  EXPECT_NEAR(signedVolume(m), 8.0, 1e-12);
}

TEST(Procedural, TorusIsRegularEverywhere) {
  const CageMesh m = scene::torus(12, 8, 1.0, 0.4);
  const TopologySummary s = expectClosedManifold(m);
  EXPECT_EQ(s.vertices, 96);
  EXPECT_EQ(s.faces, 96);
  EXPECT_EQ(s.quads, 96);
  EXPECT_EQ(s.edges, 192);
  EXPECT_EQ(s.maxValence, 4);
  EXPECT_EQ(s.extraordinaryVertices, 0);
  // The polygonal torus is inscribed in the smooth one (volume 2 pi^2 R r^2).
  const double smooth = 2.0 * std::numbers::pi * std::numbers::pi * 1.0 * 0.4 * 0.4;
  EXPECT_LT(signedVolume(m), smooth);
  EXPECT_GT(signedVolume(m), 0.7 * smooth);
  EXPECT_EQ(summarize(*makeTopologyRefiner(scene::torus(3, 3, 2.0, 1.0))).vertices, 9);
}

TEST(Procedural, TorusRejectsBadArguments) {
  EXPECT_THROW(scene::torus(2, 8), Error);
  EXPECT_THROW(scene::torus(8, 8, 1.0, 1.5), Error);
  EXPECT_THROW(scene::torus(8, 8, 1.0, 0.0), Error);
}

TEST(Procedural, PoleSphereHasTwoPolesOfTheChosenValence) {
  for (int n : {3, 4, 5, 7, 16, 64, 100}) {
    for (int rings : {1, 3}) {
      const CageMesh m = scene::poleSphere(n, rings);
      EXPECT_EQ(m.source, "built-in:pole-sphere-" + std::to_string(n));
      const auto refiner = makeTopologyRefiner(m);
      const TopologySummary s = expectClosedManifold(m);
      EXPECT_EQ(s.vertices, 2 + rings * n);
      EXPECT_EQ(s.triangles, 2 * n);
      EXPECT_EQ(s.quads, (rings - 1) * n);
      EXPECT_EQ(s.edges, n * (2 * rings + 1));
      const auto& level = refiner->GetLevel(0);
      EXPECT_EQ(level.GetVertexEdges(0).size(), n);  // north pole
      EXPECT_EQ(level.GetVertexEdges(1).size(), n);  // south pole
      for (int v = 2; v < s.vertices; ++v)
        ASSERT_EQ(level.GetVertexEdges(v).size(), 4) << "n " << n << " vertex " << v;
      EXPECT_EQ(s.maxValence, std::max(n, 4));
      EXPECT_EQ(s.extraordinaryVertices, n == 4 ? 0 : 2) << "n " << n;
      for (const glm::dvec3& p : m.positions) EXPECT_NEAR(glm::length(p), 1.0, 1e-12);
    }
  }
  EXPECT_THROW(scene::poleSphere(2), Error);
  EXPECT_THROW(scene::poleSphere(5, 0), Error);
}

TEST(Procedural, CreasedCubeCarriesItsTagsIntoOpenSubdiv) {
  const CageMesh m = scene::creasedCube();
  const auto refiner = makeTopologyRefiner(m);
  const TopologySummary s = expectClosedManifold(m);
  EXPECT_EQ(s.creasedEdges, 5);
  EXPECT_EQ(s.cornerVertices, 1);
  const auto& level = refiner->GetLevel(0);
  EXPECT_FLOAT_EQ(level.GetEdgeSharpness(level.FindEdge(4, 5)), 2.0f);
  EXPECT_FLOAT_EQ(level.GetEdgeSharpness(level.FindEdge(7, 4)), 2.0f);
  EXPECT_FLOAT_EQ(level.GetEdgeSharpness(level.FindEdge(2, 6)), 10.0f);
  EXPECT_FLOAT_EQ(level.GetEdgeSharpness(level.FindEdge(0, 1)), 0.0f);
  EXPECT_FLOAT_EQ(level.GetVertexSharpness(0), 3.0f);
  EXPECT_FLOAT_EQ(level.GetVertexSharpness(6), 0.0f);
}

TEST(Procedural, CollapsedFaceCubeHasAZeroAreaFaceAndCubeTopology) {
  const CageMesh m = scene::collapsedFaceCube();
  EXPECT_EQ(m.source, "built-in:collapsed-face");
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.edges, 12);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  // Face 1 is the top face (4, 5, 6, 7): its area (half the diagonals' cross product) is 0.
  const auto& p = m.positions;
  const glm::dvec3 areaVector = 0.5 * glm::cross(p[6] - p[4], p[7] - p[5]);
  EXPECT_EQ(glm::length(areaVector), 0.0);
  EXPECT_EQ(p[4], p[7]);
  EXPECT_EQ(p[5], p[6]);
  EXPECT_GT(signedVolume(m), 0.0);
}

TEST(Procedural, DefaultMeshIsAClosedCreasedBlobWithEightExtraordinaryVertices) {
  const CageMesh m = scene::defaultMesh();
  EXPECT_EQ(m.source, "built-in:default");
  const TopologySummary s = expectClosedManifold(m);
  EXPECT_EQ(s.vertices, 98);
  EXPECT_EQ(s.faces, 96);
  EXPECT_EQ(s.quads, 96);
  EXPECT_EQ(s.edges, 192);
  EXPECT_EQ(s.maxValence, 4);
  EXPECT_EQ(s.extraordinaryVertices, 8);
  EXPECT_EQ(s.creasedEdges, 16);
  ASSERT_EQ(m.creases.size(), 16u);
  for (const CreaseEdge& c : m.creases) EXPECT_EQ(c.sharpness, 2.0f);
  // The crease is a single loop: every vertex on it has exactly two crease edges.
  std::map<int, int> creaseValence;
  for (const CreaseEdge& c : m.creases) ++creaseValence[c.v0], ++creaseValence[c.v1];
  EXPECT_EQ(creaseValence.size(), 16u);
  for (const auto& [v, count] : creaseValence) EXPECT_EQ(count, 2) << "vertex " << v;
  for (const glm::dvec3& p : m.positions) EXPECT_GT(glm::length(p), 0.8);
}

TEST(Procedural, BuiltInMeshByName) {
  for (const char* name :
       {"cube", "torus", "creased-cube", "collapsed-face", "default", "pole-sphere-5"}) {
    const auto m = scene::builtInMesh(name);
    ASSERT_TRUE(m.has_value()) << name;
    EXPECT_EQ(m->source, std::string("built-in:") + name);
    EXPECT_NO_THROW(makeTopologyRefiner(*m)) << name;
    EXPECT_TRUE(scene::builtInMesh(m->source).has_value()) << m->source;
  }
  EXPECT_EQ(scene::builtInMesh("pole-sphere-9")->vertexCount(), 2 + 3 * 9);
  for (const char* bad :
       {"", "sphere", "pole-sphere-2", "pole-sphere-", "pole-sphere-5x", "built-in:"})
    EXPECT_FALSE(scene::builtInMesh(bad).has_value()) << bad;
  EXPECT_EQ(scene::builtInMeshNames().size(), 7u);
}

TEST(Procedural, CharacterIsAClosedOutwardFigureStandingOnItsFeet) {
  const CageMesh m = scene::character();
  EXPECT_EQ(m.source, "built-in:character");
  const TopologySummary s = expectClosedManifold(m);
  EXPECT_GT(s.extraordinaryVertices, 0);
  // 21 voxels of 0.3 x 0.45 x 0.3.
  EXPECT_NEAR(signedVolume(m), 21 * 0.3 * 0.45 * 0.3, 1e-9);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const glm::dvec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  EXPECT_NEAR(lo.z, 0.0, 1e-12);
  EXPECT_NEAR(hi.z, 2.4, 1e-12);
  EXPECT_NEAR(hi.x - lo.x, 2.1, 1e-12);  // arms out: the second-longest axis
  EXPECT_NEAR(hi.y - lo.y, 0.45, 1e-12);
}

TEST(Procedural, TranslateAndScaleKeepFacesOutward) {
  CageMesh m = scene::cube();
  scene::translate(m, {10, 0, -2});
  EXPECT_EQ(m.positions[0], glm::dvec3(9, -1, -3));
  EXPECT_NEAR(signedVolume(m), 8.0, 1e-9);
  scene::scale(m, 0.5);
  EXPECT_EQ(m.positions[0], glm::dvec3(4.5, -0.5, -1.5));
  EXPECT_NEAR(signedVolume(m), 1.0, 1e-9);
  CageMesh mirrored = scene::cube();
  scene::scale(mirrored, {-1, 2, 1});
  EXPECT_EQ(mirrored.positions[1], glm::dvec3(-1, -2, -1));
  EXPECT_EQ(mirrored.faceVertices[0], 0);  // first vertex kept, the rest reversed
  EXPECT_EQ(mirrored.faceVertices[1], 1);
  EXPECT_NEAR(signedVolume(mirrored), 16.0, 1e-9);
  expectClosedManifold(mirrored);
}

}  // namespace
}  // namespace osd_cull
