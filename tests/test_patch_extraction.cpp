// Patch extraction on cages built in code: counts by origin, layout, options, the matrix,
// and the errors for what is not extracted.
#include "osd_cull/error.h"
#include "test_patch_support.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace osd_cull {
namespace {

using test::compareWithReference;
using test::OsdReference;

// Extracts, compares with OpenSubdiv's evaluation and returns the extraction.
PatchExtraction extractAndCompare(const CageMesh& cage, const PatchOptions& options,
                                  double relTolerance = 1e-9) {
  PatchExtraction ex = extractPatches(cage, options);
  const OsdReference ref(cage, options);
  const double diag = test::boundingDiagonal(cage.positions);
  const test::Deviation d = compareWithReference(ex.patches, ref, 7);
  EXPECT_EQ(d.unmatched, 0u) << cage.source;
  EXPECT_GT(d.samples, 0u) << cage.source;
  EXPECT_LE(d.position, relTolerance * diag) << cage.source << " worst at " << d.worst;
  EXPECT_LE(d.derivative, relTolerance * diag) << cage.source << " worst at " << d.worst;
  return ex;
}

TEST(PatchExtraction, TorusGivesOnlyRegularBezierPatches) {
  const PatchExtraction ex = extractAndCompare(scene::torus(8, 6, 2.0, 0.7), {});
  EXPECT_EQ(ex.patches.bezierCount, 48u);
  EXPECT_EQ(ex.patches.gregoryCount, 0u);
  EXPECT_EQ(ex.stats.regular, 48u);
  EXPECT_EQ(ex.patches.points.size(), 48u * kBezierPoints);
  EXPECT_EQ(ex.matrix.rowCount(), 48 * 16);
  EXPECT_EQ(ex.matrix.columnCount(), 48);
}

TEST(PatchExtraction, CubeAtLevelTwoHasGregoryPatchesAroundEachCorner) {
  const PatchExtraction ex = extractAndCompare(scene::cube(), {});
  // Each face: 16 sub-faces at level 2, of which the 4 at the face corners touch a valence-3
  // vertex; 12 regular patches per face.
  EXPECT_EQ(ex.stats.regular, 72u);
  EXPECT_EQ(ex.stats.gregory, 24u);
  EXPECT_EQ(ex.patches.bezierCount, 72u);
  EXPECT_EQ(ex.patches.gregoryCount, 24u);
  EXPECT_EQ(ex.patches.points.size(), 72u * 16 + 24u * 20);
  EXPECT_EQ(ex.stats.controlPoints, ex.patches.points.size());
  EXPECT_GT(ex.stats.localPoints, 0);
  for (uint32_t p = 0; p < ex.patches.patchCount(); ++p)
    EXPECT_EQ(ex.patches.origins[p] == PatchOrigin::Gregory, p >= ex.patches.bezierCount) << p;
}

TEST(PatchExtraction, BSplineEndCapsBecomeBezierPatches) {
  PatchOptions options;
  options.endCaps = EndCap::BSplineBasis;
  const PatchExtraction ex = extractAndCompare(scene::cube(), options);
  EXPECT_EQ(ex.patches.gregoryCount, 0u);
  EXPECT_EQ(ex.stats.regular, 72u);
  EXPECT_EQ(ex.stats.bsplineEndCaps, 24u);
  EXPECT_EQ(ex.patches.bezierCount, 96u);
}

TEST(PatchExtraction, LevelZeroCubeIsSixGregoryPatches) {
  PatchOptions options;
  options.isolationLevel = 0;
  const PatchExtraction ex = extractAndCompare(scene::cube(), options);
  EXPECT_EQ(ex.patches.bezierCount, 0u);
  EXPECT_EQ(ex.patches.gregoryCount, 6u);
}

TEST(PatchExtraction, HigherLevelsIsolateFurther) {
  for (int level = 1; level <= 4; ++level) {
    PatchOptions options;
    options.isolationLevel = level;
    const PatchExtraction ex = extractAndCompare(scene::cube(), options);
    // Each level splits the sub-face at each of the 24 face corners into one new corner
    // sub-face (Gregory) and three regular patches.
    EXPECT_EQ(ex.stats.gregory, 24u) << level;
    EXPECT_EQ(ex.stats.regular, 72u * static_cast<uint32_t>(level - 1)) << level;
  }
}

TEST(PatchExtraction, OpenGridHasBoundaryAndCornerPatches) {
  CageMesh grid = test::gridCage(4);
  grid.boundary = BoundaryInterpolation::EdgeAndCorner;
  const PatchExtraction ex = extractAndCompare(grid, {});
  EXPECT_EQ(ex.stats.gregory, 0u);
  EXPECT_EQ(ex.stats.regular, 4u);
  EXPECT_EQ(ex.stats.boundary, 8u);
  EXPECT_EQ(ex.stats.corner, 4u);
}

TEST(PatchExtraction, PolesOfAnyValenceMatchOpenSubdiv) {
  for (int valence : {3, 5, 6, 8, 16, 64}) {
    SCOPED_TRACE("valence " + std::to_string(valence));
    const PatchExtraction ex = extractAndCompare(test::poleCage(valence), {});
    EXPECT_GT(ex.stats.gregory, 0u);
    EXPECT_GT(ex.stats.boundary + ex.stats.corner, 0u);
  }
}

TEST(PatchExtraction, CreasesCornersAndHolesMatchOpenSubdiv) {
  CageMesh cube = scene::cube();
  cube.creases = {{0, 1, 2.5f}, {1, 2, 10.0f}, {2, 3, 0.5f}, {4, 5, 10.0f}, {5, 6, 10.0f}};
  cube.corners = {{6, 10.0f}, {0, 1.5f}};
  cube.holes = {1};
  for (bool infSharp : {true, false})
    for (EndCap endCaps : {EndCap::GregoryBasis, EndCap::BSplineBasis}) {
      PatchOptions options;
      options.infSharpPatches = infSharp;
      options.endCaps = endCaps;
      options.isolationLevel = 3;
      const PatchExtraction ex = extractAndCompare(cube, options);
      EXPECT_GT(ex.patches.patchCount(), 0u);
      for (const Far::PatchParam& param : ex.patches.params)
        EXPECT_NE(param.GetFaceId(), 1);  // the hole
    }
}

TEST(PatchExtraction, SecondaryLevelStopsSmoothIsolationEarlier) {
  PatchOptions deep;
  deep.isolationLevel = 4;
  PatchOptions shallow = deep;
  shallow.secondaryLevel = 1;
  const PatchExtraction a = extractAndCompare(test::poleCage(5), deep);
  const PatchExtraction b = extractAndCompare(test::poleCage(5), shallow);
  EXPECT_LT(b.patches.patchCount(), a.patches.patchCount());
}

TEST(PatchMatrix, RowsSumToOne) {
  const PatchExtraction ex = extractPatches(test::poleCage(7), {});
  EXPECT_LE(test::maxRowSumError(ex.matrix), 1e-12);
  EXPECT_EQ(ex.matrix.nonZeroCount(), ex.matrix.weights().size());
  for (double w : ex.matrix.weights()) EXPECT_NE(w, 0.0);
}

TEST(PatchMatrix, OffsetsAndSizesDescribeTheRows) {
  const PatchExtraction ex = extractPatches(scene::cube(), {});
  const PatchPointMatrix& m = ex.matrix;
  ASSERT_EQ(m.sizes().size(), m.offsets().size());
  int offset = 0;
  for (size_t r = 0; r < m.sizes().size(); ++r) {
    EXPECT_EQ(m.offsets()[r], offset);
    for (int k = 1; k < m.sizes()[r]; ++k)  // columns sorted within a row
      EXPECT_LT(m.indices()[static_cast<size_t>(offset + k - 1)],
                m.indices()[static_cast<size_t>(offset + k)]);
    offset += m.sizes()[r];
  }
  EXPECT_EQ(static_cast<size_t>(offset), m.nonZeroCount());
}

TEST(PatchMatrix, UpdateAfterMovingTheCageMatchesOpenSubdiv) {
  CageMesh cage = test::poleCage(6);
  cage.creases = {{1, 2, 10.0f}};
  const PatchOptions options;
  const PatchExtraction ex = extractPatches(cage, options);
  OsdReference ref(cage, options);

  const std::vector<glm::dvec3> moved = test::jitter(cage.positions, 0.2, 3);
  PatchSet set = ex.patches;
  ex.matrix.update(moved, set.points);
  ref.setCage(moved);
  const test::Deviation d = compareWithReference(set, ref, 11);
  EXPECT_EQ(d.unmatched, 0u);
  EXPECT_LE(d.position, 1e-9);
  EXPECT_LE(d.derivative, 1e-9);

  // And the update equals a fresh extraction of the moved cage.
  CageMesh movedCage = cage;
  movedCage.positions = moved;
  const PatchExtraction fresh = extractPatches(movedCage, options);
  ASSERT_EQ(fresh.patches.points.size(), set.points.size());
  for (size_t i = 0; i < set.points.size(); ++i)
    EXPECT_LE(glm::length(fresh.patches.points[i] - set.points[i]), 1e-12) << i;
}

TEST(PatchMatrix, FloatUpdateMatchesDoubleUpdate) {
  const CageMesh cage = test::poleCage(5);
  const PatchExtraction ex = extractPatches(cage, {});
  std::vector<float> cageXyz;
  for (const glm::dvec3& p : cage.positions)
    cageXyz.insert(cageXyz.end(), {float(p.x), float(p.y), float(p.z)});
  std::vector<float> pointsXyz(3 * ex.patches.points.size());
  ex.matrix.update(cageXyz, pointsXyz);
  for (size_t i = 0; i < ex.patches.points.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(pointsXyz[3 * i + static_cast<size_t>(c)], ex.patches.points[i][c], 1e-6) << i;
}

TEST(PatchMatrix, FarStencilTableCopiesGiveTheSamePoints) {
  const CageMesh cage = test::poleCage(5);
  const PatchExtraction ex = extractPatches(cage, {});
  std::vector<test::RefPoint> src(cage.positions.size()), dst(ex.patches.points.size());
  for (size_t i = 0; i < src.size(); ++i) src[i].p = cage.positions[i];

  const auto exact = ex.matrix.toFarStencilTableDouble();
  ASSERT_EQ(exact->GetNumStencils(), ex.matrix.rowCount());
  ASSERT_EQ(exact->GetNumControlVertices(), ex.matrix.columnCount());
  exact->UpdateValues(src.data(), dst.data());
  for (size_t i = 0; i < dst.size(); ++i) EXPECT_EQ(dst[i].p, ex.patches.points[i]) << i;

  const auto single = ex.matrix.toFarStencilTable();
  ASSERT_EQ(single->GetNumStencils(), ex.matrix.rowCount());
  struct FloatPoint {
    float x = 0, y = 0, z = 0;
    void Clear(void* = nullptr) { x = y = z = 0; }
    void AddWithWeight(const test::RefPoint& s, float w) {
      x += w * float(s.p.x);
      y += w * float(s.p.y);
      z += w * float(s.p.z);
    }
  };
  std::vector<FloatPoint> fdst(ex.patches.points.size());
  single->UpdateValues(src.data(), fdst.data());
  for (size_t i = 0; i < fdst.size(); ++i)
    EXPECT_NEAR(fdst[i].y, ex.patches.points[i].y, 1e-5) << i;
}

TEST(PatchMatrix, EndCapRowsEqualOpenSubdivsAppendedLocalPointStencils) {
  // Our composition of local-point stencils with refinement stencils must give what
  // Far::StencilTableFactory::AppendLocalPointStencilTable gives, row for row.
  const CageMesh cage = test::poleCage(7);
  const PatchExtraction ex = extractPatches(cage, {});
  auto refiner = makeTopologyRefiner(cage);
  const AdaptivePatches ap = buildAdaptivePatches(*refiner, {});
  ASSERT_NE(ap.localPointStencils, nullptr);
  std::unique_ptr<const Far::StencilTableReal<double>> appended(
      Far::StencilTableFactoryReal<double>::AppendLocalPointStencilTable(
          *refiner, ap.refinedStencils.get(), ap.localPointStencils, true));
  ASSERT_TRUE(appended);
  const Far::PatchTable& table = *ap.patchTable;
  size_t row = ex.patches.bezierCount * kBezierPoints;
  int compared = 0;
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    if (table.GetPatchArrayDescriptor(a).GetType() != Far::PatchDescriptor::GREGORY_BASIS) continue;
    for (int p = 0; p < table.GetNumPatches(a); ++p) {
      const Far::ConstIndexArray cvs = table.GetPatchVertices(a, p);
      for (int k = 0; k < cvs.size(); ++k, ++row) {
        const auto stencil = appended->GetStencil(cvs[k]);
        std::vector<double> expected(cage.positions.size(), 0.0), ours(cage.positions.size(), 0.0);
        for (int e = 0; e < stencil.GetSize(); ++e)
          expected[static_cast<size_t>(stencil.GetVertexIndices()[e])] += stencil.GetWeights()[e];
        const int begin = ex.matrix.offsets()[row];
        for (int e = begin; e < begin + ex.matrix.sizes()[row]; ++e)
          ours[static_cast<size_t>(ex.matrix.indices()[static_cast<size_t>(e)])] =
              ex.matrix.weights()[static_cast<size_t>(e)];
        for (size_t v = 0; v < ours.size(); ++v)
          ASSERT_NEAR(ours[v], expected[v], 1e-14) << "row " << row << " vertex " << v;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, static_cast<int>(ex.patches.gregoryCount * kGregoryPoints));
}

TEST(PatchMatrix, UpdateRejectsWrongSizes) {
  const PatchExtraction ex = extractPatches(scene::cube(), {});
  std::vector<glm::dvec3> cage(7), points(ex.patches.points.size());
  EXPECT_THROW(ex.matrix.update(cage, points), Error);
  cage.resize(8);
  points.pop_back();
  EXPECT_THROW(ex.matrix.update(cage, points), Error);
  EXPECT_THROW(PatchPointMatrix(3, {2}, {0, 3}, {0.5, 0.5}), Error);  // column 3 of 3
  EXPECT_THROW(PatchPointMatrix(3, {3}, {0, 1}, {0.5, 0.5}), Error);  // sizes disagree
}

// Without the matrix (PatchOptions::pointMatrix off, for static meshes) the points are
// refined directly: the same points up to rounding, the same params and origins, no matrix
// and no refinement stencils.
TEST(PatchExtraction, PointsWithoutTheMatrixEqualThePointsOfTheMatrix) {
  for (const CageMesh& cage : {scene::cube(), scene::creasedCube(), scene::poleSphere(5),
                               scene::defaultMesh(), scene::torus(7, 5, 2.0, 0.7)}) {
    for (const EndCap endCaps : {EndCap::GregoryBasis, EndCap::BSplineBasis}) {
      PatchOptions options;
      options.endCaps = endCaps;
      const PatchExtraction full = extractPatches(cage, options);
      options.pointMatrix = false;
      const PatchExtraction direct = extractPatches(cage, options);
      EXPECT_EQ(direct.matrix.rowCount(), 0) << cage.source;
      EXPECT_EQ(direct.stats.stencilMs, 0.0) << cage.source;
      ASSERT_EQ(direct.patches.bezierCount, full.patches.bezierCount) << cage.source;
      ASSERT_EQ(direct.patches.gregoryCount, full.patches.gregoryCount) << cage.source;
      ASSERT_EQ(direct.patches.points.size(), full.patches.points.size()) << cage.source;
      const double tolerance = 1e-13 * test::boundingDiagonal(cage.positions);
      for (std::size_t i = 0; i < full.patches.points.size(); ++i)
        ASSERT_LE(glm::length(direct.patches.points[i] - full.patches.points[i]), tolerance)
            << cage.source << " point " << i;
      for (uint32_t p = 0; p < full.patches.patchCount(); ++p) {
        EXPECT_EQ(direct.patches.params[p].field0, full.patches.params[p].field0);
        EXPECT_EQ(direct.patches.params[p].field1, full.patches.params[p].field1);
        EXPECT_EQ(direct.patches.origins[p], full.patches.origins[p]);
      }
    }
  }
}

TEST(PatchExtractionErrors, LoopAndBilinearAreRefusedWithAClearMessage) {
  CageMesh loop;
  loop.source = "built-in:tetra";
  loop.scheme = Scheme::Loop;
  loop.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  loop.faceSizes = {3, 3, 3, 3};
  loop.faceVertices = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
  try {
    extractPatches(loop, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Loop patches are not extracted yet"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("built-in:tetra"), std::string::npos) << e.what();
  }
  CageMesh bilinear = scene::cube();
  bilinear.scheme = Scheme::Bilinear;
  try {
    extractPatches(bilinear, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bilinear patches are not extracted yet"),
              std::string::npos)
        << e.what();
  }
  // Also through the refiner entry point.
  auto refiner = makeTopologyRefiner(loop);
  EXPECT_THROW(extractPatches(*refiner, loop.positions, {}), Error);
}

TEST(PatchExtractionErrors, BadOptionsAndInputsAreRefused) {
  PatchOptions options;
  options.isolationLevel = 11;
  EXPECT_THROW(extractPatches(scene::cube(), options), Error);
  options.isolationLevel = -1;
  EXPECT_THROW(extractPatches(scene::cube(), options), Error);
  options.isolationLevel = 2;
  options.secondaryLevel = 3;
  EXPECT_THROW(extractPatches(scene::cube(), options), Error);

  // Level 0 cannot make patches for non-quad faces.
  CageMesh pyramid;
  pyramid.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
  pyramid.faceSizes = {4, 3, 3, 3, 3};
  pyramid.faceVertices = {0, 3, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  PatchOptions level0;
  level0.isolationLevel = 0;
  EXPECT_THROW(extractPatches(pyramid, level0), Error);
  EXPECT_NO_THROW(extractPatches(pyramid, {}));

  // A refiner that was refined already, and positions that do not fit the cage.
  const CageMesh cube = scene::cube();
  auto refiner = makeTopologyRefiner(cube);
  EXPECT_THROW(extractPatches(*refiner, std::span<const glm::dvec3>(cube.positions).first(7), {}),
               Error);
  extractPatches(*refiner, cube.positions, {});
  EXPECT_THROW(extractPatches(*refiner, cube.positions, {}), Error);
}

}  // namespace
}  // namespace osd_cull
