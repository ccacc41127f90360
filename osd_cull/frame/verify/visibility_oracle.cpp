#include "osd_cull/frame/verify/visibility_oracle.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/shader_variants.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <osd_cull/shared/oracle_layout.h>

#include <algorithm>
#include <cstring>

namespace osd_cull::frame {

namespace {

const vulkan::DescriptorBinding kBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};

const vulkan::ShaderSource kCountShader{"oracle/count_items.comp", {}};

}  // namespace

uint32_t VisibilityCounts::visiblePatchCount() const {
  return static_cast<uint32_t>(
      std::count_if(pixels.begin(), pixels.end(), [](uint32_t n) { return n > 0; }));
}

VisibilityOracle::VisibilityOracle(vulkan::Context& context)
    : context_(context),
      program_(std::make_unique<vulkan::ComputeProgram>(context, kCountShader, kBindings,
                                                        sizeof(shader::CountConstants))),
      pool_(std::make_unique<vulkan::DescriptorPool>(context, 1, kBindings)) {}

VisibilityCounts VisibilityOracle::count(const RenderTarget& target, uint32_t patchCount,
                                         uint32_t tileLog2) {
  if (tileLog2 > kMaxTileLog2)
    throw Error("VisibilityOracle: tileLog2 " + std::to_string(tileLog2) + " exceeds " +
                std::to_string(kMaxTileLog2));
  if (!target.hasContents()) throw Error("VisibilityOracle: the render target was never drawn");
  VisibilityCounts out;
  out.width = target.width();
  out.height = target.height();
  out.tileLog2 = tileLog2;
  const uint64_t tileBins = uint64_t{patchCount} << (2 * tileLog2);
  const uint64_t tileBytes = std::max<uint64_t>(4, tileBins * 4);
  if (tileBytes > context_.info().limits.maxStorageBufferRange)
    throw Error("VisibilityOracle: " + std::to_string(patchCount) + " patches x " +
                std::to_string(1u << (2 * tileLog2)) +
                " tiles exceed one storage buffer; use a smaller tileLog2");

  vulkan::Buffer counts(context_, (size_t{patchCount} + shader::kCountExtra) * 4,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::Buffer tiles(context_, tileBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  pool_->reset();
  const VkDescriptorSet set = pool_->allocate(program_->setLayout());
  vulkan::DescriptorWriter()
      .storageImage(0, target.items().view(), RenderTarget::kItemLayout)
      .buffer(1, counts)
      .buffer(2, tiles)
      .update(context_.device(), set);

  shader::CountConstants c{};
  c.width = out.width;
  c.height = out.height;
  c.patchCount = patchCount;
  c.tileLog2 = tileLog2;
  c.tileWidth = out.tileWidth();
  c.tileHeight = out.tileHeight();
  context_.submit([&](VkCommandBuffer cmd) {
    // Zero the counters; the item buffer was written by an earlier render pass (its
    // external dependency makes those writes available).
    vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kTransferWrite);
    vkCmdFillBuffer(cmd, counts.handle(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, tiles.handle(), 0, VK_WHOLE_SIZE, 0);
    vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite, vulkan::scope::kComputeReadWrite);
    vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kComputeRead);
    program_->dispatch(cmd, set, std::as_bytes(std::span(&c, 1)),
                       vulkan::groupCount(out.width, shader::kCountGroupSize),
                       vulkan::groupCount(out.height, shader::kCountGroupSize));
    vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kAll);
  });
  const auto all = vulkan::readback<uint32_t>(context_, counts);
  out.pixels.assign(all.begin(), all.begin() + patchCount);
  out.backgroundPixels = all[patchCount + shader::kCountBackground];
  out.occluderPixels = all[patchCount + shader::kCountOccluder];
  out.unknownPixels = all[patchCount + shader::kCountUnknown];
  out.tilePixels = vulkan::readback<uint32_t>(context_, tiles);
  out.tilePixels.resize(tileBins);
  return out;
}

VisibilityCounts VisibilityOracle::query(Renderer& renderer, RenderTarget& target,
                                         const Camera& camera, const GpuPatchSet& patches,
                                         const PatchSet* host,
                                         std::span<const GpuTriangleMesh* const> occluders,
                                         const TessellationOptions& tessellation, uint32_t tileLog2,
                                         bool cullBackFaces) {
  RenderOptions options;
  options.tessellation = tessellation;
  options.cullBackFaces = cullBackFaces;
  const PatchDraw draw{&patches, host, 0};
  renderer.render(target, camera, {&draw, 1}, occluders, options);
  return count(target, patches.patchCount(), tileLog2);
}

std::vector<vulkan::ShaderVariant> oracleShaderVariants() {
  return {vulkan::ShaderVariant::file(kCountShader)};
}

}  // namespace osd_cull::frame
