#pragma once
/// \file dynamic_rendering.h
/// \brief Passes without a VkRenderPass (Vulkan 1.3 / VK_KHR_dynamic_rendering) over a
/// RenderTarget's images, with the layout changes a render pass would make.

#include "osd_cull/frame/draw/render_target.h"

namespace osd_cull::frame {

/// \brief Moves the target's images from their resting layouts (UNDEFINED when `clear`)
/// to attachment layouts, ordered after any earlier access, and begins rendering with
/// load op CLEAR (`clears`: color, items if the target has them, then depth) or LOAD.
void beginRendering(const vulkan::Context& context, VkCommandBuffer cmd, const RenderTarget& target,
                    bool clear, const VkClearValue* clears);

/// \brief Ends rendering and returns the images to their resting layouts, the pass's
/// writes made visible to whatever comes next.
void endRendering(const vulkan::Context& context, VkCommandBuffer cmd, const RenderTarget& target);

}  // namespace osd_cull::frame
