#pragma once
/// \file hiz_cull_stage.h
/// \brief The resources of the cull kernel's Hi-Z occlusion stage ("hiz",
/// shaders/cull/occlusion_hiz.glsl): descriptor set 1 with the pyramid and its parameters.

#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"

#include <memory>
#include <span>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::frame {

/// \brief Set 1 of the "hiz" stage: binding 0 the pyramid (combined image sampler, all
/// levels, GENERAL), binding 1 a uniform buffer with shader::HiZParams.
std::span<const vulkan::DescriptorBinding> hizStageBindings();

/// \brief The descriptor set to pass to CullPass::record() for a pyramid. The pyramid must
/// outlive it; its parameters are fixed when the set is made.
class HiZCullStage {
 public:
  HiZCullStage(vulkan::Context& context, const HiZPyramid& pyramid);
  ~HiZCullStage();
  HiZCullStage(const HiZCullStage&) = delete;
  HiZCullStage& operator=(const HiZCullStage&) = delete;

  VkDescriptorSet set() const { return set_; }
  const HiZPyramid& pyramid() const { return pyramid_; }

 private:
  const HiZPyramid& pyramid_;
  vulkan::Buffer params_;
  vulkan::UniqueDescriptorSetLayout layout_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace osd_cull::frame
