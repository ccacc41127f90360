#include "osd_cull/vk/buffer.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

namespace osd_cull::vulkan {

Buffer::Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use)
    : size_(size),
      usage_(usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT),
      maxStorageRange_(context.info().limits.maxStorageBufferRange) {
  if (size == 0) throw Error("vulkan::Buffer: size must be positive");
  const bool addressable = context.info().optional.bufferDeviceAddress &&
                           (usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) != 0;
  if (addressable) usage_ |= VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage_;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateBuffer(context.device(), &info, nullptr, &buffer));
  buffer_ = UniqueBuffer(context.device(), buffer);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(context.device(), buffer, &req);
  allocation_ = context.memory().allocate(req, use, ResourceKind::Linear);
  OSD_CULL_VK(
      vkBindBufferMemory(context.device(), buffer, allocation_.memory(), allocation_.offset()));
  if (addressable) {
    VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    address.buffer = buffer;
    address_ = vkGetBufferDeviceAddress(context.device(), &address);
  }
}

VkDeviceAddress Buffer::deviceAddress() const {
  if (address_ == 0)
    throw Error(
        "vulkan::Buffer: no device address (needs the bufferDeviceAddress feature and a storage "
        "buffer)");
  return address_;
}

std::byte* Buffer::requireMapped() const {
  if (!mapped())
    throw Error(
        "vulkan::Buffer: buffer memory is not host-visible (use MemoryUse::Upload or Readback)");
  return mapped();
}

}  // namespace osd_cull::vulkan
