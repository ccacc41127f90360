#include "osd_cull/osd/storage.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

#include <algorithm>
#include <string>

namespace osd_cull::osd {

void requireStorageRange(vk::Context& context, VkDeviceSize bytes, const char* what) {
  const VkDeviceSize limit = context.info().limits.maxStorageBufferRange;
  if (bytes > limit)
    throw Error(std::string(what) + ": " + std::to_string(bytes) +
                " bytes exceed the device's maxStorageBufferRange of " + std::to_string(limit) +
                " bytes (one descriptor cannot cover the buffer)");
}

vk::Buffer makeStorageBuffer(vk::Context& context, std::span<const std::byte> bytes,
                             const char* what, VkBufferUsageFlags extraUsage) {
  requireStorageRange(context, bytes.size(), what);
  constexpr VkDeviceSize kMinBytes = 16;
  vk::Buffer buffer(context, std::max<VkDeviceSize>(bytes.size(), kMinBytes),
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | extraUsage);
  vk::uploadBytes(context, buffer, bytes);
  return buffer;
}

}  // namespace osd_cull::osd
