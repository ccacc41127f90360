#pragma once
/// \file descriptors.h
/// \brief Descriptor set layouts, pools and writes.

#include "osd_cull/vk/handle.h"

#include <cstdint>
#include <span>
#include <vector>

namespace osd_cull::vulkan {

class Context;
class Buffer;

/// \brief One binding of a descriptor set layout.
struct DescriptorBinding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  VkShaderStageFlags stages = VK_SHADER_STAGE_ALL;
  uint32_t count = 1;
};

/// \brief A descriptor set layout from a list of bindings.
UniqueDescriptorSetLayout createDescriptorSetLayout(Context& context,
                                                    std::span<const DescriptorBinding> bindings);

/// \brief A descriptor pool for up to `maxSets` sets of the given layouts' bindings.
/// Sets are freed all at once with reset() or when the pool goes away.
class DescriptorPool {
 public:
  /// \brief Room for `maxSets` sets, each with at most the bindings given; with `freeable`,
  /// sets can be returned one by one (free()).
  DescriptorPool(Context& context, uint32_t maxSets, std::span<const DescriptorBinding> perSet,
                 bool freeable = false);
  /// \brief A new set of `layout`.
  /// \throws osd_cull::Error when the pool is exhausted.
  VkDescriptorSet allocate(VkDescriptorSetLayout layout);
  /// \brief Frees every set allocated from the pool.
  void reset();
  /// \brief Returns one set to a pool made `freeable`.
  void free(VkDescriptorSet set);
  VkDescriptorPool handle() const { return pool_.get(); }

 private:
  VkDevice device_;
  UniqueDescriptorPool pool_;
};

/// \brief Collects descriptor writes for one set, then applies them with update().
class DescriptorWriter {
 public:
  /// \brief A storage or uniform buffer range (whole buffer by default).
  /// \throws osd_cull::Error when a storage-buffer range exceeds the device's
  /// maxStorageBufferRange (such buffers must be read through a device address or split),
  /// before anything is written or recorded.
  DescriptorWriter& buffer(uint32_t binding, const Buffer& buffer,
                           VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                           VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
  /// \brief A storage image view in `layout` (GENERAL for storage images).
  DescriptorWriter& storageImage(uint32_t binding, VkImageView view,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
  /// \brief A combined image sampler.
  DescriptorWriter& sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  /// \brief Writes everything collected into `set`.
  void update(VkDevice device, VkDescriptorSet set) const;

 private:
  struct Write {
    uint32_t binding;
    VkDescriptorType type;
    VkDescriptorBufferInfo buffer;
    VkDescriptorImageInfo image;
    bool isImage;
  };
  std::vector<Write> writes_;
};

}  // namespace osd_cull::vulkan
