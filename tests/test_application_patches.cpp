// Patches from the application's OpenSubdiv objects: the patch set built from its refiner
// and patch table equals the one osd_cull builds itself; control points fed from an
// Osd::Mesh's refined vertex buffer, or from the application's own buffer of cage
// positions at any stride and offset, equal the CPU path; tables osd_cull cannot use are
// named with the option that made them.
#include "osd_cull/error.h"
#include "osd_cull/osd/gpu_point_update.h"
#include "osd_cull/osd/mesh.h"
#include "osd_cull/patch/application_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"
#include "test_osd_meshes.h"

#include <gtest/gtest.h>
#include <opensubdiv/far/patchTableFactory.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace Osd = OpenSubdiv::Osd;
using test::VkTest;

// What an application does: its own refiner, refined adaptively, and a float patch table.
struct AppObjects {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<Far::PatchTable> table;
};

AppObjects appObjects(const CageMesh& cage, Far::PatchTableFactory::Options options) {
  AppObjects app;
  app.refiner = makeTopologyRefiner(cage);
  app.refiner->RefineAdaptive(options.GetRefineAdaptiveOptions());
  app.table.reset(Far::PatchTableFactory::Create(*app.refiner, options));
  return app;
}

Far::PatchTableFactory::Options gregoryOptions() {
  Far::PatchTableFactory::Options options(2);
  options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  options.useInfSharpPatch = true;  // as osd_cull's PatchOptions default
  return options;
}

std::vector<double> flat(std::span<const glm::dvec3> points) {
  std::vector<double> out;
  for (const glm::dvec3& p : points) out.insert(out.end(), {p.x, p.y, p.z});
  return out;
}

void expectSamePatchSet(const CageMesh& cage) {
  const AppObjects app = appObjects(cage, gregoryOptions());
  const ApplicationPatches adopted =
      extractApplicationPatches(*app.refiner, *app.table, cage.positions, cage.source);
  const PatchExtraction ours = extractPatches(cage, PatchOptions{});
  const PatchSet& a = adopted.extraction.patches;
  const PatchSet& b = ours.patches;
  ASSERT_EQ(a.bezierCount, b.bezierCount) << cage.source;
  ASSERT_EQ(a.gregoryCount, b.gregoryCount) << cage.source;
  ASSERT_GT(a.gregoryCount, 0u) << cage.source << ": no Gregory patch to compare";
  for (uint32_t p = 0; p < a.patchCount(); ++p) {
    EXPECT_EQ(a.params[p].field0, b.params[p].field0) << cage.source << " patch " << p;
    EXPECT_EQ(a.params[p].field1, b.params[p].field1) << cage.source << " patch " << p;
    EXPECT_EQ(a.origins[p], b.origins[p]) << cage.source << " patch " << p;
  }
  // The application's local-point stencils are float: equal up to float weights.
  const std::vector<double> pa = flat(a.points), pb = flat(b.points);
  const double diagonal = test::boxDiagonal(pb);
  EXPECT_LE(test::maxAbsDifference(pa, pb), 1e-6 * diagonal) << cage.source;
  // The cage matrix reproduces the points it made.
  std::vector<glm::dvec3> again(a.points.size());
  adopted.extraction.matrix.update(cage.positions, again);
  EXPECT_LE(test::maxAbsDifference(flat(again), pa), 1e-12 * diagonal) << cage.source;
}

TEST(ApplicationPatches, PatchSetFromTheApplicationsRefinerAndTableEqualsOurs) {
  expectSamePatchSet(scene::creasedCube());
  expectSamePatchSet(test::openFan());
}

TEST(ApplicationPatches, UnusableTablesAreNamedWithTheOptionThatMadeThem) {
  const CageMesh cage = scene::creasedCube();
  auto errorOf = [&](const Far::TopologyRefiner& refiner, const Far::PatchTable& table) {
    try {
      extractApplicationPatches(refiner, table, cage.positions, "app");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  Far::PatchTableFactory::Options legacy = gregoryOptions();
  legacy.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_LEGACY_GREGORY);
  AppObjects app = appObjects(cage, legacy);
  EXPECT_NE(errorOf(*app.refiner, *app.table).find("legacy Gregory"), std::string::npos)
      << errorOf(*app.refiner, *app.table);

  Far::PatchTableFactory::Options crease = gregoryOptions();
  crease.useSingleCreasePatch = true;
  app = appObjects(cage, crease);
  EXPECT_NE(errorOf(*app.refiner, *app.table).find("useSingleCreasePatch"), std::string::npos)
      << errorOf(*app.refiner, *app.table);

  auto uniform = makeTopologyRefiner(cage);
  uniform->RefineUniform(Far::TopologyRefiner::UniformOptions(2));
  std::unique_ptr<Far::PatchTable> quads(Far::PatchTableFactory::Create(*uniform));
  EXPECT_NE(errorOf(*uniform, *quads).find("uniformly"), std::string::npos)
      << errorOf(*uniform, *quads);

  const AppObjects other = appObjects(test::openFan(), gregoryOptions());
  const AppObjects mine = appObjects(cage, gregoryOptions());
  EXPECT_NE(errorOf(*mine.refiner, *other.table).find("another refiner"), std::string::npos)
      << errorOf(*mine.refiner, *other.table);
}

Osd::MeshBitset meshBits() {
  Osd::MeshBitset bits;
  bits.set(Osd::MeshAdaptive);
  bits.set(Osd::MeshEndCapGregoryBasis);
  bits.set(Osd::MeshUseInfSharpPatch);
  return bits;
}

// Osd::Mesh refines on the device; osd_cull turns its vertex buffer into control points.
TEST_F(VkTest, ControlPointsFedFromAnOsdMeshEqualTheCpuPath) {
  CageMesh cage = test::openFan();
  osd::DeviceContext device(context());
  osd::VkEvaluatorCache evaluators;
  osd::VkMesh mesh(makeTopologyRefiner(cage).release(), 3, 0, 2, meshBits(), &evaluators, &device);
  const ApplicationPatches patches = extractApplicationPatches(
      *mesh.GetTopologyRefiner(), *mesh.GetFarPatchTable(), cage.positions, cage.source);
  ASSERT_EQ(patches.fromPatchPoints.columnCount(), mesh.GetNumVertices());
  osd::GpuPointUpdate feed(device, patches.fromPatchPoints, {4});
  std::vector<float> previous;
  for (int pose = 0; pose < 2; ++pose) {
    if (pose == 1)
      for (size_t v = 0; v < cage.positions.size(); ++v)
        cage.positions[v] += glm::dvec3(0.2 * std::sin(1.3 * v), 0.1 * std::cos(0.7 * v), 0.15);
    const std::vector<float> xyz = test::packedXyz(cage);
    mesh.UpdateVertexBuffer(xyz.data(), 0, cage.vertexCount());
    mesh.Refine();
    feed.updateFrom(*mesh.GetVertexBuffer());
    mesh.Synchronize();
    const std::vector<float> gpu = feed.readback();
    // The CPU path: the cage matrix in double.
    std::vector<glm::dvec3> cpu(patches.extraction.patches.points.size());
    patches.extraction.matrix.update(cage.positions, cpu);
    std::vector<double> cpuXyzw;
    for (const glm::dvec3& p : cpu) cpuXyzw.insert(cpuXyzw.end(), {p.x, p.y, p.z, 1.0});
    const double diagonal = test::boxDiagonal(flat(cpu));
    ASSERT_GT(diagonal, 1.0);
    EXPECT_LE(test::maxAbsDifference(gpu, cpuXyzw), 1e-5 * diagonal) << "pose " << pose;
    if (pose == 1) {
      EXPECT_GT(test::maxAbsDifference(gpu, previous), 1e-2);
    }
    previous = gpu;
  }
}

// The application keeps cage positions in its own buffer, interleaved with normals.
TEST_F(VkTest, ControlPointsFedFromTheApplicationsOwnBufferWithStrideAndOffset) {
  const CageMesh cage = scene::creasedCube();
  const PatchExtraction extraction = extractPatches(cage, PatchOptions{});
  std::vector<float> interleaved;  // normal (3 floats), position (3 floats) per vertex
  for (const glm::dvec3& p : cage.positions)
    interleaved.insert(interleaved.end(), {0.0f, 1.0f, 0.0f, float(p.x), float(p.y), float(p.z)});
  vulkan::Buffer appBuffer(context(), interleaved.size() * sizeof(float),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  vulkan::upload<float>(context(), appBuffer, interleaved);

  osd::DeviceContext device(context());
  osd::GpuPointUpdate feed(device, extraction.matrix, {3});
  feed.updateFrom({appBuffer.handle(), interleaved.size(), osd::BufferDescriptor(3, 3, 6)});
  feed.wait();
  EXPECT_LE(test::maxAbsDifference(feed.readback(), flat(extraction.patches.points)),
            1e-5 * test::boxDiagonal(flat(extraction.patches.points)));
  // A buffer too small for the matrix is refused before anything is recorded.
  EXPECT_THROW(feed.updateFrom({appBuffer.handle(), 12, osd::BufferDescriptor(3, 3, 6)}), Error);
  EXPECT_THROW(
      feed.updateFrom({appBuffer.handle(), interleaved.size(), osd::BufferDescriptor(0, 4, 6)}),
      Error);
}

}  // namespace
}  // namespace osd_cull
