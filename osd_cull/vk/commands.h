#pragma once
/// \file commands.h
/// \brief Small command-recording helpers: pipeline barriers and image layout changes.

#include <vulkan/vulkan.h>

namespace osd_cull::vulkan {

class Buffer;
class Image;

/// \brief One synchronization scope: pipeline stages and the memory accesses in them.
struct Scope {
  VkPipelineStageFlags stages;
  VkAccessFlags access;
};

/// Common scopes.
namespace scope {
inline constexpr Scope kNone{VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0};
inline constexpr Scope kAll{VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                            VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT};
inline constexpr Scope kTransferWrite{VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
inline constexpr Scope kTransferRead{VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
inline constexpr Scope kComputeRead{VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                    VK_ACCESS_SHADER_READ_BIT};
inline constexpr Scope kComputeWrite{VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                     VK_ACCESS_SHADER_WRITE_BIT};
inline constexpr Scope kComputeReadWrite{VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                         VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
inline constexpr Scope kIndirectRead{VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                                     VK_ACCESS_INDIRECT_COMMAND_READ_BIT};
inline constexpr Scope kVertexShaderRead{VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                                             VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT |
                                             VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT,
                                         VK_ACCESS_SHADER_READ_BIT};
inline constexpr Scope kColorAttachmentWrite{VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                             VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
inline constexpr Scope kDepthAttachmentWrite{
    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
inline constexpr Scope kHostRead{VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT};
}  // namespace scope

/// \brief A global memory barrier from `src` to `dst`.
void memoryBarrier(VkCommandBuffer cmd, Scope src, Scope dst);

/// \brief A barrier on a whole buffer from `src` to `dst`.
void bufferBarrier(VkCommandBuffer cmd, const Buffer& buffer, Scope src, Scope dst);

/// \brief A layout transition (or plain barrier when the layouts are equal) of mip levels
/// [baseMip, baseMip + mipCount) of an image; mipCount 0 means all remaining levels.
void imageBarrier(VkCommandBuffer cmd, const Image& image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, Scope src, Scope dst, uint32_t baseMip = 0,
                  uint32_t mipCount = 0);

/// \brief Groups needed to cover `count` items with groups of `groupSize`.
constexpr uint32_t groupCount(uint32_t count, uint32_t groupSize) {
  return (count + groupSize - 1) / groupSize;
}

}  // namespace osd_cull::vulkan
