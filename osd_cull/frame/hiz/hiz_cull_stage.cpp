#include "osd_cull/frame/hiz/hiz_cull_stage.h"

#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

namespace osd_cull::frame {

std::span<const vulkan::DescriptorBinding> hizStageBindings() {
  static const vulkan::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
      {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  return bindings;
}

HiZCullStage::HiZCullStage(vulkan::Context& context, const HiZPyramid& pyramid)
    : pyramid_(pyramid),
      params_(context, sizeof(shader::HiZParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
      layout_(vulkan::createDescriptorSetLayout(context, hizStageBindings())),
      pool_(std::make_unique<vulkan::DescriptorPool>(context, 1, hizStageBindings())) {
  const shader::HiZParams p = pyramid.params();
  vulkan::upload<shader::HiZParams>(context, params_, std::span(&p, 1));
  set_ = pool_->allocate(layout_.get());
  vulkan::DescriptorWriter()
      .sampledImage(0, pyramid.view(), pyramid.fetchSampler(), VK_IMAGE_LAYOUT_GENERAL)
      .buffer(1, params_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      .update(context.device(), set_);
}

HiZCullStage::~HiZCullStage() = default;

}  // namespace osd_cull::frame
