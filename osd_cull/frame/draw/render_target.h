#pragma once
/// \file render_target.h
/// \brief Off-screen images of a view: shaded color, item buffer (patch IDs) and depth.

#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/image.h"

#include <cstdint>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::frame {

/// \brief Color (RGBA8), item buffer (R32_UINT, shaders/shared/draw_layout.h kItem*) and
/// depth (D32_SFLOAT) images with two compatible render passes: one clears, one keeps the
/// contents (for a second pass over the same depth).
///
/// Between passes the images rest in these layouts: color TRANSFER_SRC_OPTIMAL, items
/// GENERAL (read by compute as a storage image), depth DEPTH_STENCIL_ATTACHMENT_OPTIMAL.
/// Whoever uses them in between (Hi-Z build, item count) returns them to these layouts.
class RenderTarget {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  static constexpr VkFormat kItemFormat = VK_FORMAT_R32_UINT;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
  static constexpr VkImageLayout kColorLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  static constexpr VkImageLayout kItemLayout = VK_IMAGE_LAYOUT_GENERAL;
  static constexpr VkImageLayout kDepthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

  RenderTarget(vulkan::Context& context, uint32_t width, uint32_t height);

  uint32_t width() const { return color_.width(); }
  uint32_t height() const { return color_.height(); }
  const vulkan::Image& color() const { return color_; }
  const vulkan::Image& items() const { return items_; }
  const vulkan::Image& depth() const { return depth_; }
  VkFramebuffer framebuffer() const { return framebuffer_.get(); }
  /// \brief Render pass that clears all three images (color to `background`, items to 0,
  /// depth to 1).
  VkRenderPass clearPass() const { return clearPass_.get(); }
  /// \brief Render pass that keeps the images' contents.
  VkRenderPass loadPass() const { return loadPass_.get(); }
  /// \brief True once a pass has run (the images hold defined contents).
  bool hasContents() const { return hasContents_; }
  void markDrawn() { hasContents_ = true; }

  /// \brief The color image, RGBA8, rows top to bottom.
  std::vector<uint8_t> readColor(vulkan::Context& context) const;
  /// \brief The item buffer, one value per pixel, rows top to bottom.
  std::vector<uint32_t> readItems(vulkan::Context& context) const;
  /// \brief Depth in [0, 1] (1: nothing drawn), rows top to bottom.
  std::vector<float> readDepth(vulkan::Context& context) const;

 private:
  void requireContents() const;
  vulkan::Image color_;
  vulkan::Image items_;
  vulkan::Image depth_;
  vulkan::UniqueRenderPass clearPass_;
  vulkan::UniqueRenderPass loadPass_;
  vulkan::UniqueFramebuffer framebuffer_;
  bool hasContents_ = false;
};

/// \brief A render pass with the RenderTarget's attachments (clearing or loading).
vulkan::UniqueRenderPass createTargetRenderPass(vulkan::Context& context, bool clear);

}  // namespace osd_cull::frame
