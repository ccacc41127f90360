#include "osd_cull/vk/descriptors.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

#include <map>

namespace osd_cull::vulkan {

UniqueDescriptorSetLayout createDescriptorSetLayout(Context& context,
                                                    std::span<const DescriptorBinding> bindings) {
  std::vector<VkDescriptorSetLayoutBinding> b;
  for (const auto& d : bindings) b.push_back({d.binding, d.type, d.count, d.stages, nullptr});
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = static_cast<uint32_t>(b.size());
  info.pBindings = b.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateDescriptorSetLayout(context.device(), &info, nullptr, &layout));
  return UniqueDescriptorSetLayout(context.device(), layout);
}

DescriptorPool::DescriptorPool(Context& context, uint32_t maxSets,
                               std::span<const DescriptorBinding> perSet, bool freeable)
    : device_(context.device()) {
  std::map<VkDescriptorType, uint32_t> counts;
  for (const auto& d : perSet) counts[d.type] += d.count * maxSets;
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, n] : counts) sizes.push_back({type, n});
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.maxSets = maxSets;
  if (freeable) info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  info.poolSizeCount = static_cast<uint32_t>(sizes.size());
  info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateDescriptorPool(device_, &info, nullptr, &pool));
  pool_ = UniqueDescriptorPool(device_, pool);
}

VkDescriptorSet DescriptorPool::allocate(VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  info.descriptorPool = pool_.get();
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  OSD_CULL_VK(vkAllocateDescriptorSets(device_, &info, &set));
  return set;
}

void DescriptorPool::reset() { OSD_CULL_VK(vkResetDescriptorPool(device_, pool_.get(), 0)); }

void DescriptorPool::free(VkDescriptorSet set) {
  OSD_CULL_VK(vkFreeDescriptorSets(device_, pool_.get(), 1, &set));
}

DescriptorWriter& DescriptorWriter::buffer(uint32_t binding, const Buffer& buffer,
                                           VkDescriptorType type, VkDeviceSize offset,
                                           VkDeviceSize range) {
  const VkDeviceSize covered = range == VK_WHOLE_SIZE ? buffer.size() - offset : range;
  if ((type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER ||
       type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC) &&
      covered > buffer.maxStorageRange())
    throw Error("descriptor binding " + std::to_string(binding) + ": a storage buffer range of " +
                std::to_string(covered) + " bytes exceeds the device's maxStorageBufferRange of " +
                std::to_string(buffer.maxStorageRange()) +
                " bytes (read it through a buffer device address or split it)");
  writes_.push_back({binding, type, buffer.descriptor(offset, range), {}, false});
  return *this;
}

DescriptorWriter& DescriptorWriter::storageImage(uint32_t binding, VkImageView view,
                                                 VkImageLayout layout) {
  writes_.push_back(
      {binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, {}, {VK_NULL_HANDLE, view, layout}, true});
  return *this;
}

DescriptorWriter& DescriptorWriter::sampledImage(uint32_t binding, VkImageView view,
                                                 VkSampler sampler, VkImageLayout layout) {
  writes_.push_back(
      {binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, {}, {sampler, view, layout}, true});
  return *this;
}

void DescriptorWriter::update(VkDevice device, VkDescriptorSet set) const {
  std::vector<VkWriteDescriptorSet> w;
  w.reserve(writes_.size());
  for (const auto& d : writes_) {
    VkWriteDescriptorSet x{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    x.dstSet = set;
    x.dstBinding = d.binding;
    x.descriptorCount = 1;
    x.descriptorType = d.type;
    if (d.isImage)
      x.pImageInfo = &d.image;
    else
      x.pBufferInfo = &d.buffer;
    w.push_back(x);
  }
  vkUpdateDescriptorSets(device, static_cast<uint32_t>(w.size()), w.data(), 0, nullptr);
}

}  // namespace osd_cull::vulkan
