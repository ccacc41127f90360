// GpuPointUpdate: per-frame cage → control point update on the GPU against the CPU
// (double) product with the same matrix, frame after frame with a moving cage: Far's
// refinement stencils on small cages, and the patch set's own cage → control point matrix
// (osd_cull/patch) on the default demo mesh and BigGuy.
#include "adapters/load_mesh.h"
#include "osd_cull/error.h"
#include "osd_cull/osd/gpu_point_update.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"
#include "test_osd_meshes.h"

#include <gtest/gtest.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <cmath>
#include <memory>
#include <vector>

namespace osd_cull {
namespace {

using osd::DeviceContext;
using osd::GpuPointUpdate;
using test::VkTest;

// A cage → points matrix in compressed rows (double weights).
struct Csr {
  int columns = 0;
  std::vector<int> sizes, offsets, indices;
  std::vector<double> weights;

  // points[r] = sum of weights * cage[indices] over row r, in double.
  std::vector<double> apply(std::span<const glm::dvec3> cage) const {
    std::vector<double> out;
    for (size_t r = 0; r < sizes.size(); ++r) {
      glm::dvec3 sum(0.0);
      for (int e = offsets[r]; e < offsets[r] + sizes[r]; ++e) sum += weights[e] * cage[indices[e]];
      out.insert(out.end(), {sum.x, sum.y, sum.z});
    }
    return out;
  }
};

// Every refined vertex and Gregory end-cap point of a cage at adaptive level 2, as one
// factorized Far stencil table (the matrix Osd::Mesh evaluates), in double.
Csr refinedPointMatrix(const CageMesh& cage) {
  auto refiner = makeTopologyRefiner(cage);
  refiner->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(2));
  Far::StencilTableFactoryReal<double>::Options options;
  options.generateIntermediateLevels = true;
  options.generateOffsets = true;
  std::unique_ptr<const Far::StencilTableReal<double>> stencils(
      Far::StencilTableFactoryReal<double>::Create(*refiner, options));
  Far::PatchTableFactory::Options patchOptions(2);
  patchOptions.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  patchOptions.SetPatchPrecision<double>();
  std::unique_ptr<const Far::PatchTable> patches(
      Far::PatchTableFactory::Create(*refiner, patchOptions));
  if (patches->GetLocalPointStencilTable<double>()) {
    std::unique_ptr<const Far::StencilTableReal<double>> all(
        Far::StencilTableFactoryReal<double>::AppendLocalPointStencilTable(
            *refiner, stencils.get(), patches->GetLocalPointStencilTable<double>()));
    stencils.reset(all.release());
  }
  Csr m;
  m.columns = cage.vertexCount();
  m.sizes = stencils->GetSizes();
  m.offsets = stencils->GetOffsets();
  m.indices = stencils->GetControlIndices();
  m.weights = stencils->GetWeights();
  return m;
}

// Runs three frames of a deforming cage through GpuPointUpdate and compares each with
// the double product.
void checkFrames(vulkan::Context& context, const CageMesh& cage, const Csr& matrix, int stride) {
  DeviceContext device(context);
  GpuPointUpdate update(device, matrix.columns, matrix.sizes, matrix.offsets, matrix.indices,
                        matrix.weights, {stride});
  ASSERT_EQ(update.pointCount(), static_cast<int>(matrix.sizes.size()));
  ASSERT_EQ(update.pointStride(), stride);
  std::vector<float> previous;
  for (int frame = 0; frame < 3; ++frame) {
    std::vector<glm::dvec3> moved = cage.positions;
    for (size_t v = 0; v < moved.size(); ++v)  // a wave through the cage, different per frame
      moved[v] += 0.2 * frame *
                  glm::dvec3(std::sin(v + frame), std::cos(2.0 * v), std::sin(3.0 * v + frame));
    update.update(moved);
    update.wait();
    const std::vector<float> gpu = update.readback();
    const std::vector<double> cpu = matrix.apply(moved);
    ASSERT_EQ(gpu.size(), static_cast<size_t>(stride) * cpu.size() / 3);
    const double tolerance = 1e-5 * test::boxDiagonal(cpu);
    double worst = 0.0;
    for (size_t p = 0; p < cpu.size() / 3; ++p) {
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(gpu[stride * p + k] - cpu[3 * p + k]));
      if (stride == 4) {
        ASSERT_EQ(gpu[4 * p + 3], 1.0f) << "point " << p;
      }
    }
    EXPECT_LE(worst, tolerance) << cage.source << " frame " << frame;
    if (frame > 0) {
      EXPECT_GT(test::maxAbsDifference(gpu, previous), 1e-2)
          << "frame " << frame << " did not move";
    }
    previous = gpu;
  }
}

TEST_F(VkTest, PointUpdateFollowsAMovingCreasedCube) {
  const CageMesh cage = scene::creasedCube();
  checkFrames(context(), cage, refinedPointMatrix(cage), 3);
}

TEST_F(VkTest, PointUpdateWritesVec4PointsWithUnitW) {
  const CageMesh cage = test::openFan();
  checkFrames(context(), cage, refinedPointMatrix(cage), 4);
}

// The patch set's matrix: frame 0 is the cage as loaded (the GPU must reproduce the
// extraction's own points), frames 1-2 move it; each frame is compared with the CPU
// update PatchPointMatrix::update (double).
void checkPatchPoints(vulkan::Context& context, const CageMesh& cage, int level) {
  PatchOptions options;
  options.isolationLevel = level;
  const PatchExtraction ex = extractPatches(cage, options);
  ASSERT_GT(ex.patches.gregoryCount, 0u) << cage.source;
  DeviceContext device(context);
  GpuPointUpdate update(device, ex.matrix);
  ASSERT_EQ(update.pointCount(), static_cast<int>(ex.patches.points.size()));
  const double diagonal = test::boxDiagonal(
      std::span<const double>(&ex.patches.points.front().x, 3 * ex.patches.points.size()));
  std::vector<glm::dvec3> cpu(ex.patches.points.size());
  for (int frame = 0; frame < 3; ++frame) {
    std::vector<glm::dvec3> moved = cage.positions;
    for (size_t v = 0; v < moved.size(); ++v)
      moved[v] +=
          0.01 * diagonal * frame * glm::dvec3(std::sin(0.3 * v + frame), std::cos(0.7 * v), 0.5);
    update.update(moved);
    ex.matrix.update(moved, cpu);
    if (frame == 0) {  // the CPU update of the unmoved cage gives the patch set's points
      double offset = 0.0;
      for (size_t p = 0; p < cpu.size(); ++p)
        offset = std::max(offset, glm::length(cpu[p] - ex.patches.points[p]));
      ASSERT_LE(offset, 1e-12 * diagonal);
    }
    const std::vector<float> gpu = update.readback();
    double worst = 0.0;
    for (size_t p = 0; p < cpu.size(); ++p)
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(gpu[3 * p + k] - cpu[p][k]));
    EXPECT_LE(worst, 1e-5 * diagonal) << cage.source << " level " << level << " frame " << frame;
  }
}

TEST_F(VkTest, PatchPointsOfTheDefaultMeshFollowTheCage) {
  checkPatchPoints(context(), scene::defaultMesh(), 2);
}

TEST_F(VkTest, PatchPointsOfBigGuyFollowTheCage) {
  OSD_CULL_REQUIRE_DATA();
  checkPatchPoints(context(), adapters::loadCage(test::dataDir() / "characters" / "bigguy.obj"), 2);
}

TEST_F(VkTest, PointUpdateRejectsMismatchedInput) {
  DeviceContext device(context());
  const Csr matrix = refinedPointMatrix(scene::creasedCube());
  // The matrix reads vertex 7: a cage of 7 vertices is too small.
  EXPECT_THROW(
      GpuPointUpdate(device, 7, matrix.sizes, matrix.offsets, matrix.indices, matrix.weights),
      Error);
  EXPECT_THROW(
      GpuPointUpdate(device, 8, matrix.sizes, matrix.offsets, matrix.indices, matrix.weights, {5}),
      Error);
  GpuPointUpdate update(device, 8, matrix.sizes, matrix.offsets, matrix.indices, matrix.weights);
  const std::vector<float> tooShort(21, 0.0f);
  EXPECT_THROW(update.update(tooShort), Error);
}

}  // namespace
}  // namespace osd_cull
