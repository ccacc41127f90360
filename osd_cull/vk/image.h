#pragma once
/// \file image.h
/// \brief A 2D VkImage with its memory and views.

#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/memory.h"

#include <cstdint>
#include <vector>

namespace osd_cull::vulkan {

class Context;

/// \brief What a 2D image is.
struct ImageDesc {
  uint32_t width = 0;
  uint32_t height = 0;
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = 0;
  uint32_t mipLevels = 1;
};

/// \brief The aspect of a format: depth, depth+stencil or color.
VkImageAspectFlags aspectOf(VkFormat format);

/// \brief Bytes per texel of the formats osd_cull reads back (throws for others).
uint32_t texelSize(VkFormat format);

/// \brief A 2D image in device-local memory with a view of all mips and one view per mip.
/// Usage always includes TRANSFER_SRC (read back) and TRANSFER_DST (clear, upload).
/// Starts in VK_IMAGE_LAYOUT_UNDEFINED; the caller tracks layouts.
class Image {
 public:
  Image() = default;
  Image(Context& context, const ImageDesc& desc);

  /// \brief Wraps an image the application owns (e.g. its depth attachment) without
  /// owning it: only the views made here are destroyed with the wrapper. `desc` must say
  /// what the image is (size, format, mip levels, the usage it was created with). Views of
  /// depth formats show the depth aspect only (for sampling); barriers use aspect().
  /// \throws osd_cull::Error for a null image or a zero size.
  static Image borrow(Context& context, VkImage image, const ImageDesc& desc);

  VkImage handle() const { return image_ ? image_.get() : borrowed_; }
  /// \brief True when the image belongs to someone else (borrow()).
  bool borrowed() const { return borrowed_ != VK_NULL_HANDLE; }
  const ImageDesc& desc() const { return desc_; }
  uint32_t width() const { return desc_.width; }
  uint32_t height() const { return desc_.height; }
  VkFormat format() const { return desc_.format; }
  VkImageAspectFlags aspect() const { return aspectOf(desc_.format); }
  /// \brief A view of all mip levels.
  VkImageView view() const { return view_.get(); }
  /// \brief A view of one mip level (for storage-image writes per level).
  VkImageView mipView(uint32_t level) const { return mipViews_.at(level).get(); }
  explicit operator bool() const { return handle() != VK_NULL_HANDLE; }

 private:
  void makeViews(Context& context, VkImageAspectFlags aspect);
  UniqueImage image_;
  VkImage borrowed_ = VK_NULL_HANDLE;
  Allocation allocation_;
  UniqueImageView view_;
  std::vector<UniqueImageView> mipViews_;
  ImageDesc desc_;
};

}  // namespace osd_cull::vulkan
