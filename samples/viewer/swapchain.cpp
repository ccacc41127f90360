#include "swapchain.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

#include <algorithm>

namespace osd_cull::viewer {

Swapchain::Swapchain(vulkan::Context& context, VkSurfaceKHR surface, uint32_t width,
                     uint32_t height)
    : context_(context), surface_(surface) {
  VkBool32 canPresent = VK_FALSE;
  OSD_CULL_VK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physicalDevice(), context.queueFamily(),
                                                   surface, &canPresent));
  if (!canPresent)
    throw Error("the queue family of device '" + context.info().name +
                "' cannot present to this window");
  uint32_t count = 0;
  OSD_CULL_VK(
      vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice(), surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  OSD_CULL_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice(), surface, &count,
                                                   formats.data()));
  // UNORM formats: the rendered view is blitted as is (its colors are already display
  // values), so an sRGB swapchain would brighten it.
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const auto& f : formats)
      if (format_ == VK_FORMAT_UNDEFINED && f.format == want) {
        format_ = f.format;
        colorSpace_ = f.colorSpace;
      }
  if (format_ == VK_FORMAT_UNDEFINED)
    throw Error("the window surface offers neither B8G8R8A8_UNORM nor R8G8B8A8_UNORM");
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), format_, &props);
  if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT))
    throw Error("the swapchain format cannot be a blit destination on this device");
  create(width, height, VK_NULL_HANDLE);
}

Swapchain::~Swapchain() {
  views_.clear();
  if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
}

bool Swapchain::bgr() const { return format_ == VK_FORMAT_B8G8R8A8_UNORM; }

void Swapchain::recreate(uint32_t width, uint32_t height) {
  context_.waitIdle();
  views_.clear();
  VkSwapchainKHR old = swapchain_;
  create(width, height, old);
  vkDestroySwapchainKHR(context_.device(), old, nullptr);
}

void Swapchain::create(uint32_t width, uint32_t height, VkSwapchainKHR old) {
  VkSurfaceCapabilitiesKHR caps;
  OSD_CULL_VK(
      vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice(), surface_, &caps));
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if ((caps.supportedUsageFlags & usage) != usage)
    throw Error(
        "the window surface does not allow color-attachment, transfer-source and "
        "transfer-destination use of its images");
  extent_ = caps.currentExtent;
  if (extent_.width == UINT32_MAX) {
    extent_.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  uint32_t imageCount = std::max(2u, caps.minImageCount + 1);
  if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = imageCount;
  info.imageFormat = format_;
  info.imageColorSpace = colorSpace_;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = usage;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : static_cast<VkCompositeAlphaFlagBitsKHR>(
                                  caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  OSD_CULL_VK(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &swapchain_));

  uint32_t n = 0;
  OSD_CULL_VK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &n, nullptr));
  images_.resize(n);
  OSD_CULL_VK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &n, images_.data()));
  for (VkImage image : images_) {
    VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    v.image = image;
    v.viewType = VK_IMAGE_VIEW_TYPE_2D;
    v.format = format_;
    v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateImageView(context_.device(), &v, nullptr, &view));
    views_.emplace_back(context_.device(), view);
  }
}

}  // namespace osd_cull::viewer
