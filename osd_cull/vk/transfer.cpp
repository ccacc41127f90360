#include "osd_cull/vk/transfer.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"

#include <algorithm>
#include <cstring>

namespace osd_cull::vulkan {

void uploadGenerated(Context& context, const Buffer& dst, VkDeviceSize bytes,
                     const std::function<void(std::span<std::byte>, VkDeviceSize)>& fill,
                     VkDeviceSize dstOffset) {
  if (bytes == 0) return;
  if (dstOffset + bytes > dst.size())
    throw Error("vulkan::upload: " + std::to_string(bytes) + " bytes at offset " +
                std::to_string(dstOffset) + " do not fit a buffer of " +
                std::to_string(dst.size()) + " bytes");
  // One staging buffer of at most kUploadChunkBytes, refilled: a large upload never holds a
  // second full-size copy in host-visible memory (on lavapipe that is process memory).
  const VkDeviceSize chunk = std::min(bytes, kUploadChunkBytes);
  Buffer staging(context, chunk, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
  for (VkDeviceSize done = 0; done < bytes; done += chunk) {
    const VkDeviceSize n = std::min(chunk, bytes - done);
    fill(std::span<std::byte>(staging.mapped(), static_cast<size_t>(n)), done);
    context.submit([&](VkCommandBuffer cmd) {
      memoryBarrier(cmd, scope::kAll, scope::kTransferWrite);
      VkBufferCopy region{0, dstOffset + done, n};
      vkCmdCopyBuffer(cmd, staging.handle(), dst.handle(), 1, &region);
      memoryBarrier(cmd, scope::kTransferWrite, scope::kAll);
    });
  }
}

void initializeGenerated(Context& context, const Buffer& dst, VkDeviceSize bytes,
                         const std::function<void(std::span<std::byte>, VkDeviceSize)>& fill) {
  if (!dst.hostCoherent()) return uploadGenerated(context, dst, bytes, fill);
  if (bytes > dst.size())
    throw Error("vulkan::initializeGenerated: " + std::to_string(bytes) +
                " bytes do not fit a buffer of " + std::to_string(dst.size()) + " bytes");
  for (VkDeviceSize done = 0; done < bytes; done += kUploadChunkBytes) {
    const VkDeviceSize n = std::min(kUploadChunkBytes, bytes - done);
    fill(std::span<std::byte>(dst.mapped() + done, static_cast<size_t>(n)), done);
  }
}

void uploadBytes(Context& context, const Buffer& dst, std::span<const std::byte> bytes,
                 VkDeviceSize dstOffset) {
  uploadGenerated(
      context, dst, bytes.size(),
      [&](std::span<std::byte> chunk, VkDeviceSize offset) {
        std::memcpy(chunk.data(), bytes.data() + offset, chunk.size());
      },
      dstOffset);
}

std::vector<std::byte> readbackBytes(Context& context, const Buffer& src, VkDeviceSize offset,
                                     VkDeviceSize size) {
  if (offset > src.size())
    throw Error("vulkan::readback: offset " + std::to_string(offset) +
                " is beyond the buffer end (" + std::to_string(src.size()) + " bytes)");
  if (size == VK_WHOLE_SIZE) size = src.size() - offset;
  if (offset + size > src.size())
    throw Error("vulkan::readback: range [" + std::to_string(offset) + ", " +
                std::to_string(offset + size) + ") exceeds the buffer (" +
                std::to_string(src.size()) + " bytes)");
  std::vector<std::byte> out(size);
  if (size == 0) return out;
  Buffer staging(context, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
  context.submit([&](VkCommandBuffer cmd) {
    memoryBarrier(cmd, scope::kAll, scope::kTransferRead);
    VkBufferCopy region{offset, 0, size};
    vkCmdCopyBuffer(cmd, src.handle(), staging.handle(), 1, &region);
    memoryBarrier(cmd, scope::kTransferWrite, scope::kHostRead);
  });
  std::memcpy(out.data(), staging.mapped(), size);
  return out;
}

void fill(Context& context, const Buffer& dst, uint32_t value) {
  context.submit([&](VkCommandBuffer cmd) {
    memoryBarrier(cmd, scope::kAll, scope::kTransferWrite);
    vkCmdFillBuffer(cmd, dst.handle(), 0, VK_WHOLE_SIZE, value);
    memoryBarrier(cmd, scope::kTransferWrite, scope::kAll);
  });
}

std::vector<std::byte> readbackImage(Context& context, const Image& image, VkImageLayout layout,
                                     uint32_t mip) {
  if (layout == VK_IMAGE_LAYOUT_UNDEFINED)
    throw Error("vulkan::readbackImage: image has no contents (layout UNDEFINED)");
  if (mip >= image.desc().mipLevels)
    throw Error("vulkan::readbackImage: mip " + std::to_string(mip) + " does not exist");
  const uint32_t w = std::max(1u, image.width() >> mip);
  const uint32_t h = std::max(1u, image.height() >> mip);
  const VkDeviceSize size = VkDeviceSize{w} * h * texelSize(image.format());
  Buffer staging(context, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
  context.submit([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, scope::kAll,
                 scope::kTransferRead, mip, 1);
    VkBufferImageCopy region{};
    region.imageSubresource = {image.aspect() & ~VkImageAspectFlags(VK_IMAGE_ASPECT_STENCIL_BIT),
                               mip, 0, 1};
    region.imageExtent = {w, h, 1};
    vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           staging.handle(), 1, &region);
    imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout, scope::kTransferRead,
                 scope::kAll, mip, 1);
    memoryBarrier(cmd, scope::kTransferWrite, scope::kHostRead);
  });
  std::vector<std::byte> out(size);
  std::memcpy(out.data(), staging.mapped(), size);
  return out;
}

}  // namespace osd_cull::vulkan
