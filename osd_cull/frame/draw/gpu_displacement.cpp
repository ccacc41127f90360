#include "osd_cull/frame/draw/gpu_displacement.h"

#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

#include <shared/displacement_layout.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace osd_cull::frame {

namespace sh = osd_cull::shader;

std::span<const vulkan::DescriptorBinding> displacementSetBindings() {
  static const vulkan::DescriptorBinding bindings[] = {
      {sh::kDisplaceBindingMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
       VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT},
      {sh::kDisplaceBindingUVs, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
       VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT},
      {sh::kDisplaceBindingParams, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
       VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT},
      {sh::kDisplaceBindingEdges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
       VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT},
      {sh::kDisplaceBindingRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
       VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT}};
  return bindings;
}

GpuDisplacement::GpuDisplacement(vulkan::Context& context, const bound::DisplacementMap& map,
                                 std::span<const glm::dvec2> uvCorners, uint32_t patchCount)
    : map_(map) {
  const std::string where = "displacement map " + map.name();
  if (uvCorners.empty() && patchCount > 0)
    throw Error(where +
                ": the mesh has no texture coordinates (OBJ 'vt'); a displacement "
                "map needs them");
  if (uvCorners.size() != 4 * size_t{patchCount})
    throw Error(where + ": " + std::to_string(uvCorners.size()) + " texture coordinates for " +
                std::to_string(patchCount) + " patches (4 per patch expected)");
  const uint32_t maxSide = context.info().limits.maxImageDimension2D;
  if (map.width() > maxSide || map.height() > maxSide)
    throw Error(where + ": " + std::to_string(map.width()) + " x " + std::to_string(map.height()) +
                " texels exceed the device's maxImageDimension2D " + std::to_string(maxSide));
  VkFormatProperties format{};
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), VK_FORMAT_R32_SFLOAT, &format);
  if (!(format.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    throw Error(where + ": the device cannot filter R32_SFLOAT images linearly");

  // The map: levels 0..maxLod (the sampler never reads coarser ones).
  const uint32_t levels = map.maxLod() + 1;
  image_ = vulkan::Image(context, {map.width(), map.height(), VK_FORMAT_R32_SFLOAT,
                                   VK_IMAGE_USAGE_SAMPLED_BIT, levels});
  size_t bytes = 0;
  for (uint32_t l = 0; l < levels; ++l) bytes += map.level(l).size() * sizeof(float);
  vulkan::Buffer staging(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         vulkan::MemoryUse::Upload);
  std::vector<VkBufferImageCopy> copies;
  size_t offset = 0;
  for (uint32_t l = 0; l < levels; ++l) {
    const std::vector<float>& texels = map.level(l);
    std::memcpy(staging.mapped() + offset, texels.data(), texels.size() * sizeof(float));
    VkBufferImageCopy c{};
    c.bufferOffset = offset;
    c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
    c.imageExtent = {map.levelWidth(l), map.levelHeight(l), 1};
    copies.push_back(c);
    offset += texels.size() * sizeof(float);
  }
  context.submit([&](VkCommandBuffer cmd) {
    vulkan::imageBarrier(cmd, image_, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, vulkan::scope::kNone,
                         vulkan::scope::kTransferWrite);
    vkCmdCopyBufferToImage(cmd, staging.handle(), image_.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           static_cast<uint32_t>(copies.size()), copies.data());
    vulkan::imageBarrier(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, vulkan::scope::kTransferWrite,
                         vulkan::scope::kVertexShaderRead);
  });

  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.minLod = 0.0f;
  info.maxLod = static_cast<float>(map.maxLod());  // what the bounds assume
  VkSampler sampler = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
  sampler_ = vulkan::UniqueSampler(context.device(), sampler);

  std::vector<float> uvs(std::max<size_t>(4, 2 * size_t{uvCorners.size()}));
  for (size_t i = 0; i < uvCorners.size(); ++i) {
    uvs[2 * i] = static_cast<float>(uvCorners[i].x);
    uvs[2 * i + 1] = static_cast<float>(uvCorners[i].y);
  }
  uvs_ = vulkan::Buffer(context, uvs.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context, uvs_, uvs);
  sh::DisplacementParams params{};
  params.map = glm::vec4(float(map.scale()), float(map.midlevel()), float(map.maxLod()),
                         1.0f / float(map.width()));
  params.size =
      glm::vec4(1.0f / float(map.height()), float(map.displacementRange().maxAbs()), 0.0f, 0.0f);
  params_ = vulkan::Buffer(context, sizeof(params), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::uploadBytes(context, params_, std::as_bytes(std::span(&params, 1)));

  edges_ = frame::edgeDisplacements(map, uvCorners, patchCount);
  std::vector<float> edgeFloats(std::max<size_t>(12, 12 * edges_.size()));
  for (size_t p = 0; p < edges_.size(); ++p) {
    std::copy(edges_[p].whole.begin(), edges_[p].whole.end(), edgeFloats.begin() + 12 * p);
    std::copy(edges_[p].firstHalf.begin(), edges_[p].firstHalf.end(),
              edgeFloats.begin() + 12 * p + 4);
    std::copy(edges_[p].secondHalf.begin(), edges_[p].secondHalf.end(),
              edgeFloats.begin() + 12 * p + 8);
  }
  edgeBuffer_ = vulkan::Buffer(context, edgeFloats.size() * sizeof(float),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context, edgeBuffer_, edgeFloats);

  // (Dmin, Dmax) per patch, rounded outward exactly as the displaced cull kernel's copy
  // (packDisplacementRanges): the depth clamp of patch.tesc and the kernel's nearest depth
  // start from the same floats.
  std::vector<bound::DisplacementRange> ranges(patchCount);
  for (uint32_t p = 0; p < patchCount; ++p)
    ranges[p] = map.displacementOver(bound::patchUvRegion(uvCorners.subspan(4 * size_t{p}, 4)));
  const std::vector<float> rangeFloats = packDisplacementRanges(ranges);
  ranges_ = vulkan::Buffer(context, rangeFloats.size() * sizeof(float),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context, ranges_, rangeFloats);

  setLayout_ = vulkan::createDescriptorSetLayout(context, displacementSetBindings());
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, 1, displacementSetBindings());
  set_ = pool_->allocate(setLayout_.get());
  vulkan::DescriptorWriter()
      .sampledImage(sh::kDisplaceBindingMap, image_.view(), sampler_.get())
      .buffer(sh::kDisplaceBindingUVs, uvs_)
      .buffer(sh::kDisplaceBindingParams, params_)
      .buffer(sh::kDisplaceBindingEdges, edgeBuffer_)
      .buffer(sh::kDisplaceBindingRanges, ranges_)
      .update(context.device(), set_);
}

}  // namespace osd_cull::frame
