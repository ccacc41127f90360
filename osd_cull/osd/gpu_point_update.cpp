#include "osd_cull/osd/gpu_point_update.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/point_matrix.h"
#include "osd_cull/vk/commands.h"

#include <bit>
#include <string>

namespace osd_cull::osd {
namespace {

int checkedStride(int stride) {
  if (stride != 3 && stride != 4)
    throw Error("GpuPointUpdate: pointStride must be 3 or 4, got " + std::to_string(stride));
  return stride;
}

int checkedCount(int count, const char* what) {
  if (count <= 0) throw Error(std::string("GpuPointUpdate: needs at least one ") + what);
  return count;
}

}  // namespace

GpuPointUpdate::GpuPointUpdate(DeviceContext& deviceContext, int cageVertexCount,
                               std::span<const int> sizes, std::span<const int> offsets,
                               std::span<const int> indices, std::span<const double> weights,
                               const Options& options)
    : deviceContext_(deviceContext),
      matrix_(deviceContext, sizes, offsets, indices, weights),
      cage_(deviceContext, 3, checkedCount(cageVertexCount, "cage vertex")),
      points_(deviceContext, checkedStride(options.pointStride),
              checkedCount(static_cast<int>(sizes.size()), "control point")),
      evaluator_(deviceContext, BufferDescriptor(0, 3, 3),
                 BufferDescriptor(0, 3, options.pointStride)) {
  if (matrix_.GetNumSourceVertices() > cageVertexCount)
    throw Error("GpuPointUpdate: the matrix reads cage vertex " +
                std::to_string(matrix_.GetNumSourceVertices() - 1) + " of only " +
                std::to_string(cageVertexCount));
  if (options.pointStride == 4) {
    // w = 1 once; the kernel writes xyz only.
    const vulkan::Buffer& points = points_.buffer();
    points_.markUsed(deviceContext_.submit([&](Batch& batch) {
      vulkan::memoryBarrier(batch.commandBuffer(), vulkan::scope::kAll,
                            vulkan::scope::kTransferWrite);
      vkCmdFillBuffer(batch.commandBuffer(), points.handle(), 0, VK_WHOLE_SIZE,
                      std::bit_cast<uint32_t>(1.0f));
      vulkan::memoryBarrier(batch.commandBuffer(), vulkan::scope::kTransferWrite,
                            vulkan::scope::kAll);
    }));
  }
}

GpuPointUpdate::GpuPointUpdate(DeviceContext& deviceContext, const PatchPointMatrix& matrix,
                               const Options& options)
    : GpuPointUpdate(deviceContext, matrix.columnCount(), matrix.sizes(), matrix.offsets(),
                     matrix.indices(), matrix.weights(), options) {}

uint64_t GpuPointUpdate::update(std::span<const float> cageXyz) {
  if (cageXyz.size() != 3 * static_cast<size_t>(cageVertexCount()))
    throw Error("GpuPointUpdate::update: expected " + std::to_string(3 * cageVertexCount()) +
                " floats (x, y, z of " + std::to_string(cageVertexCount()) +
                " cage vertices), got " + std::to_string(cageXyz.size()));
  const EvaluatorBinding src{cage_.BindVBO(), 3 * static_cast<size_t>(cageVertexCount()),
                             BufferDescriptor(0, 3, 3)};
  const EvaluatorBinding dst{points_.BindVBO(),
                             static_cast<size_t>(pointStride()) * static_cast<size_t>(pointCount()),
                             BufferDescriptor(0, 3, pointStride())};
  lastTicket_ = deviceContext_.submit([&](Batch& batch) {
    cage_.recordUpdate(batch, cageXyz.data(), 0, cageVertexCount());
    evaluator_.record(batch, matrix_, src, dst, {}, {}, 0, matrix_.GetNumStencils());
  });
  cage_.markUsed(lastTicket_);
  points_.markUsed(lastTicket_);
  return lastTicket_;
}

uint64_t GpuPointUpdate::update(std::span<const glm::dvec3> cage) {
  scratch_.clear();
  for (const glm::dvec3& p : cage)
    scratch_.insert(scratch_.end(),
                    {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  return update(scratch_);
}

uint64_t GpuPointUpdate::updateFrom(const EvaluatorBinding& source) {
  if (source.desc.length != 3)
    throw Error(
        "GpuPointUpdate::updateFrom: positions must be 3 floats per vertex, the source "
        "descriptor says " +
        std::to_string(source.desc.length));
  const EvaluatorBinding dst{points_.BindVBO(),
                             static_cast<size_t>(pointStride()) * static_cast<size_t>(pointCount()),
                             BufferDescriptor(0, 3, pointStride())};
  lastTicket_ = deviceContext_.submit([&](Batch& batch) {
    evaluator_.record(batch, matrix_, source, dst, {}, {}, 0, matrix_.GetNumStencils());
  });
  points_.markUsed(lastTicket_);
  return lastTicket_;
}

uint64_t GpuPointUpdate::updateFrom(const VkVertexBuffer& source, int firstElement) {
  if (firstElement < 0 || firstElement + 3 > source.GetNumElements())
    throw Error("GpuPointUpdate::updateFrom: positions at element " + std::to_string(firstElement) +
                " do not fit vertices of " + std::to_string(source.GetNumElements()) + " floats");
  const uint64_t ticket = updateFrom(
      {source.BindVBO(),
       static_cast<size_t>(source.GetNumVertices()) * static_cast<size_t>(source.GetNumElements()),
       BufferDescriptor(firstElement, 3, source.GetNumElements())});
  source.markUsed(ticket);
  return ticket;
}

void GpuPointUpdate::wait() const { deviceContext_.wait(lastTicket_); }

}  // namespace osd_cull::osd
