#include "osd_cull/frame/hiz_cull_stage.h"

#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

namespace osd_cull::frame {

std::span<const vk::DescriptorBinding> hizStageBindings() {
  static const vk::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
      {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  return bindings;
}

HiZCullStage::HiZCullStage(vk::Context& context, const HiZPyramid& pyramid)
    : pyramid_(pyramid),
      params_(context, sizeof(shader::HiZParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
      layout_(vk::createDescriptorSetLayout(context, hizStageBindings())),
      pool_(std::make_unique<vk::DescriptorPool>(context, 1, hizStageBindings())) {
  const shader::HiZParams p = pyramid.params();
  vk::upload<shader::HiZParams>(context, params_, std::span(&p, 1));
  set_ = pool_->allocate(layout_.get());
  vk::DescriptorWriter()
      .sampledImage(0, pyramid.view(), pyramid.fetchSampler(), VK_IMAGE_LAYOUT_GENERAL)
      .buffer(1, params_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      .update(context.device(), set_);
}

HiZCullStage::~HiZCullStage() = default;

}  // namespace osd_cull::frame
