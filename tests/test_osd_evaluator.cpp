// VkComputeEvaluator on its own: raw compressed-row matrices with double weights against
// a double CPU reference, buffer descriptors with offsets and strides, limit stencils with
// derivatives, Synchronize waiting for evaluations only, and the errors it reports.
#include "osd_cull/error.h"
#include "osd_cull/osd/compute_evaluator.h"
#include "osd_cull/osd/vertex_buffer.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/buffer.h"
#include "support/vk_test_context.h"
#include "test_osd_meshes.h"

#include <gtest/gtest.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <random>
#include <vector>

namespace osd_cull {
namespace {

using osd::BufferDescriptor;
using osd::DeviceContext;
using osd::VkComputeEvaluator;
using osd::VkStencilTable;
using osd::VkVertexBuffer;
using test::VkTest;

// A random sparse matrix in compressed rows with double weights.
struct RandomCsr {
  int columns = 0;
  std::vector<int> sizes, offsets, indices;
  std::vector<double> weights;

  RandomCsr(int rows, int cols, int maxRowSize, unsigned seed) : columns(cols) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> rowSize(1, maxRowSize), column(0, cols - 1);
    std::uniform_real_distribution<double> weight(-1.0, 1.0);
    for (int r = 0; r < rows; ++r) {
      sizes.push_back(rowSize(rng));
      offsets.push_back(static_cast<int>(indices.size()));
      for (int e = 0; e < sizes.back(); ++e) {
        indices.push_back(column(rng));
        weights.push_back(weight(rng));
      }
    }
  }
  int rows() const { return static_cast<int>(sizes.size()); }
};

std::vector<float> randomValues(size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-10.0f, 10.0f);
  std::vector<float> out(count);
  for (float& v : out) v = value(rng);
  return out;
}

TEST_F(VkTest, RawCsrWithDoubleWeightsMatchesADoubleReference) {
  DeviceContext device(context());
  const RandomCsr csr(5000, 700, 30, 7);
  const VkStencilTable table(device, csr.sizes, csr.offsets, csr.indices, csr.weights);
  EXPECT_EQ(table.GetNumStencils(), 5000);
  EXPECT_LE(table.GetNumSourceVertices(), 700);

  const std::vector<float> src = randomValues(3 * 700, 11);
  VkVertexBuffer srcBuffer(device, 3, 700);
  VkVertexBuffer dstBuffer(device, 3, csr.rows());
  srcBuffer.UpdateData(src.data(), 0, 700, &device);
  const BufferDescriptor desc(0, 3, 3);
  // No instance: the static form makes a temporary one, as OpenSubdiv's evaluators do.
  ASSERT_TRUE(VkComputeEvaluator::EvalStencils(&srcBuffer, desc, &dstBuffer, desc, &table, nullptr,
                                               &device));
  VkComputeEvaluator::Synchronize(&device);
  const std::vector<float> gpu = dstBuffer.readback();

  ASSERT_EQ(gpu.size(), 3u * csr.rows());
  for (int r = 0; r < csr.rows(); ++r)
    for (int k = 0; k < 3; ++k) {
      double sum = 0.0, magnitude = 0.0;
      for (int e = csr.offsets[r]; e < csr.offsets[r] + csr.sizes[r]; ++e) {
        const double term = csr.weights[e] * src[3 * csr.indices[e] + k];
        sum += term;
        magnitude += std::abs(term);
      }
      // fp32 weights, products and sums: at most (n + 2) roundings of the magnitudes.
      const double bound = (csr.sizes[r] + 2) * 1.2e-7 * magnitude;
      ASSERT_NEAR(gpu[3 * r + k], sum, bound) << "row " << r << " element " << k;
    }
}

TEST_F(VkTest, DescriptorOffsetsAndStridesPlaceEveryElement) {
  DeviceContext device(context());
  const RandomCsr csr(300, 40, 6, 3);
  const VkStencilTable table(device, csr.sizes, csr.offsets, csr.indices, csr.weights);
  // Source: 5 floats per vertex, xyz at 1..3. Destination: 4 floats per vertex, xyz at
  // 1..3, starting two vertices in.
  const BufferDescriptor srcDesc(1, 3, 5), dstDesc(2 * 4 + 1, 3, 4);
  const std::vector<float> src = randomValues(5 * 40, 5);
  VkVertexBuffer srcBuffer(device, 5, 40);
  VkVertexBuffer dstBuffer(device, 4, 302);
  srcBuffer.UpdateData(src.data(), 0, 40);
  const std::vector<float> sentinel(4 * 302, -7.0f);
  dstBuffer.UpdateData(sentinel.data(), 0, 302);

  std::unique_ptr<VkComputeEvaluator> evaluator(
      VkComputeEvaluator::Create(srcDesc, dstDesc, {}, {}, &device));
  ASSERT_TRUE(evaluator->EvalStencils(&srcBuffer, srcDesc, &dstBuffer, dstDesc, &table));
  evaluator->synchronize();
  const std::vector<float> gpu = dstBuffer.readback();
  for (int v = 0; v < 302; ++v)
    for (int e = 0; e < 4; ++e) {
      const int stencil = v - 2;
      if (stencil < 0 || e == 0) {
        ASSERT_EQ(gpu[4 * v + e], -7.0f) << "vertex " << v << " element " << e << " was written";
        continue;
      }
      double sum = 0.0;
      for (int j = csr.offsets[stencil]; j < csr.offsets[stencil] + csr.sizes[stencil]; ++j)
        sum += csr.weights[j] * src[5 * csr.indices[j] + 1 + (e - 1)];
      ASSERT_NEAR(gpu[4 * v + e], sum, 1e-4) << "vertex " << v << " element " << e;
    }
}

TEST_F(VkTest, LimitStencilsGivePositionsAndDerivatives) {
  DeviceContext device(context());
  auto refiner = makeTopologyRefiner(scene::creasedCube());
  refiner->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(3));
  // Five locations on each of the six faces.
  const std::vector<float> s = {0.1f, 0.5f, 0.9f, 0.0f, 0.33f};
  const std::vector<float> t = {0.2f, 0.5f, 0.7f, 1.0f, 0.01f};
  Far::LimitStencilTableFactory::LocationArrayVec locations;
  for (int face = 0; face < 6; ++face) {
    Far::LimitStencilTableFactory::LocationArray a;
    a.ptexIdx = face;
    a.numLocations = static_cast<int>(s.size());
    a.s = s.data();
    a.t = t.data();
    locations.push_back(a);
  }
  const std::unique_ptr<const Far::LimitStencilTable> limit(
      Far::LimitStencilTableFactory::Create(*refiner, locations));
  ASSERT_EQ(limit->GetNumStencils(), 30);
  std::unique_ptr<VkStencilTable> table(VkStencilTable::Create(limit.get(), &device));
  ASSERT_TRUE(table->HasDerivatives());
  ASSERT_LE(table->GetNumSourceVertices(), 8);

  const std::vector<float> cage = test::packedXyz(scene::creasedCube());
  VkVertexBuffer cageBuffer(device, 3, 8);
  cageBuffer.UpdateData(cage.data(), 0, 8);
  VkVertexBuffer position(device, 3, 30), du(device, 3, 30), dv(device, 3, 30);
  const BufferDescriptor desc(0, 3, 3);
  ASSERT_TRUE(VkComputeEvaluator::EvalStencils(&cageBuffer, desc, &position, desc, &du, desc, &dv,
                                               desc, table.get(), nullptr, &device));
  VkComputeEvaluator::Synchronize(&device);

  struct P {
    float v[3] = {0, 0, 0};
    void Clear() { v[0] = v[1] = v[2] = 0; }
    void AddWithWeight(const P& p, float w) {
      for (int k = 0; k < 3; ++k) v[k] += w * p.v[k];
    }
  };
  std::vector<P> cpuCage(8), cpuPos(30), cpuDu(30), cpuDv(30);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) cpuCage[i].v[k] = cage[3 * i + k];
  limit->UpdateValues(cpuCage.data(), cpuPos.data());
  limit->UpdateDerivs(cpuCage.data(), cpuDu.data(), cpuDv.data());
  const auto flat = [](const std::vector<P>& ps) {
    std::vector<float> out;
    for (const P& p : ps) out.insert(out.end(), {p.v[0], p.v[1], p.v[2]});
    return out;
  };
  const double diagonal = 2.0 * std::sqrt(3.0);
  EXPECT_LE(test::maxAbsDifference(position.readback(), flat(cpuPos)), 1e-5 * diagonal);
  EXPECT_LE(test::maxAbsDifference(du.readback(), flat(cpuDu)), 1e-5 * diagonal);
  EXPECT_LE(test::maxAbsDifference(dv.readback(), flat(cpuDv)), 1e-5 * diagonal);
  // Derivatives are not positions: the outputs really differ.
  EXPECT_GT(test::maxAbsDifference(du.readback(), dv.readback()), 0.1);
}

TEST_F(VkTest, SynchronizeWaitsForEvaluationsButNotForLaterWork) {
  DeviceContext device(context());
  const RandomCsr csr(200, 20, 4, 9);
  const VkStencilTable table(device, csr.sizes, csr.offsets, csr.indices, csr.weights);
  const std::vector<float> src = randomValues(3 * 20, 1);
  VkVertexBuffer srcBuffer(device, 3, 20), dstBuffer(device, 3, 200);
  srcBuffer.UpdateData(src.data(), 0, 20);
  const BufferDescriptor desc(0, 3, 3);
  VkComputeEvaluator::EvalStencils(&srcBuffer, desc, &dstBuffer, desc, &table, nullptr, &device);
  const uint64_t evaluation = device.lastTicket();

  // A later submission that cannot finish until the host sets an event.
  VkEventCreateInfo eventInfo{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
  VkEvent rawEvent = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateEvent(context().device(), &eventInfo, nullptr, &rawEvent), VK_SUCCESS);
  const vulkan::DeviceHandle<VkEvent, vkDestroyEvent> event(context().device(), rawEvent);
  vulkan::Buffer scratch(context(), 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const uint64_t blocked = device.submit([&](osd::Batch& batch) {
    vkCmdWaitEvents(batch.commandBuffer(), 1, &rawEvent, VK_PIPELINE_STAGE_HOST_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, 0, nullptr, 0, nullptr, 0, nullptr);
    vkCmdFillBuffer(batch.commandBuffer(), scratch.handle(), 0, VK_WHOLE_SIZE, 1u);
  });
  ASSERT_GT(blocked, evaluation);

  auto synchronized =
      std::async(std::launch::async, [&] { VkComputeEvaluator::Synchronize(&device); });
  const bool returned =
      synchronized.wait_for(std::chrono::seconds(20)) == std::future_status::ready;
  const bool blockedWasPending = !device.isComplete(blocked);
  vkSetEvent(context().device(), rawEvent);  // release the queue in every case
  synchronized.wait();
  EXPECT_TRUE(returned) << "Synchronize waited for a submission that is not an evaluation";
  EXPECT_TRUE(device.isComplete(evaluation));
  EXPECT_TRUE(blockedWasPending);
  device.waitAll();
  EXPECT_TRUE(device.isComplete(blocked));
}

TEST_F(VkTest, EvaluatorRejectsWhatItCannotDo) {
  DeviceContext device(context());
  const RandomCsr csr(50, 10, 3, 2);
  const VkStencilTable table(device, csr.sizes, csr.offsets, csr.indices, csr.weights);
  VkVertexBuffer src(device, 3, 10), smallDst(device, 3, 49), dst(device, 3, 50);
  const BufferDescriptor desc(0, 3, 3);
  // Destination too small for 50 stencils.
  EXPECT_THROW(
      VkComputeEvaluator::EvalStencils(&src, desc, &smallDst, desc, &table, nullptr, &device),
      Error);
  // Lengths differ.
  EXPECT_THROW(VkComputeEvaluator(device, desc, BufferDescriptor(0, 2, 3)), Error);
  // length > stride.
  EXPECT_THROW(VkComputeEvaluator(device, BufferDescriptor(0, 4, 3), BufferDescriptor(0, 4, 3)),
               Error);
  // Second derivatives.
  EXPECT_THROW(VkComputeEvaluator::Create(desc, desc, desc, desc, desc, {}, {}, &device), Error);
  // Derivatives from a table without derivative weights.
  EXPECT_THROW(VkComputeEvaluator::EvalStencils(&src, desc, &dst, desc, &dst, desc, &dst, desc,
                                                &table, nullptr, &device),
               Error);
  // No DeviceContext.
  EXPECT_THROW(VkComputeEvaluator::EvalStencils(&src, desc, &dst, desc, &table, nullptr, nullptr),
               Error);
  // Rows that point past the entries.
  const std::vector<int> sizes = {2, 2}, offsets = {0, 1}, indices = {0, 1};
  const std::vector<float> weights = {0.5f, 0.5f};
  EXPECT_THROW(VkStencilTable(device, sizes, std::vector<int>{0, 2}, indices, weights), Error);
  EXPECT_NO_THROW(VkStencilTable(device, std::vector<int>{1, 1}, offsets, indices, weights));
  // Updates outside the vertex buffer.
  const std::vector<float> values(30, 1.0f);
  EXPECT_THROW(src.UpdateData(values.data(), 5, 6), Error);
  EXPECT_THROW(VkVertexBuffer::Create(3, 0, &device), Error);
}

}  // namespace
}  // namespace osd_cull
