#include "osd_cull/frame/occlusion_cull.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/gpu_patch_set.h"
#include "osd_cull/frame/hiz_pyramid.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <shared/hiz_layout.h>
#include <shared/visibility_layout.h>

namespace osd_cull::frame {

namespace {

const vk::DescriptorBinding kBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};

constexpr uint32_t kMaxSets = 64;

}  // namespace

OcclusionCullResult decodeOcclusionResult(uint32_t code) {
  OcclusionCullResult r;
  const uint32_t verdict = (code >> shader::kOcclusionVerdictShift) & 0xFFu;
  r.tested = verdict != shader::kOcclusionVerdictUntested;
  r.culled = (code & shader::kResultStageMask) == shader::kResultOcclusion;
  r.level = (code >> shader::kOcclusionLevelShift) & 0xFu;
  return r;
}

OcclusionCullKernel::OcclusionCullKernel(vk::Context& context)
    : context_(context),
      program_(std::make_unique<vk::ComputeProgram>(
          context, vk::ShaderSource{"hiz/occlusion_cull.comp", {}}, kBindings,
          sizeof(shader::OcclusionCullConstants))),
      pool_(std::make_unique<vk::DescriptorPool>(context, kMaxSets, kBindings)) {}

OcclusionCullKernel::~OcclusionCullKernel() = default;

VkDescriptorSet OcclusionCullKernel::set(const GpuPatchSet& patches, const HiZPyramid& pyramid,
                                         const vk::Buffer& results) {
  auto& set = sets_[{patches.points().handle(), pyramid.view(), results.handle()}];
  if (set) return set;
  if (allocated_ == kMaxSets) {
    // Start over; the caller's earlier command buffers have completed (record() is used
    // with submit-and-wait submissions).
    sets_.clear();
    pool_->reset();
    allocated_ = 0;
    return this->set(patches, pyramid, results);
  }
  set = pool_->allocate(program_->setLayout());
  ++allocated_;
  vk::DescriptorWriter()
      .buffer(0, patches.points())
      .sampledImage(1, pyramid.view(), pyramid.fetchSampler(), VK_IMAGE_LAYOUT_GENERAL)
      .buffer(2, results)
      .update(context_.device(), set);
  return set;
}

void OcclusionCullKernel::record(VkCommandBuffer cmd, const GpuPatchSet& patches,
                                 const Camera& camera, const HiZPyramid& pyramid,
                                 const vk::Buffer& results) {
  const auto& layout = pyramid.layout();
  if (camera.width != layout.width || camera.height != layout.height)
    throw Error("OcclusionCullKernel: camera viewport " + std::to_string(camera.width) + "x" +
                std::to_string(camera.height) + " differs from the pyramid's depth image " +
                std::to_string(layout.width) + "x" + std::to_string(layout.height));
  const uint32_t n = patches.patchCount();
  if (results.size() < size_t{n} * 4)
    throw Error("OcclusionCullKernel: results buffer of " + std::to_string(results.size()) +
                " bytes for " + std::to_string(n) + " patches");
  if (n == 0) return;
  shader::OcclusionCullConstants c{};
  c.viewProjection = glm::mat4(camera.viewProjection());
  c.hiz = pyramid.params();
  c.bezierCount = patches.bezierCount();
  c.patchCount = n;
  c.pointStride = patches.pointStride();
  c.pointOffset = patches.pointOffset();
  program_->dispatch(cmd, set(patches, pyramid, results), std::as_bytes(std::span(&c, 1)),
                     vk::groupCount(n, shader::kOcclusionGroupSize));
  vk::memoryBarrier(cmd, vk::scope::kComputeWrite,
                    {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT});
}

std::vector<OcclusionCullResult> OcclusionCullKernel::run(const GpuPatchSet& patches,
                                                          const Camera& camera,
                                                          const HiZPyramid& pyramid) {
  const uint32_t n = patches.patchCount();
  if (n == 0) return {};
  vk::Buffer results(context_, size_t{n} * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  context_.submit([&](VkCommandBuffer cmd) {
    vk::memoryBarrier(cmd, vk::scope::kAll, vk::scope::kComputeRead);
    record(cmd, patches, camera, pyramid, results);
  });
  const auto raw = vk::readback<uint32_t>(context_, results);
  sets_.erase({patches.points().handle(), pyramid.view(), results.handle()});
  std::vector<OcclusionCullResult> out(n);
  for (uint32_t p = 0; p < n; ++p) out[p] = decodeOcclusionResult(raw[p]);
  return out;
}

}  // namespace osd_cull::frame
