#pragma once
/// \file storage.h
/// \brief Storage buffers of the Osd backend: size checks and filled device buffers.

#include "osd_cull/vk/buffer.h"

#include <cstddef>
#include <span>

namespace osd_cull::osd {

/// \brief Throws osd_cull::Error naming `what` when `bytes` exceeds the device's
/// maxStorageBufferRange (a descriptor cannot cover more; 128 MiB on lavapipe).
void requireStorageRange(vulkan::Context& context, VkDeviceSize bytes, const char* what);

/// \brief A device-local storage buffer (plus `extraUsage`) holding `bytes` (uploaded,
/// waits). An empty span still gets a small buffer, so that descriptors can always be written.
vulkan::Buffer makeStorageBuffer(vulkan::Context& context, std::span<const std::byte> bytes,
                             const char* what, VkBufferUsageFlags extraUsage = 0);

/// \brief makeStorageBuffer for an array of T.
template <class T>
vulkan::Buffer makeStorageBuffer(vulkan::Context& context, std::span<const T> values, const char* what,
                             VkBufferUsageFlags extraUsage = 0) {
  return makeStorageBuffer(context, std::as_bytes(values), what, extraUsage);
}

}  // namespace osd_cull::osd
