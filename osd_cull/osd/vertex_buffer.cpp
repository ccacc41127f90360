#include "osd_cull/osd/vertex_buffer.h"

#include "osd_cull/error.h"
#include "osd_cull/osd/storage.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/transfer.h"

#include <cstring>
#include <memory>
#include <string>

namespace osd_cull::osd {

VkVertexBuffer* VkVertexBuffer::Create(int numElements, int numVertices,
                                       DeviceContext* deviceContext) {
  if (!deviceContext) throw Error("VkVertexBuffer::Create: the DeviceContext is null");
  // Osd::Mesh deletes what Create returns: ownership leaves as a raw pointer by contract.
  return std::make_unique<VkVertexBuffer>(*deviceContext, numElements, numVertices).release();
}

VkVertexBuffer::VkVertexBuffer(DeviceContext& deviceContext, int numElements, int numVertices)
    : deviceContext_(deviceContext), numElements_(numElements), numVertices_(numVertices) {
  if (numElements <= 0 || numVertices <= 0)
    throw Error("VkVertexBuffer: needs positive element and vertex counts, got " +
                std::to_string(numElements) + " elements x " + std::to_string(numVertices) +
                " vertices");
  const VkDeviceSize bytes = VkDeviceSize{sizeof(float)} * static_cast<VkDeviceSize>(numElements) *
                             static_cast<VkDeviceSize>(numVertices);
  requireStorageRange(deviceContext.context(), bytes, "VkVertexBuffer");
  buffer_ = vulkan::Buffer(deviceContext.context(), bytes,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
}

VkVertexBuffer::~VkVertexBuffer() {
  try {
    deviceContext_.wait(std::max(lastUse_, stagingTicket_));
  } catch (...) {
    // A destructor cannot report; a failed wait means the device is lost.
  }
}

void VkVertexBuffer::UpdateData(const float* src, int startVertex, int numVertices,
                                DeviceContext* deviceContext) {
  if (deviceContext && deviceContext != &deviceContext_)
    throw Error("VkVertexBuffer::UpdateData: called with another DeviceContext than Create");
  if (numVertices == 0) return;
  deviceContext_.submit([&](Batch& batch) { recordUpdate(batch, src, startVertex, numVertices); });
}

void VkVertexBuffer::recordUpdate(Batch& batch, const float* src, int startVertex,
                                  int numVertices) {
  if (startVertex < 0 || numVertices < 0 || startVertex + numVertices > numVertices_)
    throw Error("VkVertexBuffer::UpdateData: vertices [" + std::to_string(startVertex) + ", " +
                std::to_string(startVertex + numVertices) + ") outside the buffer of " +
                std::to_string(numVertices_) + " vertices");
  if (numVertices == 0) return;
  if (!src) throw Error("VkVertexBuffer::UpdateData: source pointer is null");
  const VkDeviceSize bytes = VkDeviceSize{sizeof(float)} * static_cast<VkDeviceSize>(numElements_) *
                             static_cast<VkDeviceSize>(numVertices);
  // The staging buffer is reused: the copy that read it last must be done.
  deviceContext_.wait(stagingTicket_);
  if (!staging_ || staging_.size() < bytes)
    staging_ = vulkan::Buffer(deviceContext_.context(), bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          vulkan::MemoryUse::Upload);
  std::memcpy(staging_.mapped(), src, bytes);

  VkCommandBuffer cmd = batch.commandBuffer();
  // Earlier readers (stencil kernels, draws, read-backs) and writers of the buffer finish first.
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kTransferWrite);
  const VkBufferCopy region{0,
                            VkDeviceSize{sizeof(float)} * static_cast<VkDeviceSize>(numElements_) *
                                static_cast<VkDeviceSize>(startVertex),
                            bytes};
  vkCmdCopyBuffer(cmd, staging_.handle(), buffer_.handle(), 1, &region);
  vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite, vulkan::scope::kAll);
  stagingTicket_ = batch.ticket();
  lastUse_ = batch.ticket();
}

VkBuffer VkVertexBuffer::BindVBO(DeviceContext* deviceContext) const {
  if (deviceContext && deviceContext != &deviceContext_)
    throw Error("VkVertexBuffer::BindVBO: called with another DeviceContext than Create");
  return buffer_.handle();
}

std::vector<float> VkVertexBuffer::readback() const {
  return vulkan::readback<float>(deviceContext_.context(), buffer_);
}

void VkVertexBuffer::markUsed(uint64_t ticket) const { lastUse_ = std::max(lastUse_, ticket); }

}  // namespace osd_cull::osd
