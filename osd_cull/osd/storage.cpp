#include "osd_cull/osd/storage.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

#include <algorithm>
#include <string>

namespace osd_cull::osd {

void requireStorageRange(vulkan::Context& context, VkDeviceSize bytes, const char* what) {
  const VkDeviceSize limit = context.info().limits.maxStorageBufferRange;
  if (bytes > limit)
    throw Error(std::string(what) + ": " + std::to_string(bytes) +
                " bytes exceed the device's maxStorageBufferRange of " + std::to_string(limit) +
                " bytes (one descriptor cannot cover the buffer)");
}

vulkan::Buffer makeStorageBuffer(vulkan::Context& context, std::span<const std::byte> bytes,
                             const char* what, VkBufferUsageFlags extraUsage) {
  requireStorageRange(context, bytes.size(), what);
  constexpr VkDeviceSize kMinBytes = 16;
  vulkan::Buffer buffer(context, std::max<VkDeviceSize>(bytes.size(), kMinBytes),
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | extraUsage);
  vulkan::uploadBytes(context, buffer, bytes);
  return buffer;
}

}  // namespace osd_cull::osd
