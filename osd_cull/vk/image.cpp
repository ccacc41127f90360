#include "osd_cull/vk/image.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

namespace osd_cull::vulkan {

VkImageAspectFlags aspectOf(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
      return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
      return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
      return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

uint32_t texelSize(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM:
      return 1;
    case VK_FORMAT_R16_UNORM:
    case VK_FORMAT_D16_UNORM:
      return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
      return 4;
    case VK_FORMAT_R32G32_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      throw Error("vulkan::texelSize: format " + std::to_string(static_cast<int>(format)) +
                  " is not supported for read back");
  }
}

Image::Image(Context& context, const ImageDesc& desc) : desc_(desc) {
  if (desc.width == 0 || desc.height == 0 || desc.mipLevels == 0)
    throw Error("vulkan::Image: width, height and mip levels must be positive (got " +
                std::to_string(desc.width) + "x" + std::to_string(desc.height) + ", " +
                std::to_string(desc.mipLevels) + " mips)");
  desc_.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = desc.mipLevels;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc_.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateImage(context.device(), &info, nullptr, &image));
  image_ = UniqueImage(context.device(), image);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(context.device(), image, &req);
  allocation_ = context.memory().allocate(req, MemoryUse::DeviceLocal, ResourceKind::Optimal);
  OSD_CULL_VK(
      vkBindImageMemory(context.device(), image, allocation_.memory(), allocation_.offset()));

  makeViews(context, aspectOf(desc.format));
}

Image Image::borrow(Context& context, VkImage image, const ImageDesc& desc) {
  if (!image) throw Error("vulkan::Image::borrow: the image handle is null");
  if (desc.width == 0 || desc.height == 0 || desc.mipLevels == 0)
    throw Error("vulkan::Image::borrow: width, height and mip levels must be positive (got " +
                std::to_string(desc.width) + "x" + std::to_string(desc.height) + ", " +
                std::to_string(desc.mipLevels) + " mips)");
  Image out;
  out.desc_ = desc;
  out.borrowed_ = image;
  const VkImageAspectFlags aspect = aspectOf(desc.format);
  out.makeViews(context, (aspect & VK_IMAGE_ASPECT_DEPTH_BIT)
                             ? VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT}
                             : aspect);
  return out;
}

void Image::makeViews(Context& context, VkImageAspectFlags aspect) {
  auto makeView = [&](uint32_t base, uint32_t count) {
    VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    v.image = handle();
    v.viewType = VK_IMAGE_VIEW_TYPE_2D;
    v.format = desc_.format;
    v.subresourceRange = {aspect, base, count, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateImageView(context.device(), &v, nullptr, &view));
    return UniqueImageView(context.device(), view);
  };
  view_ = makeView(0, desc_.mipLevels);
  for (uint32_t level = 0; level < desc_.mipLevels; ++level)
    mipViews_.push_back(makeView(level, 1));
}

}  // namespace osd_cull::vulkan
