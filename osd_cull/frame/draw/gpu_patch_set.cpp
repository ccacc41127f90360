#include "osd_cull/frame/draw/gpu_patch_set.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/limits.h"
#include "osd_cull/vk/transfer.h"

#include <shared/point_source.h>

#include <algorithm>
#include <numeric>

namespace osd_cull::frame {

std::span<const vulkan::DescriptorBinding> patchSetBindings() {
  static const vulkan::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_ALL},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_ALL},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_ALL},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_ALL}};
  return bindings;
}

const char* pointsByAddressDefine(const vulkan::Context& context) {
  return context.info().optional.bufferDeviceAddress ? "1" : "0";
}

namespace {

// Without device addresses the points are bound as one descriptor.
void checkPointRange(const vulkan::Context& context, VkDeviceSize bytes, const std::string& what) {
  if (bytes > context.info().limits.maxStorageBufferRange)
    vulkan::checkStorageBufferRange(
        context, bytes,
        what + " (the device lacks bufferDeviceAddress, which would lift this limit)");
}

}  // namespace

std::vector<float> packPoints(std::span<const glm::dvec3> points) {
  std::vector<float> out(points.size() * 4);
  for (size_t i = 0; i < points.size(); ++i) {
    out[4 * i + 0] = static_cast<float>(points[i].x);
    out[4 * i + 1] = static_cast<float>(points[i].y);
    out[4 * i + 2] = static_cast<float>(points[i].z);
    out[4 * i + 3] = 1.0f;
  }
  return out;
}

GpuPatchSet::GpuPatchSet(vulkan::Context& context, const PatchSet& patches)
    : bezierCount_(patches.bezierCount),
      gregoryCount_(patches.gregoryCount),
      pointCount_(static_cast<uint32_t>(patches.points.size())),
      transitionEdges_(frame::hasTransitionEdges(patches)),
      pointsByAddress_(context.info().optional.bufferDeviceAddress) {
  const uint32_t n = patches.patchCount();
  const size_t expectedPoints =
      size_t{patches.bezierCount} * kBezierPoints + size_t{patches.gregoryCount} * kGregoryPoints;
  if (patches.points.size() != expectedPoints || patches.params.size() != n)
    throw Error("GpuPatchSet: PatchSet '" + patches.source +
                "' is inconsistent: " + std::to_string(patches.points.size()) + " points and " +
                std::to_string(patches.params.size()) + " params for " +
                std::to_string(patches.bezierCount) + " Bezier and " +
                std::to_string(patches.gregoryCount) + " Gregory patches (expected " +
                std::to_string(expectedPoints) + " points)");
  // Buffers are never empty (Vulkan forbids size 0); an empty set draws nothing.
  const size_t pointBytes =
      std::max<size_t>(16, patches.points.size() * kOwnPointStride * sizeof(float));
  const std::string name = "GpuPatchSet '" + patches.source + "': ";
  if (!pointsByAddress_)
    checkPointRange(context, pointBytes,
                    name + "the " + std::to_string(pointCount_) + " control points");
  vulkan::checkStorageBufferRange(context, size_t{n} * 8, name + "the PatchParams");
  vulkan::checkStorageBufferRange(context, size_t{n} * 4, name + "the draw list");
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  points_ = vulkan::Buffer(context, pointBytes, storage);
  params_ = vulkan::Buffer(context, std::max<size_t>(8, size_t{n} * 8), storage);
  drawList_ = vulkan::Buffer(context, std::max<size_t>(4, size_t{n} * 4), storage);
  tessLevels_ = vulkan::Buffer(context, std::max<size_t>(8, size_t{n} * 8), storage);
  tessLevelSlots_ = 1;
  if (pointsByAddress_) {
    pointRecord_ =
        vulkan::Buffer(context, sizeof(shader::PointSource), storage, vulkan::MemoryUse::Upload);
    writePointRecord();
  }
  setLayout_ = vulkan::createDescriptorSetLayout(context, patchSetBindings());
  pool_ =
      std::make_unique<vulkan::DescriptorPool>(context, 1 + kMaxDrawListSets, patchSetBindings(),
                                               /*freeable=*/true);
  set_ = pool_->allocate(setLayout_.get());
  writeDescriptorSet(context.device(), set_, drawList_);
  if (n == 0) return;
  updatePoints(context, patches.points);
  std::vector<uint32_t> params(2 * size_t{n});
  for (uint32_t p = 0; p < n; ++p) {
    params[2 * p] = patches.params[p].field0;
    params[2 * p + 1] = patches.params[p].field1;
  }
  vulkan::upload<uint32_t>(context, params_, params);
  std::vector<uint32_t> list(n);
  std::iota(list.begin(), list.end(), 0u);
  vulkan::upload<uint32_t>(context, drawList_, list);
}

VkDescriptorSet GpuPatchSet::descriptorSetWithDrawList(vulkan::Context& context,
                                                       const vulkan::Buffer& drawList) {
  if (extraSets_ >= kMaxDrawListSets)
    throw Error("GpuPatchSet: more than " + std::to_string(kMaxDrawListSets) +
                " draw-list descriptor sets requested");
  const VkDescriptorSet set = pool_->allocate(setLayout_.get());
  ++extraSets_;
  extraSetLists_.emplace_back(set, &drawList);
  writeDescriptorSet(context.device(), set, drawList);
  return set;
}

void GpuPatchSet::releaseDrawListSet(VkDescriptorSet set) {
  const auto it = std::find_if(extraSetLists_.begin(), extraSetLists_.end(),
                               [&](const auto& entry) { return entry.first == set; });
  if (it == extraSetLists_.end()) return;
  extraSetLists_.erase(it);
  --extraSets_;
  pool_->free(set);
}

void GpuPatchSet::reserveTessLevelSlots(vulkan::Context& context, uint32_t slots) {
  if (slots <= tessLevelSlots_) return;
  const size_t bytes = size_t{slots} * patchCount() * 8;
  vulkan::checkStorageBufferRange(context, bytes,
                                  "GpuPatchSet: the tessellation levels of " +
                                      std::to_string(slots) + " instances");
  tessLevels_ =
      vulkan::Buffer(context, std::max<size_t>(8, bytes), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  tessLevelSlots_ = slots;
  writeDescriptorSet(context.device(), set_, drawList_);
  for (const auto& [set, list] : extraSetLists_) writeDescriptorSet(context.device(), set, *list);
}

void GpuPatchSet::readPointsFrom(vulkan::Context& context, const vulkan::Buffer& points,
                                 uint32_t stride, uint32_t offset) {
  const uint64_t needed = (uint64_t{offset} + uint64_t{pointCount_} * stride) * sizeof(float);
  if (stride < 3 || points.size() < needed)
    throw Error("GpuPatchSet::readPointsFrom: " + std::to_string(pointCount_) +
                " points of stride " + std::to_string(stride) + " from float " +
                std::to_string(offset) + " need " + std::to_string(needed) +
                " bytes (stride >= 3), the buffer has " + std::to_string(points.size()));
  if (!pointsByAddress_)
    checkPointRange(context, points.size(), "GpuPatchSet::readPointsFrom: the point buffer");
  pointSource_ = &points;
  pointStride_ = stride;
  pointOffset_ = offset;
  if (pointsByAddress_)
    writePointRecord();  // every set bound to the record follows
  else
    vulkan::DescriptorWriter().buffer(0, points).update(context.device(), set_);
}

void GpuPatchSet::writePointRecord() {
  const VkDeviceAddress address = pointSource_->deviceAddress();
  const shader::PointSource record{static_cast<uint32_t>(address),
                                   static_cast<uint32_t>(address >> 32), 0u, 0u};
  pointRecord_.mappedAs<shader::PointSource>()[0] = record;
}

void GpuPatchSet::writeDescriptorSet(VkDevice device, VkDescriptorSet set,
                                     const vulkan::Buffer& drawList) const {
  vulkan::DescriptorWriter()
      .buffer(0, pointBinding())
      .buffer(1, params_)
      .buffer(2, drawList)
      .buffer(3, tessLevels_)
      .update(device, set);
}

void GpuPatchSet::updatePoints(vulkan::Context& context, std::span<const glm::dvec3> points) {
  if (pointSource_ != &points_)
    throw Error(
        "GpuPatchSet::updatePoints: the set reads its points from another buffer (readPointsFrom)");
  if (points.size() != pointCount_)
    throw Error("GpuPatchSet::updatePoints: got " + std::to_string(points.size()) +
                " points, the set has " + std::to_string(pointCount_));
  // Converted straight into staging memory, piece by piece (no full-size float copy); a
  // piece may end inside a point.
  vulkan::uploadGenerated(
      context, points_, points.size() * kOwnPointStride * sizeof(float),
      [&](std::span<std::byte> chunk, VkDeviceSize offset) {
        auto* out = reinterpret_cast<float*>(chunk.data());
        size_t f = static_cast<size_t>(offset / sizeof(float));
        for (size_t i = 0; i < chunk.size() / sizeof(float); ++i, ++f)
          out[i] = static_cast<float>(points[f / kOwnPointStride][int(f % kOwnPointStride)]);
      });
}

}  // namespace osd_cull::frame
