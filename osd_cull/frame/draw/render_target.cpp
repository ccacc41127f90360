#include "osd_cull/frame/draw/render_target.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

#include <cstring>
#include <string>

namespace osd_cull::frame {

namespace {

std::string formatName(VkFormat format) { return std::to_string(static_cast<int>(format)); }

void requireFormat(const vulkan::Context& context, VkFormat format, VkFormatFeatureFlags need,
                   const char* what) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), format, &props);
  if ((props.optimalTilingFeatures & need) != need)
    throw Error(std::string("RenderTarget: the device cannot use format ") + formatName(format) +
                " as " + what);
}

void checkSize(const vulkan::Context& context, uint32_t width, uint32_t height) {
  const auto& limits = context.info().limits;
  if (width == 0 || height == 0 || width > limits.maxFramebufferWidth ||
      height > limits.maxFramebufferHeight)
    throw Error("RenderTarget: size " + std::to_string(width) + "x" + std::to_string(height) +
                " is not in [1, " + std::to_string(limits.maxFramebufferWidth) + "]x[1, " +
                std::to_string(limits.maxFramebufferHeight) + "]");
}

void requireDynamicRendering(const vulkan::Context& context) {
  if (!context.info().optional.dynamicRendering)
    throw Error(
        "RenderTarget: dynamic rendering was asked for but the device has not enabled it "
        "(Vulkan 1.3 dynamicRendering or VK_KHR_dynamic_rendering)");
}

}  // namespace

vulkan::UniqueRenderPass createTargetRenderPass(vulkan::Context& context, bool clear,
                                                const TargetFormat& format) {
  using T = RenderTarget;
  VkAttachmentDescription a[3]{};
  const VkFormat formats[3] = {format.color, format.items, format.depth};
  const VkImageLayout resting[3] = {T::kColorLayout, T::kItemLayout, T::kDepthLayout};
  for (int i = 0; i < 3; ++i) {
    a[i].format = formats[i];
    a[i].samples = format.samples;
    a[i].loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a[i].initialLayout = clear ? VK_IMAGE_LAYOUT_UNDEFINED : resting[i];
    a[i].finalLayout = resting[i];
  }
  const VkAttachmentReference colorRefs[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                              {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
  const VkAttachmentReference depthRef{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 2;
  subpass.pColorAttachments = colorRefs;
  subpass.pDepthStencilAttachment = &depthRef;
  // Whatever touched the images before (copies, compute, an earlier pass) finishes before
  // this pass, and this pass finishes before whatever comes after.
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT;
  deps[0].dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT;
  deps[1].srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  deps[1].dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 3;
  info.pAttachments = a;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateRenderPass(context.device(), &info, nullptr, &pass));
  return vulkan::UniqueRenderPass(context.device(), pass);
}

RenderTarget::RenderTarget(vulkan::Context& context, uint32_t width, uint32_t height)
    : RenderTarget(context, width, height, OwnTargetOptions{}) {}

RenderTarget::RenderTarget(vulkan::Context& context, uint32_t width, uint32_t height,
                           const OwnTargetOptions& options) {
  checkSize(context, width, height);
  if (vulkan::aspectOf(options.depth) != VK_IMAGE_ASPECT_DEPTH_BIT)
    throw Error("RenderTarget: own depth format " + formatName(options.depth) +
                " is not a depth-only format (D16_UNORM, X8_D24_UNORM_PACK32, D32_SFLOAT)");
  requireFormat(context, options.color, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, "color attachment");
  requireFormat(
      context, options.depth,
      VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT,
      "a sampled depth attachment");
  if (options.dynamicRendering) requireDynamicRendering(context);
  format_.color = options.color;
  format_.depth = options.depth;
  format_.dynamicRendering = options.dynamicRendering;
  color_ =
      vulkan::Image(context, {width, height, options.color,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
  items_ =
      vulkan::Image(context, {width, height, kItemFormat,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT});
  depth_ = vulkan::Image(
      context, {width, height, options.depth,
                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
  colorView_ = color_.view();
  depthView_ = depth_.view();
  if (options.dynamicRendering) return;
  clearPass_ = createTargetRenderPass(context, true, format_);
  loadPass_ = createTargetRenderPass(context, false, format_);
  const VkImageView views[3] = {color_.view(), items_.view(), depth_.view()};
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = clearPass_.get();
  info.attachmentCount = 3;
  info.pAttachments = views;
  info.width = width;
  info.height = height;
  info.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateFramebuffer(context.device(), &info, nullptr, &fb));
  framebuffer_ = vulkan::UniqueFramebuffer(context.device(), fb);
}

RenderTarget::RenderTarget(vulkan::Context& context, const ExternalTarget& t) : external_(true) {
  std::vector<std::string> missing;
  if (!t.colorImage) missing.push_back("colorImage");
  if (!t.colorView) missing.push_back("colorView");
  if (!t.depthImage) missing.push_back("depthImage");
  if (!t.depthView) missing.push_back("depthView");
  if (t.colorFormat == VK_FORMAT_UNDEFINED) missing.push_back("colorFormat");
  if (t.depthFormat == VK_FORMAT_UNDEFINED) missing.push_back("depthFormat");
  const bool passMode = t.clearPass || t.loadPass || t.framebuffer;
  if (passMode && !t.clearPass) missing.push_back("clearPass");
  if (passMode && !t.loadPass) missing.push_back("loadPass (a compatible pass that loads)");
  if (passMode && !t.framebuffer) missing.push_back("framebuffer");
  if (!(t.colorUsage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT))
    missing.push_back("COLOR_ATTACHMENT usage of the color image (colorUsage)");
  if (!(t.depthUsage & VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT))
    missing.push_back("DEPTH_STENCIL_ATTACHMENT usage of the depth image (depthUsage)");
  if (!missing.empty()) {
    std::string list;
    for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw Error("RenderTarget(ExternalTarget): missing " + list);
  }
  checkSize(context, t.width, t.height);
  if (!(vulkan::aspectOf(t.depthFormat) & VK_IMAGE_ASPECT_DEPTH_BIT))
    throw Error("RenderTarget(ExternalTarget): depthFormat " + formatName(t.depthFormat) +
                " is not a depth format");
  if (!passMode) requireDynamicRendering(context);
  format_.color = t.colorFormat;
  format_.items = VK_FORMAT_UNDEFINED;
  format_.depth = t.depthFormat;
  format_.samples = t.samples;
  format_.renderPass = t.clearPass;
  format_.dynamicRendering = !passMode;
  color_ = vulkan::Image::borrow(context, t.colorImage,
                                 {t.width, t.height, t.colorFormat, t.colorUsage});
  depth_ = vulkan::Image::borrow(context, t.depthImage,
                                 {t.width, t.height, t.depthFormat, t.depthUsage});
  colorLayout_ = t.colorLayout;
  depthLayout_ = t.depthLayout;
  colorView_ = t.colorView;
  depthView_ = t.depthView;
  appClearPass_ = t.clearPass;
  appLoadPass_ = t.loadPass;
  appFramebuffer_ = t.framebuffer;
  clearValues_ = t.clearValues;
}

const vulkan::Image& RenderTarget::items() const {
  if (!items_)
    throw Error(
        "RenderTarget: an application's target has no item buffer (the oracle and "
        "item counts need osd_cull's own target)");
  return items_;
}

void RenderTarget::requireContents() const {
  if (!hasContents_) throw Error("RenderTarget: nothing has been drawn yet");
}

std::vector<uint8_t> RenderTarget::readColor(vulkan::Context& context) const {
  requireContents();
  if (!(color_.desc().usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
    throw Error("RenderTarget::readColor: the color image was not created with TRANSFER_SRC usage");
  const auto bytes = vulkan::readbackImage(context, color_, colorLayout_);
  return std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()),
                              reinterpret_cast<const uint8_t*>(bytes.data()) + bytes.size());
}

std::vector<uint32_t> RenderTarget::readItems(vulkan::Context& context) const {
  requireContents();
  const auto bytes = vulkan::readbackImage(context, items(), kItemLayout);
  std::vector<uint32_t> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

std::vector<float> RenderTarget::readDepth(vulkan::Context& context) const {
  requireContents();
  if (depth_.format() != VK_FORMAT_D32_SFLOAT)
    throw Error("RenderTarget::readDepth: reads D32_SFLOAT depth only (format " +
                formatName(depth_.format()) + ")");
  const auto bytes = vulkan::readbackImage(context, depth_, depthLayout_);
  std::vector<float> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

}  // namespace osd_cull::frame
