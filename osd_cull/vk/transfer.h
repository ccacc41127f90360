#pragma once
/// \file transfer.h
/// \brief Uploads and read-backs through staging buffers (one-shot submissions).
///
/// Each call submits and waits, with full barriers before and after the copy, so it is
/// safe after any earlier submission. Use them for setup and checks, not per-frame work
/// that should overlap.

#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/image.h"

#include <cstddef>
#include <cstring>
#include <functional>
#include <span>
#include <vector>

namespace osd_cull::vulkan {

class Context;

/// \brief Staging size of uploads: larger uploads are copied in pieces of this size.
inline constexpr VkDeviceSize kUploadChunkBytes = VkDeviceSize{16} << 20;

/// \brief Fills `bytes` bytes of `dst` from `dstOffset` on with what `fill(chunk, offset)`
/// writes into each staging piece (`offset`: of the piece within the `bytes`), so a caller
/// can convert its data straight into staging memory without a full-size host copy.
/// \throws osd_cull::Error when the range does not fit.
void uploadGenerated(Context& context, const Buffer& dst, VkDeviceSize bytes,
                     const std::function<void(std::span<std::byte>, VkDeviceSize)>& fill,
                     VkDeviceSize dstOffset = 0);

/// \brief uploadGenerated for a buffer that no submitted work uses yet (just created): where
/// its memory is mapped and host-coherent (unified-memory devices, lavapipe) `fill` writes
/// straight into it, in the same pieces and without a staging copy or a submission; elsewhere
/// it is uploadGenerated.
/// \throws osd_cull::Error when the range does not fit.
void initializeGenerated(Context& context, const Buffer& dst, VkDeviceSize bytes,
                         const std::function<void(std::span<std::byte>, VkDeviceSize)>& fill);

/// \brief Copies `bytes` into `dst` at `dstOffset`.
/// \throws osd_cull::Error when the range does not fit.
void uploadBytes(Context& context, const Buffer& dst, std::span<const std::byte> bytes,
                 VkDeviceSize dstOffset = 0);

/// \brief Copies an array into `dst` at element offset `first` (in units of T).
template <class T>
void upload(Context& context, const Buffer& dst, std::span<const T> values, size_t first = 0) {
  uploadBytes(context, dst, std::as_bytes(values), first * sizeof(T));
}

/// \brief Reads `size` bytes of `src` from `offset` (VK_WHOLE_SIZE: to the end).
std::vector<std::byte> readbackBytes(Context& context, const Buffer& src, VkDeviceSize offset = 0,
                                     VkDeviceSize size = VK_WHOLE_SIZE);

/// \brief Reads the buffer as an array of T (whole elements only).
template <class T>
std::vector<T> readback(Context& context, const Buffer& src) {
  const std::vector<std::byte> bytes = readbackBytes(context, src);
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

/// \brief Fills a buffer with a 32-bit value (vkCmdFillBuffer), submit and wait.
void fill(Context& context, const Buffer& dst, uint32_t value);

/// \brief Reads mip level `mip` of a color or depth image, tightly packed rows, top row
/// first. The image is in `layout` (not UNDEFINED) and is returned to it.
std::vector<std::byte> readbackImage(Context& context, const Image& image, VkImageLayout layout,
                                     uint32_t mip = 0);

}  // namespace osd_cull::vulkan
