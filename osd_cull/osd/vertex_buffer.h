#pragma once
/// \file vertex_buffer.h
/// \brief VkVertexBuffer: the VERTEX_BUFFER of Osd::Mesh for Vulkan (like Osd::GLVertexBuffer).

#include "osd_cull/osd/device_context.h"
#include "osd_cull/vk/buffer.h"

#include <cstdint>
#include <span>
#include <vector>

namespace osd_cull::osd {

/// \brief A device buffer of `numVertices` vertices with `numElements` floats each,
/// usable as a storage buffer (stencil evaluation, patch drawing) and vertex buffer.
///
/// Satisfies OpenSubdiv's vertex-buffer concept: Create, UpdateData, GetNumElements,
/// GetNumVertices and BindVBO (which returns the VkBuffer, Osd::Mesh's
/// VertexBufferBinding for this backend).
class VkVertexBuffer {
 public:
  /// \brief A new buffer, owned by the caller (Osd::Mesh deletes it; OpenSubdiv's concept
  /// hands over a raw pointer). Contents are undefined until written.
  /// \throws osd_cull::Error when deviceContext is null, a count is not positive, or the
  /// buffer would exceed the device's maxStorageBufferRange.
  static VkVertexBuffer* Create(int numElements, int numVertices, DeviceContext* deviceContext);

  VkVertexBuffer(DeviceContext& deviceContext, int numElements, int numVertices);
  VkVertexBuffer(const VkVertexBuffer&) = delete;
  VkVertexBuffer& operator=(const VkVertexBuffer&) = delete;
  /// \brief Waits for the submissions that use this buffer, then frees it.
  ~VkVertexBuffer();

  /// \brief Copies `numVertices` vertices (numElements floats each) from `src` into the
  /// buffer starting at vertex `startVertex`. `src` is read before the call returns; the
  /// copy on the device is submitted without waiting and is ordered before later work.
  /// \throws osd_cull::Error when the range exceeds the buffer.
  void UpdateData(const float* src, int startVertex, int numVertices,
                  DeviceContext* deviceContext = nullptr);

  int GetNumElements() const { return numElements_; }
  int GetNumVertices() const { return numVertices_; }

  /// \brief The VkBuffer (for descriptor writes or vkCmdBindVertexBuffers).
  VkBuffer BindVBO(DeviceContext* deviceContext = nullptr) const;
  /// \brief The buffer object.
  const vulkan::Buffer& buffer() const { return buffer_; }

  /// \brief Records the copy of UpdateData into `batch` (for callers that combine the
  /// upload with other work in one submission). Same contract as UpdateData.
  void recordUpdate(Batch& batch, const float* src, int startVertex, int numVertices);

  /// \brief Reads the whole buffer back (waits for earlier work; for tests and tools).
  std::vector<float> readback() const;

  /// \brief Notes that submission `ticket` uses this buffer; the destructor waits for it.
  void markUsed(uint64_t ticket) const;

 private:
  DeviceContext& deviceContext_;
  int numElements_;
  int numVertices_;
  vulkan::Buffer buffer_;
  vulkan::Buffer staging_;            // host-visible source of UpdateData copies
  uint64_t stagingTicket_ = 0;    // last submission reading staging_
  mutable uint64_t lastUse_ = 0;  // last submission using buffer_
};

}  // namespace osd_cull::osd
