#pragma once
/// \file swapchain.h
/// \brief A presentable swapchain on a window surface: FIFO present mode, images usable as
/// color attachments (the HUD), blit destinations (the rendered view) and copy sources
/// (screenshots); recreated when the window size changes.

#include "osd_cull/vk/handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::viewer {

class Swapchain {
 public:
  /// \throws osd_cull::Error when the queue cannot present to `surface` or the surface
  /// offers no usable format or usage.
  Swapchain(vulkan::Context& context, VkSurfaceKHR surface, uint32_t width, uint32_t height);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  /// \brief Rebuilds the images for a new size (waits for the device first).
  void recreate(uint32_t width, uint32_t height);

  VkSwapchainKHR handle() const { return swapchain_; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
  VkImage image(uint32_t i) const { return images_.at(i); }
  VkImageView view(uint32_t i) const { return views_.at(i).get(); }
  /// \brief True when the format stores blue first (B8G8R8A8): screenshots swap to RGBA.
  bool bgr() const;

 private:
  void create(uint32_t width, uint32_t height, VkSwapchainKHR old);

  vulkan::Context& context_;
  VkSurfaceKHR surface_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR colorSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{};
  std::vector<VkImage> images_;
  std::vector<vulkan::UniqueImageView> views_;
};

}  // namespace osd_cull::viewer
