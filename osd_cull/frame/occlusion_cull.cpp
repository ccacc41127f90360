#include "osd_cull/frame/occlusion_cull.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/gpu_patch_set.h"
#include "osd_cull/frame/hiz_pyramid.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <shared/hiz_layout.h>

#include <algorithm>

namespace osd_cull::frame {

namespace {

const vk::DescriptorBinding kBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};

}  // namespace

OcclusionCullKernel::OcclusionCullKernel(vk::Context& context)
    : context_(context),
      program_(std::make_unique<vk::ComputeProgram>(
          context, vk::ShaderSource{"hiz/occlusion_cull.comp", {}}, kBindings,
          sizeof(shader::OcclusionCullConstants))),
      pool_(std::make_unique<vk::DescriptorPool>(context, 1, kBindings)) {}

OcclusionCullKernel::~OcclusionCullKernel() = default;

std::vector<OcclusionCullResult> OcclusionCullKernel::run(const GpuPatchSet& patches,
                                                          const Camera& camera,
                                                          const HiZPyramid& pyramid) {
  const auto& layout = pyramid.layout();
  if (camera.width != layout.width || camera.height != layout.height)
    throw Error("OcclusionCullKernel: camera viewport " + std::to_string(camera.width) + "x" +
                std::to_string(camera.height) + " differs from the pyramid's depth image " +
                std::to_string(layout.width) + "x" + std::to_string(layout.height));
  const uint32_t n = patches.patchCount();
  if (n == 0) return {};
  vk::Buffer results(context_, size_t{n} * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  pool_->reset();
  const VkDescriptorSet set = pool_->allocate(program_->setLayout());
  vk::DescriptorWriter()
      .buffer(0, patches.points())
      .sampledImage(1, pyramid.view(), pyramid.fetchSampler(), VK_IMAGE_LAYOUT_GENERAL)
      .buffer(2, results)
      .update(context_.device(), set);
  shader::OcclusionCullConstants c{};
  c.viewProjection = glm::mat4(camera.viewProjection());
  c.hiz = pyramid.params();
  c.bezierCount = patches.bezierCount();
  c.patchCount = n;
  c.pointStride = patches.pointStride();
  c.pointOffset = patches.pointOffset();
  context_.submit([&](VkCommandBuffer cmd) {
    vk::memoryBarrier(cmd, vk::scope::kAll, vk::scope::kComputeRead);
    program_->dispatch(cmd, set, std::as_bytes(std::span(&c, 1)),
                       vk::groupCount(n, shader::kOcclusionGroupSize));
    vk::memoryBarrier(cmd, vk::scope::kComputeWrite, vk::scope::kAll);
  });
  const auto raw = vk::readback<uint32_t>(context_, results);
  std::vector<OcclusionCullResult> out(n);
  for (uint32_t p = 0; p < n; ++p) {
    out[p].tested = (raw[p] & shader::kOcclusionTested) != 0;
    out[p].culled = (raw[p] & shader::kOcclusionCulled) != 0;
    out[p].level = (raw[p] >> shader::kOcclusionLevelShift) & 0xFFu;
  }
  return out;
}

}  // namespace osd_cull::frame
