#pragma once
/// \file render_target.h
/// \brief Where a view is drawn: osd_cull's own off-screen images (shaded color, item
/// buffer of patch IDs, depth) or the application's color and depth attachments.

#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/image.h"

#include <cstdint>
#include <tuple>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::frame {

/// \brief What the patch and occluder pipelines are built for: attachment formats, sample
/// count, and a render pass + subpass or dynamic rendering. Targets with equal formats
/// share pipelines.
struct TargetFormat {
  VkFormat color = VK_FORMAT_R8G8B8A8_UNORM;
  /// The item buffer (R32_UINT, second color attachment); VK_FORMAT_UNDEFINED: none (the
  /// fragment shaders then write color only).
  VkFormat items = VK_FORMAT_R32_UINT;
  VkFormat depth = VK_FORMAT_D32_SFLOAT;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  /// The application's render pass the pipelines are made for; null with osd_cull's own
  /// passes (built per format set) or with dynamic rendering.
  VkRenderPass renderPass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  bool dynamicRendering = false;

  auto key() const {
    return std::tuple(color, items, depth, samples, renderPass, subpass, dynamicRendering);
  }
  bool operator<(const TargetFormat& o) const { return key() < o.key(); }
  bool operator==(const TargetFormat& o) const { return key() == o.key(); }
};

/// \brief osd_cull's own images: formats and how passes begin.
struct OwnTargetOptions {
  VkFormat color = VK_FORMAT_R8G8B8A8_UNORM;  ///< RGBA8 or BGRA8 (UNORM or SRGB)
  VkFormat depth = VK_FORMAT_D32_SFLOAT;      ///< a depth-only format (D16, X8_D24, D32)
  /// Begin passes with vkCmdBeginRendering instead of a VkRenderPass (needs
  /// OptionalFeatures::dynamicRendering).
  bool dynamicRendering = false;
};

/// \brief The application's attachments (borrowed: osd_cull destroys none of them), one
/// view, single mip level and layer each.
///
/// Layouts: the images are in `colorLayout` and `depthLayout` whenever osd_cull begins a
/// pass or builds the Hi-Z pyramid, and are left in them. With the application's render
/// passes, those are the passes' final layouts (and `loadPass`'s initial layouts); with
/// dynamic rendering, osd_cull moves the images to COLOR_ATTACHMENT_OPTIMAL and
/// DEPTH_STENCIL_ATTACHMENT_OPTIMAL for a pass and back, with barriers that also order the
/// pass after earlier writes and reads of the images.
struct ExternalTarget {
  uint32_t width = 0;
  uint32_t height = 0;
  VkImage colorImage = VK_NULL_HANDLE;
  VkImageView colorView = VK_NULL_HANDLE;
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;
  VkImageLayout colorLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  /// The depth attachment; created with SAMPLED usage (the Hi-Z pyramid reads it), a
  /// depth format the device can sample.
  VkImage depthImage = VK_NULL_HANDLE;
  VkImageView depthView = VK_NULL_HANDLE;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  /// Usage flags the images were created with (checked: COLOR/DEPTH attachment, and
  /// SAMPLED on depth for occlusion culling).
  VkImageUsageFlags colorUsage = 0;
  VkImageUsageFlags depthUsage = 0;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  /// Render-pass mode: the pass the first (clearing) pass begins, one compatible pass
  /// that loads color and depth for the second pass, and the framebuffer of both. The
  /// patches draw in subpass 0. All null: dynamic rendering with the views above.
  VkRenderPass clearPass = VK_NULL_HANDLE;
  VkRenderPass loadPass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  /// Clear values of clearPass, in its attachment order; empty: {background color, depth
  /// 1.0} for attachments {0: color, 1: depth}.
  std::vector<VkClearValue> clearValues;
};

/// \brief A view's images with the passes that draw into them.
///
/// Own targets: color (RGBA8 by default), item buffer (R32_UINT, shaders/shared/
/// draw_layout.h kItem*) and depth (D32_SFLOAT by default), with two compatible render
/// passes (one clears, one keeps the contents) or dynamic rendering. Between passes the
/// images rest in these layouts: color TRANSFER_SRC_OPTIMAL, items GENERAL (read by
/// compute as a storage image), depth DEPTH_STENCIL_ATTACHMENT_OPTIMAL. Whoever uses them
/// in between (Hi-Z build, item count) returns them to these layouts.
///
/// External targets (ExternalTarget): the application's color and depth, no item buffer.
class RenderTarget {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  static constexpr VkFormat kItemFormat = VK_FORMAT_R32_UINT;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
  static constexpr VkImageLayout kColorLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  static constexpr VkImageLayout kItemLayout = VK_IMAGE_LAYOUT_GENERAL;
  static constexpr VkImageLayout kDepthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

  /// \brief Own images in the default formats with render passes.
  RenderTarget(vulkan::Context& context, uint32_t width, uint32_t height);
  /// \brief Own images in the given formats.
  /// \throws osd_cull::Error for a format the device cannot render to (named), or dynamic
  /// rendering without the feature.
  RenderTarget(vulkan::Context& context, uint32_t width, uint32_t height,
               const OwnTargetOptions& options);
  /// \brief The application's attachments.
  /// \throws osd_cull::Error naming what is missing or unusable.
  RenderTarget(vulkan::Context& context, const ExternalTarget& target);

  uint32_t width() const { return depth_.width(); }
  uint32_t height() const { return depth_.height(); }
  const TargetFormat& format() const { return format_; }
  /// \brief False for external targets.
  bool hasItems() const { return static_cast<bool>(items_); }
  bool external() const { return external_; }
  const vulkan::Image& color() const { return color_; }
  /// \throws osd_cull::Error for targets without an item buffer.
  const vulkan::Image& items() const;
  const vulkan::Image& depth() const { return depth_; }
  /// \brief Layouts the images rest in between passes (see the class comment).
  VkImageLayout colorLayout() const { return colorLayout_; }
  VkImageLayout depthLayout() const { return depthLayout_; }
  /// \brief Views the passes render to (own or the application's).
  VkImageView colorView() const { return colorView_; }
  VkImageView depthView() const { return depthView_; }
  VkFramebuffer framebuffer() const { return framebuffer_ ? framebuffer_.get() : appFramebuffer_; }
  /// \brief Render pass that clears (null with dynamic rendering).
  VkRenderPass clearPass() const { return clearPass_ ? clearPass_.get() : appClearPass_; }
  /// \brief Render pass that keeps the images' contents (null with dynamic rendering).
  VkRenderPass loadPass() const { return loadPass_ ? loadPass_.get() : appLoadPass_; }
  /// \brief The application's clear values (empty: osd_cull's).
  const std::vector<VkClearValue>& clearValues() const { return clearValues_; }
  /// \brief True once a pass has run (the images hold defined contents).
  bool hasContents() const { return hasContents_; }
  void markDrawn() { hasContents_ = true; }

  /// \brief The color image, 4 bytes per pixel in its format's order, rows top to bottom.
  std::vector<uint8_t> readColor(vulkan::Context& context) const;
  /// \brief The item buffer, one value per pixel, rows top to bottom.
  std::vector<uint32_t> readItems(vulkan::Context& context) const;
  /// \brief Depth in [0, 1] (1: nothing drawn), rows top to bottom (D32_SFLOAT only).
  std::vector<float> readDepth(vulkan::Context& context) const;

 private:
  void createOwn(vulkan::Context& context, uint32_t width, uint32_t height,
                 const OwnTargetOptions& options);
  void requireContents() const;
  TargetFormat format_;
  bool external_ = false;
  vulkan::Image color_;
  vulkan::Image items_;
  vulkan::Image depth_;
  VkImageLayout colorLayout_ = kColorLayout;
  VkImageLayout depthLayout_ = kDepthLayout;
  VkImageView colorView_ = VK_NULL_HANDLE;
  VkImageView depthView_ = VK_NULL_HANDLE;
  vulkan::UniqueRenderPass clearPass_;
  vulkan::UniqueRenderPass loadPass_;
  vulkan::UniqueFramebuffer framebuffer_;
  VkRenderPass appClearPass_ = VK_NULL_HANDLE;
  VkRenderPass appLoadPass_ = VK_NULL_HANDLE;
  VkFramebuffer appFramebuffer_ = VK_NULL_HANDLE;
  std::vector<VkClearValue> clearValues_;
  bool hasContents_ = false;
};

/// \brief A render pass with the own-target attachments of `format` (clearing or loading).
vulkan::UniqueRenderPass createTargetRenderPass(vulkan::Context& context, bool clear,
                                                const TargetFormat& format = {});

}  // namespace osd_cull::frame
