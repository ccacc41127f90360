#include "osd_cull/frame/draw/tess_levels_pass.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/limits.h"
#include "osd_cull/vk/transfer.h"

namespace osd_cull::frame {

namespace {

constexpr uint32_t kGroupSize = 64;  // local_size_x of tess_levels.comp

vulkan::ShaderSource levelsShader(const char* bda) {
  return {"patch/tess_levels.comp", {{"OSD_CULL_POINTS_BDA", bda}}};
}

}  // namespace

void writeTessConstants(shader::DrawConstants& c, const Camera& camera,
                        const TessellationOptions& t) {
  c.viewProjection = glm::mat4(camera.viewProjection());
  c.eye = glm::vec4(glm::vec3(camera.eye()), float(t.pixelsPerSegment));
  c.viewport = glm::vec4(float(camera.width), float(camera.height), float(t.uniformLevel),
                         float(t.maxLevel));
  c.mode =
      t.mode == TessellationOptions::Mode::Uniform ? shader::kTessUniform : shader::kTessAdaptive;
}

bool usesTessLevelsPass(const GpuPatchSet& gpu, const TessellationOptions& options) {
  return options.mode == TessellationOptions::Mode::Adaptive && gpu.displacement() == nullptr;
}

std::vector<PatchTessLevels> readTessLevels(vulkan::Context& context, const GpuPatchSet& gpu,
                                            uint32_t slot) {
  if (slot >= gpu.tessLevelSlots())
    throw Error("readTessLevels: level slot " + std::to_string(slot) + " of a set with " +
                std::to_string(gpu.tessLevelSlots()));
  const uint32_t n = gpu.patchCount();
  const std::vector<uint32_t> words = vulkan::readback<uint32_t>(context, gpu.tessLevels());
  std::vector<PatchTessLevels> levels(n);
  for (uint32_t p = 0; p < n; ++p) {
    const uint32_t lo = words[2 * (size_t{slot} * n + p)];
    const uint32_t hi = words[2 * (size_t{slot} * n + p) + 1];
    for (int e = 0; e < 4; ++e) {  // packTessLevels (tess_levels.glsl): a byte per edge
      levels[p].lo[e] = double((lo >> (8 * e)) & 0xFFu);
      levels[p].hi[e] = double((hi >> (8 * e)) & 0xFFu);
    }
  }
  return levels;
}

std::vector<vulkan::ShaderVariant> tessLevelsPassShaderVariants() {
  return {vulkan::ShaderVariant::file(levelsShader("0")),
          vulkan::ShaderVariant::file(levelsShader("1"))};
}

TessLevelsPass::TessLevelsPass(vulkan::Context& context) {
  setLayout_ = vulkan::createDescriptorSetLayout(context, patchSetBindings());
  const VkDescriptorSetLayout set = setLayout_.get();
  layout_ = vulkan::createPipelineLayout(context, {&set, 1}, sizeof(shader::DrawConstants),
                                         VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vulkan::createComputePipeline(context, layout_.get(),
                                            levelsShader(pointsByAddressDefine(context)));
  groupLimit_ = context.info().limits.maxComputeWorkGroupCount[0];
}

void TessLevelsPass::record(VkCommandBuffer cmd, const Camera& world, const glm::dmat4* model,
                            const GpuPatchSet& gpu, uint32_t slot,
                            const TessellationOptions& options) const {
  if (slot >= gpu.tessLevelSlots())
    throw Error("TessLevelsPass: level slot " + std::to_string(slot) + " of a set with " +
                std::to_string(gpu.tessLevelSlots()) + " (GpuPatchSet::reserveTessLevelSlots)");
  if (!usesTessLevelsPass(gpu, options))
    throw Error("TessLevelsPass: only adaptive levels of undisplaced sets are precomputed");
  const uint32_t n = gpu.patchCount();
  if (n == 0) return;
  const uint64_t groups = (uint64_t{n} + kGroupSize - 1) / kGroupSize;
  if (groups > groupLimit_)
    throw Error("TessLevelsPass: " + std::to_string(n) + " patches need " +
                std::to_string(groups) + " workgroups, the device allows " +
                std::to_string(groupLimit_));
  const Camera camera = model ? instanceCamera(world, *model) : world;
  shader::DrawConstants c{};
  writeTessConstants(c, camera, effectiveOptions(options, gpu.hasTransitionEdges()));
  c.bezierCount = gpu.bezierCount();
  c.pointStride = gpu.pointStride();
  c.pointOffset = gpu.pointOffset();
  c.levelBase = slot * n;
  c.levelCount = n;
  // Earlier readers of these entries (draws, the cull kernel) finish before they are written.
  const vulkan::Scope readers{VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT |
                                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                              VK_ACCESS_SHADER_READ_BIT};
  vulkan::bufferBarrier(cmd, gpu.tessLevels(), readers, vulkan::scope::kComputeWrite);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  const VkDescriptorSet set = gpu.descriptorSet();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set, 0,
                          nullptr);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  vkCmdDispatch(cmd, static_cast<uint32_t>(groups), 1, 1);
  vulkan::bufferBarrier(cmd, gpu.tessLevels(), vulkan::scope::kComputeWrite, readers);
}

}  // namespace osd_cull::frame
