#include "osd_cull/vk/pipeline.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/image.h"

namespace osd_cull::vulkan {

const VkSpecializationInfo* SpecializationConstants::info() const {
  if (entries_.empty()) return nullptr;
  info_.mapEntryCount = static_cast<uint32_t>(entries_.size());
  info_.pMapEntries = entries_.data();
  info_.dataSize = data_.size();
  info_.pData = data_.data();
  return &info_;
}

UniqueShaderModule createShaderModule(Context& context, std::span<const uint32_t> spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateShaderModule(context.device(), &info, nullptr, &module));
  return UniqueShaderModule(context.device(), module);
}

UniquePipelineLayout createPipelineLayout(Context& context,
                                          std::span<const VkDescriptorSetLayout> setLayouts,
                                          uint32_t pushConstantBytes,
                                          VkShaderStageFlags pushStages) {
  if (pushConstantBytes > context.info().limits.maxPushConstantsSize)
    throw Error("push constants of " + std::to_string(pushConstantBytes) +
                " bytes exceed the device limit of " +
                std::to_string(context.info().limits.maxPushConstantsSize));
  VkPushConstantRange range{pushStages, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = static_cast<uint32_t>(setLayouts.size());
  info.pSetLayouts = setLayouts.data();
  info.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  info.pPushConstantRanges = pushConstantBytes ? &range : nullptr;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreatePipelineLayout(context.device(), &info, nullptr, &layout));
  return UniquePipelineLayout(context.device(), layout);
}

UniquePipeline createComputePipeline(Context& context, VkPipelineLayout layout, const Spirv& spirv,
                                     const SpecializationConstants& constants) {
  UniqueShaderModule module = createShaderModule(context, *spirv);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module.get();
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = constants.info();
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  OSD_CULL_VK(
      vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return UniquePipeline(context.device(), pipeline);
}

UniquePipeline createComputePipeline(Context& context, VkPipelineLayout layout,
                                     const ShaderSource& shader,
                                     const SpecializationConstants& constants) {
  if (shaderStageOf(shader.path) != VK_SHADER_STAGE_COMPUTE_BIT)
    throw Error("createComputePipeline: " + shader.path + " is not a compute shader (.comp)");
  return createComputePipeline(context, layout, compileShader(shader), constants);
}

UniquePipeline createGraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc) {
  std::vector<UniqueShaderModule> modules;
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  bool tessellated = false;
  for (const auto& s : desc.stages) {
    modules.push_back(createShaderModule(context, *s.spirv));
    VkPipelineShaderStageCreateInfo st{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    st.stage = s.stage;
    st.module = modules.back().get();
    st.pName = "main";
    st.pSpecializationInfo = s.constants.info();
    stages.push_back(st);
    tessellated |= s.stage == VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
  }
  if (tessellated != (desc.topology == VK_PRIMITIVE_TOPOLOGY_PATCH_LIST))
    throw Error("createGraphicsPipeline: tessellation stages need PATCH_LIST topology and back");

  VkPipelineVertexInputStateCreateInfo vertexInput{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineTessellationDomainOriginStateCreateInfo origin{
      VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_DOMAIN_ORIGIN_STATE_CREATE_INFO};
  origin.domainOrigin = desc.domainOrigin;
  VkPipelineTessellationStateCreateInfo tess{
      VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
  tess.pNext = &origin;
  tess.patchControlPoints = desc.patchControlPoints;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = desc.polygonMode;
  raster.cullMode = desc.cullMode;
  raster.frontFace = desc.frontFace;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = desc.samples;
  VkPipelineDepthStencilStateCreateInfo depth{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depthTest;
  depth.depthWriteEnable = desc.depthWrite;
  depth.depthCompareOp = desc.depthCompare;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorAttachments);
  for (auto& b : blends)
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                       VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = desc.colorAttachments;
  blend.pAttachments = blends.data();
  const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamicState{
      VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamicState.dynamicStateCount = 2;
  dynamicState.pDynamicStates = dynamic;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pTessellationState = tessellated ? &tess : nullptr;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamicState;
  info.layout = desc.layout;
  info.renderPass = desc.renderPass;
  info.subpass = desc.subpass;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  if (!desc.renderPass) {
    if (desc.colorFormats.size() != desc.colorAttachments)
      throw Error(
          "createGraphicsPipeline: dynamic rendering needs one format per color attachment (" +
          std::to_string(desc.colorAttachments) + " attachments, " +
          std::to_string(desc.colorFormats.size()) + " formats)");
    rendering.colorAttachmentCount = desc.colorAttachments;
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;
    if (aspectOf(desc.depthFormat) & VK_IMAGE_ASPECT_STENCIL_BIT)
      rendering.stencilAttachmentFormat = desc.depthFormat;
    info.pNext = &rendering;
  }
  VkPipeline pipeline = VK_NULL_HANDLE;
  OSD_CULL_VK(
      vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return UniquePipeline(context.device(), pipeline);
}

ComputeProgram::ComputeProgram(Context& context, const ShaderSource& shader,
                               std::span<const DescriptorBinding> bindings,
                               uint32_t pushConstantBytes, const SpecializationConstants& constants)
    : pushBytes_(pushConstantBytes) {
  setLayout_ = createDescriptorSetLayout(context, bindings);
  const VkDescriptorSetLayout set = setLayout_.get();
  layout_ =
      createPipelineLayout(context, {&set, 1}, pushConstantBytes, VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = createComputePipeline(context, layout_.get(), shader, constants);
}

void ComputeProgram::dispatch(VkCommandBuffer cmd, VkDescriptorSet set,
                              std::span<const std::byte> push, uint32_t groupsX, uint32_t groupsY,
                              uint32_t groupsZ) const {
  if (push.size() != pushBytes_)
    throw Error("ComputeProgram::dispatch: push constants of " + std::to_string(push.size()) +
                " bytes, the program declares " + std::to_string(pushBytes_));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set, 0,
                          nullptr);
  if (!push.empty())
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       static_cast<uint32_t>(push.size()), push.data());
  vkCmdDispatch(cmd, groupsX, groupsY, groupsZ);
}

}  // namespace osd_cull::vulkan
