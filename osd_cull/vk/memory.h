#pragma once
/// \file memory.h
/// \brief Device memory sub-allocated from a few large blocks.
///
/// Vulkan limits the number of vkAllocateMemory calls and each one is slow, so buffers
/// and images take ranges of large blocks (64 MiB by default). Buffers and images live in
/// different blocks, which keeps bufferImageGranularity out of the picture. A request
/// larger than half a block gets a block of its own, freed when the request is.

#include "osd_cull/vk/handle.h"

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace osd_cull::vulkan {

/// \brief What the host does with a resource's memory.
enum class MemoryUse {
  DeviceLocal,  ///< GPU only (filled by copies or shaders)
  Upload,       ///< host writes, GPU reads (staging, per-frame constants): host-visible, coherent
  Readback,     ///< GPU writes, host reads: host-visible, coherent, cached when available
};

/// \brief Whether a resource is a buffer (linear) or an optimally tiled image.
enum class ResourceKind { Linear, Optimal };

class MemoryAllocator;

/// \brief A range of a memory block; returns itself to the allocator when destroyed.
class Allocation {
 public:
  Allocation() = default;
  Allocation(const Allocation&) = delete;
  Allocation& operator=(const Allocation&) = delete;
  Allocation(Allocation&& other) noexcept;
  Allocation& operator=(Allocation&& other) noexcept;
  ~Allocation();

  VkDeviceMemory memory() const;
  VkDeviceSize offset() const { return offset_; }
  VkDeviceSize size() const { return size_; }
  /// \brief Host pointer to the start of this range, or nullptr if not host-visible.
  std::byte* mapped() const;
  /// \brief Whether host writes through mapped() are visible to the device without a flush
  /// (host-visible and HOST_COHERENT memory).
  bool hostCoherent() const;
  explicit operator bool() const { return allocator_ != nullptr; }

 private:
  friend class MemoryAllocator;
  MemoryAllocator* allocator_ = nullptr;
  void* block_ = nullptr;  // MemoryAllocator::Block
  VkDeviceSize offset_ = 0;
  VkDeviceSize size_ = 0;
};

/// \brief Sub-allocates device memory from large blocks (first fit, coalescing free list).
/// Thread-safe.
class MemoryAllocator {
 public:
  /// \brief `deviceAddress`: allocate buffer memory with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT
  /// (needs the bufferDeviceAddress feature enabled), so any buffer may have an address.
  MemoryAllocator(VkPhysicalDevice physicalDevice, VkDevice device, VkDeviceSize blockSize,
                  bool deviceAddress = false);
  MemoryAllocator(const MemoryAllocator&) = delete;
  MemoryAllocator& operator=(const MemoryAllocator&) = delete;
  ~MemoryAllocator();

  /// \brief Memory for a resource with these requirements.
  /// \throws osd_cull::Error when no memory type fits `use`, the request is larger than the
  /// memory heap of its type (named, before any allocation) or the device is out of memory.
  Allocation allocate(const VkMemoryRequirements& requirements, MemoryUse use, ResourceKind kind);

  /// \brief Counts for reports and tests.
  struct Stats {
    size_t blocks = 0;
    VkDeviceSize reservedBytes = 0;  ///< sum of block sizes
    VkDeviceSize usedBytes = 0;      ///< sum of live allocation sizes (after alignment)
    size_t allocations = 0;          ///< live allocations
  };
  Stats stats() const;

  /// \brief Index of the memory type chosen for `use` among `typeBits`.
  uint32_t memoryType(uint32_t typeBits, MemoryUse use) const;

 private:
  friend class Allocation;
  struct Block {
    UniqueDeviceMemory memory;
    uint32_t typeIndex = 0;
    ResourceKind kind = ResourceKind::Linear;
    VkDeviceSize size = 0;
    bool dedicated = false;
    std::byte* mapped = nullptr;
    bool coherent = false;                            // mapped and HOST_COHERENT
    std::map<VkDeviceSize, VkDeviceSize> freeRanges;  // offset -> size
    size_t live = 0;
  };
  Block& newBlock(uint32_t typeIndex, ResourceKind kind, VkDeviceSize size, bool dedicated);
  void release(Block* block, VkDeviceSize offset, VkDeviceSize size);

  VkDevice device_;
  VkPhysicalDeviceMemoryProperties properties_{};
  VkDeviceSize blockSize_;
  VkDeviceSize nonCoherentAtomSize_;
  bool deviceAddress_ = false;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Block>> blocks_;
};

}  // namespace osd_cull::vulkan
