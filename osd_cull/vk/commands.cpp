#include "osd_cull/vk/commands.h"

#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/image.h"

namespace osd_cull::vulkan {

void memoryBarrier(VkCommandBuffer cmd, Scope src, Scope dst) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  b.srcAccessMask = src.access;
  b.dstAccessMask = dst.access;
  vkCmdPipelineBarrier(cmd, src.stages, dst.stages, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void bufferBarrier(VkCommandBuffer cmd, const Buffer& buffer, Scope src, Scope dst) {
  VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  b.srcAccessMask = src.access;
  b.dstAccessMask = dst.access;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = buffer.handle();
  b.offset = 0;
  b.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, src.stages, dst.stages, 0, 0, nullptr, 1, &b, 0, nullptr);
}

void imageBarrier(VkCommandBuffer cmd, const Image& image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, Scope src, Scope dst, uint32_t baseMip,
                  uint32_t mipCount) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src.access;
  b.dstAccessMask = dst.access;
  b.oldLayout = oldLayout;
  b.newLayout = newLayout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image.handle();
  b.subresourceRange = {image.aspect(), baseMip,
                        mipCount ? mipCount : image.desc().mipLevels - baseMip, 0, 1};
  vkCmdPipelineBarrier(cmd, src.stages, dst.stages, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace osd_cull::vulkan
