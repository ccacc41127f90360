#include "osd_cull/frame/hiz/hiz_pyramid.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/shader_variants.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <cstring>

namespace osd_cull::frame {

namespace {

constexpr VkFormat kPyramidFormat = VK_FORMAT_R32_SFLOAT;
constexpr VkImageLayout kPyramidLayout = VK_IMAGE_LAYOUT_GENERAL;
constexpr VkImageLayout kDepthReadLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;

const vulkan::DescriptorBinding kBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};

constexpr vulkan::Scope kDepthWrite{
    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
constexpr vulkan::Scope kDepthTests{
    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
// Whoever read or wrote the pyramid before this build: cull kernels, read-backs.
constexpr vulkan::Scope kPyramidUsers{
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT};

vulkan::UniqueSampler createSampler(vulkan::Context& context, bool maxReduction,
                                    VkSamplerAddressMode address) {
  VkSamplerReductionModeCreateInfo reduction{VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO};
  reduction.reductionMode = VK_SAMPLER_REDUCTION_MODE_MAX;
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.pNext = maxReduction ? &reduction : nullptr;
  info.magFilter = info.minFilter = maxReduction ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = address;
  info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // depth 1: far
  info.minLod = 0.0f;
  info.maxLod = maxReduction ? 0.0f : VK_LOD_CLAMP_NONE;
  // The reduction samples at integer texel corners (2x + 1, 2y + 1): exact.
  info.unnormalizedCoordinates = maxReduction ? VK_TRUE : VK_FALSE;
  VkSampler sampler = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
  return vulkan::UniqueSampler(context.device(), sampler);
}

// MINMAX filtering, and LINEAR too: validation layers before the 1.3.2xx specs demand it
// for any linear sampler, whatever its reduction mode.
bool formatHasMinmax(const vulkan::Context& context, VkFormat format) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), format, &props);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_MINMAX_BIT |
                                    VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  return (props.optimalTilingFeatures & need) == need;
}

const vulkan::DescriptorBinding kSinglePassBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT, shader::kHiZMaxLevels},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};

// The shaders the pyramid builds with (hizPyramidShaderVariants lists them).
const vulkan::ShaderSource kReduceFetch{"hiz/hiz_reduce.comp", {}};
const vulkan::ShaderSource kReduceSampler{"hiz/hiz_reduce.comp", {{"HIZ_SAMPLER", ""}}};
const vulkan::ShaderSource kReduceGather{"hiz/hiz_reduce.comp", {{"HIZ_GATHER", ""}}};
const vulkan::ShaderSource kSinglePass{"hiz/hiz_single_pass.comp", {}};
// The blocked build: the top level's sources, then the other levels'.
const vulkan::ShaderSource kBlocksDepthRows{"hiz/hiz_blocks.comp", {{"HIZ_DEPTH_ROWS", ""}}};
const vulkan::ShaderSource kBlocksDepthRowsFull{
    "hiz/hiz_blocks.comp", {{"HIZ_DEPTH_ROWS", ""}, {"HIZ_FULL_RESOLUTION", ""}}};
const vulkan::ShaderSource kBlocksDepthGather{"hiz/hiz_blocks.comp", {{"HIZ_DEPTH_GATHER", ""}}};
const vulkan::ShaderSource kBlocksDepthFetch{"hiz/hiz_blocks.comp", {{"HIZ_DEPTH_FETCH", ""}}};
const vulkan::ShaderSource kBlocksSampler{"hiz/hiz_blocks.comp", {{"HIZ_SAMPLER", ""}}};
const vulkan::ShaderSource kBlocksFourTap{"hiz/hiz_blocks.comp", {}};
const vulkan::ShaderSource kTailSampler{"hiz/hiz_tail.comp", {{"HIZ_SAMPLER", ""}}};
const vulkan::ShaderSource kTailFourTap{"hiz/hiz_tail.comp", {}};

// Binding 0 the source (the depth rows buffer or an image), 1-3 the levels written.
const vulkan::DescriptorBinding kBlockBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
const vulkan::DescriptorBinding kBlockRowsBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
// The tail: binding 0 the level below its first, 1-8 its levels.
const vulkan::DescriptorBinding kTailBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
    {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
static_assert(std::size(kTailBindings) == 1 + shader::kHiZTailLevels);
// What a pool of the blocked build's sets holds per set (either binding 0).
const vulkan::DescriptorBinding kBlockPoolBindings[] = {
    {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT, shader::kHiZTailLevels}};
constexpr VkFormat kDepthRowsFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

}  // namespace

const char* toString(HiZReduction reduction) {
  switch (reduction) {
    case HiZReduction::Auto:
      return "auto";
    case HiZReduction::Blocked:
      return "blocked";
    case HiZReduction::SinglePass:
      return "single";
    case HiZReduction::Sampler:
      return "sampler";
    case HiZReduction::FourTap:
      return "fourtap";
  }
  return "?";
}

bool supportsMinmaxReduction(const vulkan::Context& context) {
  return context.info().optional.samplerFilterMinmax && formatHasMinmax(context, kPyramidFormat);
}

bool supportsMinmaxDepthReduction(const vulkan::Context& context) {
  return supportsMinmaxReduction(context) && formatHasMinmax(context, VK_FORMAT_D32_SFLOAT);
}

HiZPyramid::HiZPyramid(vulkan::Context& context, const vulkan::Image& depth,
                       const HiZOptions& options)
    : depth_(depth),
      layout_(bound::HiZLayout::make(depth.width(), depth.height(), options.fullResolution)) {
  if (!(vulkan::aspectOf(depth.format()) & VK_IMAGE_ASPECT_DEPTH_BIT))
    throw Error("HiZPyramid: the depth image must have a depth format (got format " +
                std::to_string(static_cast<int>(depth.format())) + ")");
  if (!(depth.desc().usage & VK_IMAGE_USAGE_SAMPLED_BIT))
    throw Error("HiZPyramid: the depth image must have SAMPLED usage (the pyramid reads it)");
  const bool minmax = supportsMinmaxReduction(context);
  if (options.reduction == HiZReduction::Sampler && !minmax)
    throw Error("HiZPyramid: min/max sampler reduction requested, but device '" +
                context.info().name +
                "' lacks samplerFilterMinmax or MINMAX and LINEAR filtering of R32_SFLOAT");
  // Auto: the fastest build measured on lavapipe (docs/algorithms/occlusion.md).
  blocked_ = options.reduction == HiZReduction::Blocked || options.reduction == HiZReduction::Auto;
  singlePass_ = options.reduction == HiZReduction::SinglePass;
  sampler_ =
      options.reduction == HiZReduction::Sampler || (blocked_ && minmax && !options.fourTapLevels);
  depthSampler_ = sampler_ && !blocked_ && formatHasMinmax(context, depth.format());
  lookup_ = options.lookup;
  legacy_ = options.legacyBuild;
  if (singlePass_ && layout_.levelCount > shader::kHiZMaxLevels)
    throw Error("HiZPyramid: " + std::to_string(layout_.levelCount) +
                " levels for a depth image of " + std::to_string(depth.width()) + "x" +
                std::to_string(depth.height()) + " exceed the single-pass build's " +
                std::to_string(shader::kHiZMaxLevels));

  image_ = vulkan::Image(
      context, {layout_.levelWidth(0), layout_.levelHeight(0), kPyramidFormat,
                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, layout_.levelCount});
  fetchSampler_ = createSampler(context, false, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  if (singlePass_) {
    createSinglePass(context);
    return;
  }
  if (blocked_) {
    createBlocked(context, options.readDepthImage);
    return;
  }
  if (depthSampler_)
    depthMaxSampler_ = createSampler(context, true, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
  if (sampler_)
    levelMaxSampler_ = createSampler(context, true, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  fetchProgram_ = std::make_unique<vulkan::ComputeProgram>(context, kReduceFetch, kBindings,
                                                           sizeof(shader::HiZReduceConstants));
  if (sampler_)
    samplerProgram_ = std::make_unique<vulkan::ComputeProgram>(context, kReduceSampler, kBindings,
                                                               sizeof(shader::HiZReduceConstants));
  // The sampler build's top level when the depth format has no min/max filtering: one
  // gather of the 2 x 2 pixels (nearest, white border) instead of four fetches.
  if (sampler_ && !depthSampler_ && !legacy_) {
    gatherProgram_ = std::make_unique<vulkan::ComputeProgram>(context, kReduceGather, kBindings,
                                                              sizeof(shader::HiZReduceConstants));
    depthMaxSampler_ = createSampler(context, false, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
  }
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, layout_.levelCount, kBindings);
  for (uint32_t level = 0; level < layout_.levelCount; ++level) {
    const vulkan::ComputeProgram& program = programOf(level);
    const VkDescriptorSet set = pool_->allocate(program.setLayout());
    vulkan::DescriptorWriter w;
    if (level == 0)
      w.sampledImage(0, depth.view(),
                     depthMaxSampler_ ? depthMaxSampler_.get() : fetchSampler_.get(),
                     kDepthReadLayout);
    else
      w.sampledImage(0, image_.mipView(level - 1),
                     sampler_ ? levelMaxSampler_.get() : fetchSampler_.get(), kPyramidLayout);
    w.storageImage(1, image_.mipView(level), kPyramidLayout).update(context.device(), set);
    sets_.push_back(set);
  }
}

HiZPyramid::~HiZPyramid() = default;

uint32_t HiZPyramid::dispatchCount() const {
  if (singlePass_) return 1;
  if (blocked_) return static_cast<uint32_t>(blockDispatches_.size());
  return layout_.levelCount;
}

const vulkan::ComputeProgram& HiZPyramid::programOf(uint32_t level) const {
  if (level == 0 && gatherProgram_ && layout_.baseShift == 1) return *gatherProgram_;
  return (level == 0 ? depthSampler_ : sampler_) ? *samplerProgram_ : *fetchProgram_;
}

shader::HiZParams HiZPyramid::params() const {
  shader::HiZParams p{};
  p.width = layout_.width;
  p.height = layout_.height;
  p.baseShift = layout_.baseShift;
  p.levelCount = layout_.levelCount;
  p.level0Width = layout_.levelWidth(0);
  p.level0Height = layout_.levelHeight(0);
  p.enabled = 1;
  p.lookup = lookup_ == bound::HiZLookup::Tight ? shader::kHiZLookupTight : shader::kHiZLookupPaper;
  return p;
}

void HiZPyramid::createSinglePass(vulkan::Context& context) {
  singlePassProgram_ = std::make_unique<vulkan::ComputeProgram>(
      context, kSinglePass, kSinglePassBindings, sizeof(shader::HiZSinglePassConstants));
  counter_ = vulkan::Buffer(context, 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, 1, kSinglePassBindings);
  singlePassSet_ = pool_->allocate(singlePassProgram_->setLayout());
  depthMaxSampler_ = createSampler(context, false, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
  const VkDescriptorImageInfo depthInfo{depthMaxSampler_.get(), depth_.view(), kDepthReadLayout};
  // Entries past the last level repeat it: the shader never writes them (level < count).
  std::vector<VkDescriptorImageInfo> levelInfos;
  for (uint32_t l = 0; l < shader::kHiZMaxLevels; ++l)
    levelInfos.push_back(
        {VK_NULL_HANDLE, image_.mipView(std::min(l, layout_.levelCount - 1)), kPyramidLayout});
  const VkDescriptorBufferInfo counterInfo = counter_.descriptor();
  VkWriteDescriptorSet w[3]{};
  for (auto& x : w) {
    x.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    x.dstSet = singlePassSet_;
    x.descriptorCount = 1;
  }
  w[0].dstBinding = 0;
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[0].pImageInfo = &depthInfo;
  w[1].dstBinding = 1;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  w[1].descriptorCount = shader::kHiZMaxLevels;
  w[1].pImageInfo = levelInfos.data();
  w[2].dstBinding = 2;
  w[2].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w[2].pBufferInfo = &counterInfo;
  vkUpdateDescriptorSets(context.device(), 3, w, 0, nullptr);
}

void HiZPyramid::recordSinglePass(VkCommandBuffer cmd) {
  // The finished-workgroup counter starts at 0 (earlier builds' atomics come first).
  vulkan::bufferBarrier(cmd, counter_, vulkan::scope::kComputeReadWrite,
                        vulkan::scope::kTransferWrite);
  vkCmdFillBuffer(cmd, counter_.handle(), 0, VK_WHOLE_SIZE, 0);
  vulkan::bufferBarrier(cmd, counter_, vulkan::scope::kTransferWrite,
                        vulkan::scope::kComputeReadWrite);
  shader::HiZSinglePassConstants c{};
  c.width = layout_.width;
  c.height = layout_.height;
  c.level0Width = layout_.levelWidth(0);
  c.level0Height = layout_.levelHeight(0);
  c.levelCount = layout_.levelCount;
  c.baseShift = layout_.baseShift;
  c.invWidth = 1.0f / float(layout_.width);
  c.invHeight = 1.0f / float(layout_.height);
  const VkExtent2D extent = updatedExtent(0);
  singlePassProgram_->dispatch(cmd, singlePassSet_, std::as_bytes(std::span(&c, 1)),
                               vulkan::groupCount(extent.width, shader::kHiZTile),
                               vulkan::groupCount(extent.height, shader::kHiZTile));
  vulkan::imageBarrier(cmd, image_, kPyramidLayout, kPyramidLayout, vulkan::scope::kComputeWrite,
                       {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT});
}

void HiZPyramid::record(VkCommandBuffer cmd, VkImageLayout depthLayout) {
  vulkan::imageBarrier(
      cmd, image_, built_ ? kPyramidLayout : VK_IMAGE_LAYOUT_UNDEFINED, kPyramidLayout,
      kPyramidUsers, singlePass_ ? vulkan::scope::kComputeReadWrite : vulkan::scope::kComputeWrite);
  if (blocked_) {
    recordBlocked(cmd, depthLayout);
    built_ = true;
    return;
  }
  vulkan::imageBarrier(cmd, depth_, depthLayout, kDepthReadLayout, kDepthWrite,
                       vulkan::scope::kComputeRead);
  if (singlePass_)
    recordSinglePass(cmd);
  else
    recordPerLevel(cmd);
  vulkan::imageBarrier(cmd, depth_, kDepthReadLayout, depthLayout, vulkan::scope::kComputeRead,
                       kDepthTests);
  built_ = true;
}

void HiZPyramid::createBlocked(vulkan::Context& context, bool readDepthImage) {
  const uint32_t rowTexels = (layout_.width + 3) / 4;
  VkFormatProperties rows;
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), kDepthRowsFormat, &rows);
  const bool copy =
      !readDepthImage && depth_.format() == VK_FORMAT_D32_SFLOAT &&
      (depth_.desc().usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) &&
      (rows.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT) &&
      uint64_t{rowTexels} * layout_.height <= context.info().limits.maxTexelBufferElements;
  const bool full = layout_.baseShift == 0;
  const vulkan::ShaderSource& top = copy   ? (full ? kBlocksDepthRowsFull : kBlocksDepthRows)
                                    : full ? kBlocksDepthFetch
                                           : kBlocksDepthGather;
  topProgram_ = std::make_unique<vulkan::ComputeProgram>(
      context, top, copy ? std::span(kBlockRowsBindings) : std::span(kBlockBindings),
      sizeof(shader::HiZBlockConstants));
  // Three levels a dispatch from the depth, then until the rest fit the tail's workgroup.
  for (uint32_t first = 0; first < layout_.levelCount; first += shader::kHiZBlockLevels) {
    const uint32_t rest = layout_.levelCount - first;
    if (first > 0 && rest <= shader::kHiZTailLevels &&
        layout_.levelWidth(first) * layout_.levelHeight(first) <= shader::kHiZTailTexels) {
      blockDispatches_.push_back({first, rest, true});
      break;
    }
    blockDispatches_.push_back({first, std::min(rest, shader::kHiZBlockLevels), false});
  }
  const size_t blockedDispatches = blockDispatches_.size() - (blockDispatches_.back().tail ? 1 : 0);
  if (blockedDispatches > 1)
    blockProgram_ = std::make_unique<vulkan::ComputeProgram>(
        context, sampler_ ? kBlocksSampler : kBlocksFourTap, kBlockBindings,
        sizeof(shader::HiZBlockConstants));
  if (blockDispatches_.back().tail)
    tailProgram_ =
        std::make_unique<vulkan::ComputeProgram>(context, sampler_ ? kTailSampler : kTailFourTap,
                                                 kTailBindings, sizeof(shader::HiZBlockConstants));
  if (copy) {
    depthRowTexels_ = rowTexels;
    depthRows_ =
        vulkan::Buffer(context, VkDeviceSize{rowTexels} * layout_.height * 16,
                       VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    info.buffer = depthRows_.handle();
    info.format = kDepthRowsFormat;
    info.range = VK_WHOLE_SIZE;
    VkBufferView view = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateBufferView(context.device(), &info, nullptr, &view));
    depthRowsView_ =
        vulkan::DeviceHandle<VkBufferView, vkDestroyBufferView>(context.device(), view);
  } else {
    depthMaxSampler_ = createSampler(context, false, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
  }
  if (sampler_)
    levelMaxSampler_ = createSampler(context, true, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, dispatchCount(), kBlockPoolBindings);
  for (uint32_t d = 0; d < dispatchCount(); ++d) {
    const BlockDispatch& b = blockDispatches_[d];
    const uint32_t first = b.firstLevel;
    const VkDescriptorSet set = pool_->allocate(blockProgramOf(b).setLayout());
    vulkan::DescriptorWriter w;
    if (d > 0)
      w.sampledImage(0, image_.mipView(first - 1),
                     sampler_ ? levelMaxSampler_.get() : fetchSampler_.get(), kPyramidLayout);
    else if (!copy)
      w.sampledImage(0, depth_.view(), full ? fetchSampler_.get() : depthMaxSampler_.get(),
                     kDepthReadLayout);
    // Levels past the last repeat it (the shader writes only pc.levels of them).
    for (uint32_t k = 0; k < (b.tail ? shader::kHiZTailLevels : shader::kHiZBlockLevels); ++k)
      w.storageImage(1 + k, image_.mipView(std::min(first + k, layout_.levelCount - 1)),
                     kPyramidLayout);
    w.update(context.device(), set);
    if (d == 0 && copy) {
      const VkBufferView view = depthRowsView_.get();
      VkWriteDescriptorSet rowsWrite{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      rowsWrite.dstSet = set;
      rowsWrite.dstBinding = 0;
      rowsWrite.descriptorCount = 1;
      rowsWrite.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
      rowsWrite.pTexelBufferView = &view;
      vkUpdateDescriptorSets(context.device(), 1, &rowsWrite, 0, nullptr);
    }
    sets_.push_back(set);
  }
}

const vulkan::ComputeProgram& HiZPyramid::blockProgramOf(const BlockDispatch& b) const {
  if (b.tail) return *tailProgram_;
  return b.firstLevel == 0 ? *topProgram_ : *blockProgram_;
}

void HiZPyramid::recordBlocked(VkCommandBuffer cmd, VkImageLayout depthLayout) {
  if (copiesDepth()) {
    // The depth pixels into the rows buffer (a copy: four per texel fetch afterwards), and
    // the depth image straight back to its layout for the next render pass.
    constexpr VkImageLayout kCopyLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    vulkan::imageBarrier(cmd, depth_, depthLayout, kCopyLayout, kDepthWrite,
                         vulkan::scope::kTransferRead);
    vulkan::bufferBarrier(cmd, depthRows_, vulkan::scope::kComputeRead,
                          vulkan::scope::kTransferWrite);  // the last build's reads
    VkBufferImageCopy region{};
    region.bufferRowLength = depthRowTexels_ * 4;
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.imageExtent = {layout_.width, layout_.height, 1};
    vkCmdCopyImageToBuffer(cmd, depth_.handle(), kCopyLayout, depthRows_.handle(), 1, &region);
    vulkan::bufferBarrier(cmd, depthRows_, vulkan::scope::kTransferWrite,
                          vulkan::scope::kComputeRead);
    vulkan::imageBarrier(cmd, depth_, kCopyLayout, depthLayout, vulkan::scope::kTransferRead,
                         kDepthTests);
  } else {
    vulkan::imageBarrier(cmd, depth_, depthLayout, kDepthReadLayout, kDepthWrite,
                         vulkan::scope::kComputeRead);
  }
  for (uint32_t d = 0; d < dispatchCount(); ++d) {
    const BlockDispatch& b = blockDispatches_[d];
    shader::HiZBlockConstants c{};
    c.firstLevel = b.firstLevel;
    c.levels = b.levels;
    c.srcWidth = d == 0 ? layout_.width : layout_.levelWidth(c.firstLevel - 1);
    c.srcHeight = d == 0 ? layout_.height : layout_.levelHeight(c.firstLevel - 1);
    c.level0Width = layout_.levelWidth(0);
    c.level0Height = layout_.levelHeight(0);
    c.rowTexels = depthRowTexels_;
    const VkExtent2D extent = updatedExtent(c.firstLevel);
    const std::span<const std::byte> push = std::as_bytes(std::span(&c, 1));
    if (b.tail) {
      // One workgroup; the levels above the first are small enough to write whole.
      c.srcWidth = extent.width;
      c.srcHeight = extent.height;
      tailProgram_->dispatch(cmd, sets_[d], push, 1, 1);
    } else {
      // Each invocation covers kHiZBlock texels of the first level per axis, and so the
      // updated part of the levels above it.
      blockProgramOf(b).dispatch(
          cmd, sets_[d], push,
          vulkan::groupCount(vulkan::groupCount(extent.width, shader::kHiZBlock),
                             shader::kHiZBlockGroup),
          vulkan::groupCount(vulkan::groupCount(extent.height, shader::kHiZBlock),
                             shader::kHiZBlockGroup));
    }
    vulkan::imageBarrier(cmd, image_, kPyramidLayout, kPyramidLayout, vulkan::scope::kComputeWrite,
                         {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT},
                         c.firstLevel, c.levels);
  }
  if (!copiesDepth())
    vulkan::imageBarrier(cmd, depth_, kDepthReadLayout, depthLayout, vulkan::scope::kComputeRead,
                         kDepthTests);
}

VkExtent2D HiZPyramid::updatedExtent(uint32_t level) const {
  const VkExtent2D all{layout_.levelWidth(level), layout_.levelHeight(level)};
  if (!built_ || legacy_) return all;
  // Texels whose footprint lies wholly in the padding are far in every build: the first
  // build wrote them, later builds skip them.
  const uint32_t shift = level + layout_.baseShift;
  auto covered = [&](uint32_t pixels) {
    return shift >= 32
               ? 1u
               : static_cast<uint32_t>((uint64_t{pixels} + (uint64_t{1} << shift) - 1) >> shift);
  };
  return {std::min(all.width, covered(layout_.width)),
          std::min(all.height, covered(layout_.height))};
}

void HiZPyramid::recordPerLevel(VkCommandBuffer cmd) {
  for (uint32_t level = 0; level < layout_.levelCount; ++level) {
    shader::HiZReduceConstants c{};
    if (level == 0) {
      c.srcWidth = layout_.width;
      c.srcHeight = layout_.height;
      c.srcBounded = 1;
      c.mode = layout_.baseShift == 0 ? shader::kHiZCopy : shader::kHiZReduce2x2;
    } else {
      c.srcWidth = layout_.levelWidth(level - 1);
      c.srcHeight = layout_.levelHeight(level - 1);
      c.srcBounded = 0;
      c.mode = shader::kHiZReduce2x2;
    }
    c.dstWidth = layout_.levelWidth(level);
    c.dstHeight = layout_.levelHeight(level);
    const VkExtent2D extent = updatedExtent(level);
    programOf(level).dispatch(cmd, sets_[level], std::as_bytes(std::span(&c, 1)),
                              vulkan::groupCount(extent.width, shader::kHiZGroupSize),
                              vulkan::groupCount(extent.height, shader::kHiZGroupSize));
    // This level is the next one's source (and the cull kernel's input).
    vulkan::imageBarrier(cmd, image_, kPyramidLayout, kPyramidLayout, vulkan::scope::kComputeWrite,
                         {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT},
                         level, 1);
  }
}

void HiZPyramid::build(vulkan::Context& context, VkImageLayout depthLayout) {
  context.submit([&](VkCommandBuffer cmd) { record(cmd, depthLayout); });
}

std::vector<std::vector<float>> HiZPyramid::readLevels(vulkan::Context& context) const {
  if (!built_) throw Error("HiZPyramid::readLevels: the pyramid was never built");
  std::vector<std::vector<float>> levels;
  for (uint32_t level = 0; level < layout_.levelCount; ++level) {
    const auto bytes = vulkan::readbackImage(context, image_, kPyramidLayout, level);
    std::vector<float> texels(bytes.size() / 4);
    std::memcpy(texels.data(), bytes.data(), texels.size() * 4);
    levels.push_back(std::move(texels));
  }
  return levels;
}

std::vector<vulkan::ShaderVariant> hizPyramidShaderVariants() {
  std::vector<vulkan::ShaderVariant> v;
  for (const vulkan::ShaderSource* s :
       {&kReduceFetch, &kReduceSampler, &kReduceGather, &kSinglePass, &kBlocksDepthRows,
        &kBlocksDepthRowsFull, &kBlocksDepthGather, &kBlocksDepthFetch, &kBlocksSampler,
        &kBlocksFourTap, &kTailSampler, &kTailFourTap})
    v.push_back(vulkan::ShaderVariant::file(*s));
  return v;
}

}  // namespace osd_cull::frame
