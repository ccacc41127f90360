#pragma once
/// \file buffer.h
/// \brief A VkBuffer with its memory range.

#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/memory.h"

#include <cstddef>
#include <span>

namespace osd_cull::vulkan {

class Context;

/// \brief A buffer bound to a sub-allocated memory range. Usage always includes
/// TRANSFER_SRC and TRANSFER_DST so that any buffer can be uploaded to and read back, and
/// storage buffers get SHADER_DEVICE_ADDRESS when the device has bufferDeviceAddress, so
/// that shaders can read more than maxStorageBufferRange through deviceAddress().
/// Upload and Readback buffers are persistently mapped (mapped() is non-null).
class Buffer {
 public:
  Buffer() = default;
  /// \throws osd_cull::Error when size is 0 or the device refuses.
  Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
         MemoryUse use = MemoryUse::DeviceLocal);

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  VkBufferUsageFlags usage() const { return usage_; }
  /// \brief The buffer's device address (vkGetBufferDeviceAddress).
  /// \throws osd_cull::Error naming bufferDeviceAddress when the buffer has none (the device
  /// lacks the feature or the buffer is not a storage buffer).
  VkDeviceAddress deviceAddress() const;
  /// \brief The device's maxStorageBufferRange: the most one storage-buffer descriptor of
  /// this buffer may cover (checked by DescriptorWriter).
  VkDeviceSize maxStorageRange() const { return maxStorageRange_; }
  explicit operator bool() const { return static_cast<bool>(buffer_); }
  /// \brief Host pointer to the buffer's bytes, or nullptr if its memory is not mapped.
  std::byte* mapped() const { return allocation_.mapped(); }
  /// \brief Whether the memory is mapped and host-coherent (host writes need no flush): on
  /// unified-memory devices (lavapipe) device-local buffers are too.
  bool hostCoherent() const { return allocation_.hostCoherent(); }
  /// \brief The mapped bytes as an array of T (size()/sizeof(T) elements).
  /// \throws osd_cull::Error when the buffer is not host-visible.
  template <class T>
  std::span<T> mappedAs() const {
    return {reinterpret_cast<T*>(requireMapped()), static_cast<size_t>(size_ / sizeof(T))};
  }
  /// \brief Descriptor info for a range (whole buffer by default).
  VkDescriptorBufferInfo descriptor(VkDeviceSize offset = 0,
                                    VkDeviceSize range = VK_WHOLE_SIZE) const {
    return {buffer_.get(), offset, range};
  }

 private:
  std::byte* requireMapped() const;
  UniqueBuffer buffer_;
  Allocation allocation_;
  VkDeviceSize size_ = 0;
  VkBufferUsageFlags usage_ = 0;
  VkDeviceAddress address_ = 0;
  VkDeviceSize maxStorageRange_ = 0;
};

}  // namespace osd_cull::vulkan
