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

}  // namespace

const char* toString(HiZReduction reduction) {
  switch (reduction) {
    case HiZReduction::Auto:
      return "auto";
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
  // Auto: the fastest build measured on lavapipe (docs/results/frame-cost.md), where the
  // cost is per texel accessed, not per dispatch.
  singlePass_ = options.reduction == HiZReduction::SinglePass ||
                (options.reduction == HiZReduction::Auto && !minmax);
  sampler_ = options.reduction == HiZReduction::Sampler ||
             (options.reduction == HiZReduction::Auto && minmax);
  depthSampler_ = sampler_ && formatHasMinmax(context, depth.format());
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
  vulkan::imageBarrier(cmd, depth_, depthLayout, kDepthReadLayout, kDepthWrite,
                       vulkan::scope::kComputeRead);
  vulkan::imageBarrier(
      cmd, image_, built_ ? kPyramidLayout : VK_IMAGE_LAYOUT_UNDEFINED, kPyramidLayout,
      kPyramidUsers, singlePass_ ? vulkan::scope::kComputeReadWrite : vulkan::scope::kComputeWrite);
  if (singlePass_)
    recordSinglePass(cmd);
  else
    recordPerLevel(cmd);
  vulkan::imageBarrier(cmd, depth_, kDepthReadLayout, depthLayout, vulkan::scope::kComputeRead,
                       kDepthTests);
  built_ = true;
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
       {&kReduceFetch, &kReduceSampler, &kReduceGather, &kSinglePass})
    v.push_back(vulkan::ShaderVariant::file(*s));
  return v;
}

}  // namespace osd_cull::frame
