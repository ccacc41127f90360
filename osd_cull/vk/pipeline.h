#pragma once
/// \file pipeline.h
/// \brief Shader modules, pipeline layouts, compute and graphics pipelines.

#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/shader_compiler.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace osd_cull::vulkan {

class Context;
struct DescriptorBinding;

/// \brief Specialization constant values of one shader stage.
class SpecializationConstants {
 public:
  /// \brief Sets constant `id` (`layout(constant_id = id)`) to a 32-bit value.
  template <class T>
  SpecializationConstants& set(uint32_t id, T value) {
    static_assert(sizeof(T) == 4, "specialization constants here are 32-bit (bool as uint32_t)");
    const uint32_t offset = static_cast<uint32_t>(data_.size());
    data_.resize(data_.size() + 4);
    std::memcpy(data_.data() + offset, &value, 4);
    entries_.push_back({id, offset, 4});
    return *this;
  }
  bool empty() const { return entries_.empty(); }
  /// \brief The VkSpecializationInfo (valid while this object lives and is unchanged).
  const VkSpecializationInfo* info() const;

 private:
  std::vector<VkSpecializationMapEntry> entries_;
  std::vector<std::byte> data_;
  mutable VkSpecializationInfo info_{};
};

/// \brief A shader module from SPIR-V words.
UniqueShaderModule createShaderModule(Context& context, std::span<const uint32_t> spirv);

/// \brief A pipeline layout with descriptor set layouts and one push-constant range at
/// offset 0 (none when pushConstantBytes is 0).
UniquePipelineLayout createPipelineLayout(Context& context,
                                          std::span<const VkDescriptorSetLayout> setLayouts,
                                          uint32_t pushConstantBytes = 0,
                                          VkShaderStageFlags pushStages = VK_SHADER_STAGE_ALL);

/// \brief A compute pipeline from an embedded shader variant.
UniquePipeline createComputePipeline(Context& context, VkPipelineLayout layout,
                                     const ShaderSource& shader,
                                     const SpecializationConstants& constants = {});

/// \brief A compute pipeline from SPIR-V.
UniquePipeline createComputePipeline(Context& context, VkPipelineLayout layout, const Spirv& spirv,
                                     const SpecializationConstants& constants = {});

/// \brief One stage of a graphics pipeline.
struct GraphicsStage {
  VkShaderStageFlagBits stage;
  Spirv spirv;
  SpecializationConstants constants;
};

/// \brief Everything a graphics pipeline needs. Viewport and scissor are dynamic.
struct GraphicsPipelineDesc {
  std::vector<GraphicsStage> stages;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  /// Null: dynamic rendering with the formats below (VkPipelineRenderingCreateInfo).
  VkRenderPass renderPass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  uint32_t colorAttachments = 1;
  /// Dynamic rendering only: one format per color attachment, and the depth format (its
  /// stencil aspect, if any, is declared too).
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  uint32_t patchControlPoints = 0;  ///< for PATCH_LIST
  VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
  VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
  VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depthTest = true;
  bool depthWrite = true;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
  /// Tessellation domain origin (Vulkan 1.1 core); LOWER_LEFT matches OpenGL.
  VkTessellationDomainOrigin domainOrigin = VK_TESSELLATION_DOMAIN_ORIGIN_UPPER_LEFT;
};

/// \brief A graphics pipeline (no vertex input: shaders fetch from storage buffers).
UniquePipeline createGraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc);

/// \brief Set layout, pipeline layout and pipeline of one compute shader with one
/// descriptor set and a push-constant block: the unit cull kernels and evaluators are
/// built from.
class ComputeProgram {
 public:
  ComputeProgram(Context& context, const ShaderSource& shader,
                 std::span<const DescriptorBinding> bindings, uint32_t pushConstantBytes,
                 const SpecializationConstants& constants = {});
  VkPipeline pipeline() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkDescriptorSetLayout setLayout() const { return setLayout_.get(); }
  /// \brief Binds pipeline and `set`, pushes `push` (if any) and dispatches.
  void dispatch(VkCommandBuffer cmd, VkDescriptorSet set, std::span<const std::byte> push,
                uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1) const;

 private:
  UniqueDescriptorSetLayout setLayout_;
  UniquePipelineLayout layout_;
  UniquePipeline pipeline_;
  uint32_t pushBytes_;
};

}  // namespace osd_cull::vulkan
