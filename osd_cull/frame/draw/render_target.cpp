#include "osd_cull/frame/draw/render_target.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

#include <cstring>

namespace osd_cull::frame {

vulkan::UniqueRenderPass createTargetRenderPass(vulkan::Context& context, bool clear) {
  using T = RenderTarget;
  VkAttachmentDescription a[3]{};
  const VkFormat formats[3] = {T::kColorFormat, T::kItemFormat, T::kDepthFormat};
  const VkImageLayout resting[3] = {T::kColorLayout, T::kItemLayout, T::kDepthLayout};
  for (int i = 0; i < 3; ++i) {
    a[i].format = formats[i];
    a[i].samples = VK_SAMPLE_COUNT_1_BIT;
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

RenderTarget::RenderTarget(vulkan::Context& context, uint32_t width, uint32_t height) {
  const auto& limits = context.info().limits;
  if (width == 0 || height == 0 || width > limits.maxFramebufferWidth ||
      height > limits.maxFramebufferHeight)
    throw Error("RenderTarget: size " + std::to_string(width) + "x" + std::to_string(height) +
                " is not in [1, " + std::to_string(limits.maxFramebufferWidth) + "]x[1, " +
                std::to_string(limits.maxFramebufferHeight) + "]");
  color_ = vulkan::Image(context, {width, height, kColorFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
  items_ = vulkan::Image(context, {width, height, kItemFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT});
  depth_ = vulkan::Image(context,
                     {width, height, kDepthFormat,
                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
  clearPass_ = createTargetRenderPass(context, true);
  loadPass_ = createTargetRenderPass(context, false);
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

void RenderTarget::requireContents() const {
  if (!hasContents_) throw Error("RenderTarget: nothing has been drawn yet");
}

std::vector<uint8_t> RenderTarget::readColor(vulkan::Context& context) const {
  requireContents();
  const auto bytes = vulkan::readbackImage(context, color_, kColorLayout);
  return std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()),
                              reinterpret_cast<const uint8_t*>(bytes.data()) + bytes.size());
}

std::vector<uint32_t> RenderTarget::readItems(vulkan::Context& context) const {
  requireContents();
  const auto bytes = vulkan::readbackImage(context, items_, kItemLayout);
  std::vector<uint32_t> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

std::vector<float> RenderTarget::readDepth(vulkan::Context& context) const {
  requireContents();
  const auto bytes = vulkan::readbackImage(context, depth_, kDepthLayout);
  std::vector<float> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

}  // namespace osd_cull::frame
