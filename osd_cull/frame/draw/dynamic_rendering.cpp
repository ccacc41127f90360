#include "osd_cull/frame/draw/dynamic_rendering.h"

#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"

namespace osd_cull::frame {

namespace {

constexpr VkImageLayout kColorAttachment = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
constexpr VkImageLayout kDepthAttachment = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
constexpr vulkan::Scope kColorAccess{
    VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
    VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
constexpr vulkan::Scope kDepthAccess{
    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};

VkRenderingAttachmentInfo attachment(VkImageView view, VkImageLayout layout, bool clear,
                                     const VkClearValue& value) {
  VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  a.imageView = view;
  a.imageLayout = layout;
  a.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.clearValue = value;
  return a;
}

}  // namespace

void beginRendering(const vulkan::Context& context, VkCommandBuffer cmd, const RenderTarget& target,
                    bool clear, const VkClearValue* clears) {
  const VkImageLayout colorFrom = clear ? VK_IMAGE_LAYOUT_UNDEFINED : target.colorLayout();
  const VkImageLayout depthFrom = clear ? VK_IMAGE_LAYOUT_UNDEFINED : target.depthLayout();
  vulkan::imageBarrier(cmd, target.color(), colorFrom, kColorAttachment, vulkan::scope::kAll,
                       kColorAccess);
  vulkan::imageBarrier(cmd, target.depth(), depthFrom, kDepthAttachment, vulkan::scope::kAll,
                       kDepthAccess);
  VkRenderingAttachmentInfo colors[2] = {
      attachment(target.colorView(), kColorAttachment, clear, clears[0]), {}};
  uint32_t colorCount = 1;
  if (target.hasItems()) {
    vulkan::imageBarrier(cmd, target.items(),
                         clear ? VK_IMAGE_LAYOUT_UNDEFINED : RenderTarget::kItemLayout,
                         RenderTarget::kItemLayout, vulkan::scope::kAll, kColorAccess);
    colors[colorCount++] =
        attachment(target.items().view(), RenderTarget::kItemLayout, clear, clears[1]);
  }
  const VkRenderingAttachmentInfo depth =
      attachment(target.depthView(), kDepthAttachment, clear, clears[colorCount]);
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {target.width(), target.height()}};
  info.layerCount = 1;
  info.colorAttachmentCount = colorCount;
  info.pColorAttachments = colors;
  info.pDepthAttachment = &depth;
  if (vulkan::aspectOf(target.format().depth) & VK_IMAGE_ASPECT_STENCIL_BIT)
    info.pStencilAttachment = &depth;
  context.cmdBeginRendering()(cmd, &info);
}

void endRendering(const vulkan::Context& context, VkCommandBuffer cmd, const RenderTarget& target) {
  context.cmdEndRendering()(cmd);
  vulkan::imageBarrier(cmd, target.color(), kColorAttachment, target.colorLayout(), kColorAccess,
                       vulkan::scope::kAll);
  vulkan::imageBarrier(cmd, target.depth(), kDepthAttachment, target.depthLayout(), kDepthAccess,
                       vulkan::scope::kAll);
  if (target.hasItems())
    vulkan::imageBarrier(cmd, target.items(), RenderTarget::kItemLayout, RenderTarget::kItemLayout,
                         kColorAccess, vulkan::scope::kAll);
}

}  // namespace osd_cull::frame
