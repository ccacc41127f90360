// Osd::Mesh with the Vulkan backend (VkVertexBuffer, VkStencilTable, VkComputeEvaluator,
// VkPatchTable, DeviceContext) against OpenSubdiv's CPU refinement: every refined vertex
// and every local (Gregory end-cap) point, before and after the cage moves; and the patch
// table buffers against Far's arrays, word for word.
#include "osd_cull/osd/mesh.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"
#include "test_osd_meshes.h"

#include <gtest/gtest.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace osd_cull {
namespace {

namespace Osd = OpenSubdiv::Osd;
using osd::DeviceContext;
using osd::VkEvaluatorCache;
using osd::VkMesh;
using test::VkTest;

// A vertex for OpenSubdiv's CPU interpolation, in double.
struct Point {
  double x = 0, y = 0, z = 0;
  void Clear() { x = y = z = 0; }
  void AddWithWeight(const Point& p, float w) {
    x += w * p.x;
    y += w * p.y;
    z += w * p.z;
  }
};

// The CPU reference of what Osd::Mesh's vertex buffer holds after Refine(): the cage,
// every vertex of refinement levels 1..N (Far::PrimvarRefiner, no stencils), then the
// local points of the patch table (Far::PatchTable::ComputeLocalPointValues).
std::vector<double> cpuRefinedPoints(const Far::TopologyRefiner& refiner,
                                     const Far::PatchTable& patches, std::span<const float> cage) {
  std::vector<Point> points(static_cast<size_t>(refiner.GetNumVerticesTotal()) +
                            static_cast<size_t>(patches.GetNumLocalPoints()));
  for (size_t v = 0; v < cage.size() / 3; ++v)
    points[v] = {cage[3 * v], cage[3 * v + 1], cage[3 * v + 2]};
  Far::PrimvarRefiner primvar(refiner);
  Point* src = points.data();
  for (int level = 1; level <= refiner.GetMaxLevel(); ++level) {
    Point* dst = src + refiner.GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  if (patches.GetNumLocalPoints() > 0)
    patches.ComputeLocalPointValues(points.data(), points.data() + refiner.GetNumVerticesTotal());
  std::vector<double> xyz;
  for (const Point& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return xyz;
}

Osd::MeshBitset adaptiveGregoryBits() {
  Osd::MeshBitset bits;
  bits.set(Osd::MeshAdaptive);
  bits.set(Osd::MeshEndCapGregoryBasis);
  return bits;
}

// Refines `cage` at adaptive level 2 through VkMesh and compares with the CPU reference;
// then moves the cage and compares again.
void checkMeshAgainstCpu(vulkan::Context& context, const CageMesh& cage) {
  DeviceContext device(context);
  VkEvaluatorCache evaluators;
  VkMesh mesh(makeTopologyRefiner(cage).release(), 3, 0, 2, adaptiveGregoryBits(), &evaluators,
              &device);
  const Far::TopologyRefiner& refiner = *mesh.GetTopologyRefiner();
  const Far::PatchTable& farPatches = *mesh.GetFarPatchTable();
  ASSERT_EQ(refiner.GetMaxLevel(), 2) << cage.source;
  ASSERT_GT(farPatches.GetNumLocalPoints(), 0) << cage.source << ": no Gregory points to check";
  ASSERT_EQ(mesh.GetNumVertices(), refiner.GetNumVerticesTotal() + farPatches.GetNumLocalPoints());

  std::vector<float> xyz = test::packedXyz(cage);
  const int cageVertices = cage.vertexCount();
  std::vector<float> previous;
  for (int pose = 0; pose < 2; ++pose) {
    if (pose == 1)  // a non-rigid move: every vertex gets its own offset
      for (size_t i = 0; i < xyz.size(); ++i)
        xyz[i] += 0.25f * std::sin(1.7f * static_cast<float>(i));
    mesh.UpdateVertexBuffer(xyz.data(), 0, cageVertices);
    mesh.Refine();
    mesh.Synchronize();
    const std::vector<float> gpu = mesh.GetVertexBuffer()->readback();
    const std::vector<double> cpu = cpuRefinedPoints(refiner, farPatches, xyz);
    ASSERT_EQ(gpu.size(), cpu.size()) << cage.source;
    const double diagonal = test::boxDiagonal(cpu);
    ASSERT_GT(diagonal, 1.0);
    EXPECT_LE(test::maxAbsDifference(gpu, cpu), 1e-5 * diagonal) << cage.source << " pose " << pose;
    if (pose == 1) {  // the second Refine really recomputed the points
      EXPECT_GT(test::maxAbsDifference(gpu, previous), 1e-2) << cage.source;
    }
    previous = gpu;
    EXPECT_EQ(mesh.BindVertexBuffer(), mesh.GetVertexBuffer()->BindVBO(&device));
  }
}

TEST_F(VkTest, OsdMeshRefinesACreasedCubeLikeTheCpu) {
  checkMeshAgainstCpu(context(), scene::creasedCube());
}

TEST_F(VkTest, OsdMeshRefinesAnOpenCageWithPolesLikeTheCpu) {
  checkMeshAgainstCpu(context(), test::openFan());
}

TEST_F(VkTest, OsdMeshKeepsOneEvaluatorPerBufferLayout) {
  DeviceContext device(context());
  VkEvaluatorCache evaluators;
  VkMesh mesh(makeTopologyRefiner(scene::creasedCube()).release(), 3, 0, 2, adaptiveGregoryBits(),
              &evaluators, &device);
  const std::vector<float> xyz = test::packedXyz(scene::creasedCube());
  mesh.UpdateVertexBuffer(xyz.data(), 0, 8);
  mesh.Refine();
  mesh.Refine();
  mesh.Synchronize();
  const osd::VkComputeEvaluator* first = evaluators.GetEvaluator(
      Osd::BufferDescriptor(0, 3, 3), Osd::BufferDescriptor(24, 3, 3), &device);
  // Same local offset, length and stride: the cache answers with the same instance.
  EXPECT_EQ(first, evaluators.GetEvaluator(Osd::BufferDescriptor(0, 3, 3),
                                           Osd::BufferDescriptor(24, 3, 3), &device));
  EXPECT_EQ(first->length(), 3);
  EXPECT_FALSE(first->hasDerivatives());
  EXPECT_TRUE(device.isComplete(device.lastTicket()));
}

template <class T>
std::vector<T> readArray(vulkan::Context& context, const vulkan::Buffer& buffer, size_t count) {
  const std::vector<std::byte> bytes = vulkan::readbackBytes(context, buffer, 0, count * sizeof(T));
  std::vector<T> out(count);
  std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

TEST_F(VkTest, PatchTableBuffersEqualFarArrays) {
  DeviceContext device(context());
  VkEvaluatorCache evaluators;
  VkMesh mesh(makeTopologyRefiner(test::openFan()).release(), 3, 0, 2, adaptiveGregoryBits(),
              &evaluators, &device);
  const Far::PatchTable& far = *mesh.GetFarPatchTable();
  const osd::VkPatchTable& table = *mesh.GetPatchTable();

  const Osd::PatchArrayVector& arrays = table.GetPatchArrays();
  ASSERT_EQ(arrays.size(), static_cast<size_t>(far.GetNumPatchArrays()));
  std::vector<int> farIndices;
  int patchBase = 0;
  for (int a = 0; a < far.GetNumPatchArrays(); ++a) {
    EXPECT_EQ(arrays[a].GetDescriptor(), far.GetPatchArrayDescriptor(a));
    EXPECT_EQ(arrays[a].GetNumPatches(), far.GetNumPatches(a));
    EXPECT_EQ(arrays[a].GetIndexBase(), static_cast<int>(farIndices.size()));
    EXPECT_EQ(arrays[a].GetPrimitiveIdBase(), patchBase);
    const Far::ConstIndexArray cvs = far.GetPatchArrayVertices(a);
    farIndices.insert(farIndices.end(), cvs.begin(), cvs.end());
    patchBase += far.GetNumPatches(a);
  }
  ASSERT_EQ(patchBase, far.GetNumPatchesTotal());
  ASSERT_EQ(table.GetPatchIndexSize(), farIndices.size());
  EXPECT_EQ(readArray<int>(context(), table.patchIndexBuffer(), farIndices.size()), farIndices);

  ASSERT_EQ(table.GetPatchParamSize(), static_cast<size_t>(far.GetNumPatchesTotal()));
  const auto params =
      readArray<Osd::PatchParam>(context(), table.patchParamBuffer(), table.GetPatchParamSize());
  const Far::PatchParamTable& farParams = far.GetPatchParamTable();
  for (size_t p = 0; p < params.size(); ++p) {
    EXPECT_EQ(params[p].field0, farParams[p].field0) << "patch " << p;
    EXPECT_EQ(params[p].field1, farParams[p].field1) << "patch " << p;
    const int sharpnessIndex =
        p < far.GetSharpnessIndexTable().size() ? far.GetSharpnessIndexTable()[p] : -1;
    const float sharpness = sharpnessIndex >= 0 ? far.GetSharpnessValues()[sharpnessIndex] : 0.0f;
    EXPECT_EQ(params[p].sharpness, sharpness) << "patch " << p;
  }
  EXPECT_NE(table.GetPatchIndexBuffer(), VK_NULL_HANDLE);
  EXPECT_NE(table.GetPatchParamBuffer(), VK_NULL_HANDLE);
  EXPECT_EQ(table.GetNumFVarChannels(), 0);
}

}  // namespace
}  // namespace osd_cull
