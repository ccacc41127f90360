#include "osd_cull/vk/memory.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"

#include <algorithm>
#include <optional>
#include <string>

namespace osd_cull::vulkan {

namespace {

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

}  // namespace

Allocation::Allocation(Allocation&& other) noexcept
    : allocator_(std::exchange(other.allocator_, nullptr)),
      block_(other.block_),
      offset_(other.offset_),
      size_(other.size_) {}

Allocation& Allocation::operator=(Allocation&& other) noexcept {
  if (this != &other) {
    if (allocator_)
      allocator_->release(static_cast<MemoryAllocator::Block*>(block_), offset_, size_);
    allocator_ = std::exchange(other.allocator_, nullptr);
    block_ = other.block_;
    offset_ = other.offset_;
    size_ = other.size_;
  }
  return *this;
}

Allocation::~Allocation() {
  if (allocator_) allocator_->release(static_cast<MemoryAllocator::Block*>(block_), offset_, size_);
}

VkDeviceMemory Allocation::memory() const {
  return block_ ? static_cast<MemoryAllocator::Block*>(block_)->memory.get() : VK_NULL_HANDLE;
}

std::byte* Allocation::mapped() const {
  auto* b = static_cast<MemoryAllocator::Block*>(block_);
  return b && b->mapped ? b->mapped + offset_ : nullptr;
}

bool Allocation::hostCoherent() const {
  auto* b = static_cast<MemoryAllocator::Block*>(block_);
  return b && b->mapped && b->coherent;
}

MemoryAllocator::MemoryAllocator(VkPhysicalDevice physicalDevice, VkDevice device,
                                 VkDeviceSize blockSize, bool deviceAddress)
    : device_(device), blockSize_(blockSize), deviceAddress_(deviceAddress) {
  vkGetPhysicalDeviceMemoryProperties(physicalDevice, &properties_);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physicalDevice, &props);
  nonCoherentAtomSize_ = std::max<VkDeviceSize>(1, props.limits.nonCoherentAtomSize);
}

MemoryAllocator::~MemoryAllocator() = default;

uint32_t MemoryAllocator::memoryType(uint32_t typeBits, MemoryUse use) const {
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
  switch (use) {
    case MemoryUse::DeviceLocal:
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUse::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUse::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  int best = -1;
  for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    const VkMemoryPropertyFlags flags = properties_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (best < 0) best = static_cast<int>(i);
  }
  if (best < 0)
    throw Error("no Vulkan memory type fits (type bits 0x" + std::to_string(typeBits) +
                ", needs host-visible coherent memory: " + (required ? "yes" : "no") + ")");
  return static_cast<uint32_t>(best);
}

MemoryAllocator::Block& MemoryAllocator::newBlock(uint32_t typeIndex, ResourceKind kind,
                                                  VkDeviceSize size, bool dedicated) {
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = size;
  info.memoryTypeIndex = typeIndex;
  // Buffers may be read through their device address (vulkan::Buffer::deviceAddress).
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (deviceAddress_ && kind == ResourceKind::Linear) info.pNext = &flags;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  OSD_CULL_VK(vkAllocateMemory(device_, &info, nullptr, &memory));
  auto block = std::make_unique<Block>();
  block->memory = UniqueDeviceMemory(device_, memory);
  block->typeIndex = typeIndex;
  block->kind = kind;
  block->size = size;
  block->dedicated = dedicated;
  if (properties_.memoryTypes[typeIndex].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    void* p = nullptr;
    OSD_CULL_VK(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &p));
    block->mapped = static_cast<std::byte*>(p);
    block->coherent = (properties_.memoryTypes[typeIndex].propertyFlags &
                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  }
  block->freeRanges.emplace(0, size);
  blocks_.push_back(std::move(block));
  return *blocks_.back();
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& requirements, MemoryUse use,
                                     ResourceKind kind) {
  const uint32_t typeIndex = memoryType(requirements.memoryTypeBits, use);
  const bool hostVisible =
      properties_.memoryTypes[typeIndex].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  // Host-visible ranges start and end on nonCoherentAtomSize so that any later flush of a
  // range never touches a neighbour.
  const VkDeviceSize alignment =
      std::max(requirements.alignment, hostVisible ? nonCoherentAtomSize_ : VkDeviceSize{1});
  const VkDeviceSize size = alignUp(std::max<VkDeviceSize>(requirements.size, 1), alignment);
  const uint32_t heap = properties_.memoryTypes[typeIndex].heapIndex;
  if (size > properties_.memoryHeaps[heap].size)
    throw Error("a Vulkan allocation of " + std::to_string(size) + " bytes exceeds memory heap " +
                std::to_string(heap) + " of " + std::to_string(properties_.memoryHeaps[heap].size) +
                " bytes (the device's memory heap size)");

  std::lock_guard lock(mutex_);
  // First fit: carve [start, start + size) out of the first free range that holds it.
  auto place = [&](Block& block) -> std::optional<VkDeviceSize> {
    for (auto it = block.freeRanges.begin(); it != block.freeRanges.end(); ++it) {
      const VkDeviceSize start = alignUp(it->first, alignment);
      const VkDeviceSize end = it->first + it->second;
      if (start + size > end) continue;
      const VkDeviceSize freeOffset = it->first;
      block.freeRanges.erase(it);
      if (start > freeOffset) block.freeRanges.emplace(freeOffset, start - freeOffset);
      if (start + size < end) block.freeRanges.emplace(start + size, end - start - size);
      ++block.live;
      return start;
    }
    return std::nullopt;
  };

  Allocation out;
  out.allocator_ = this;
  out.size_ = size;
  if (size <= blockSize_ / 2) {
    for (auto& block : blocks_) {
      if (block->dedicated || block->typeIndex != typeIndex || block->kind != kind) continue;
      if (auto offset = place(*block)) {
        out.offset_ = *offset;
        out.block_ = block.get();
        return out;
      }
    }
  }
  const bool dedicated = size > blockSize_ / 2;
  Block& block = newBlock(typeIndex, kind, dedicated ? size : blockSize_, dedicated);
  out.offset_ = *place(block);
  out.block_ = &block;
  return out;
}

void MemoryAllocator::release(Block* block, VkDeviceSize offset, VkDeviceSize size) {
  std::lock_guard lock(mutex_);
  --block->live;
  if (block->dedicated) {
    std::erase_if(blocks_, [&](const std::unique_ptr<Block>& b) { return b.get() == block; });
    return;
  }
  auto [it, inserted] = block->freeRanges.emplace(offset, size);
  (void)inserted;
  // Coalesce with the next and previous free ranges.
  auto next = std::next(it);
  if (next != block->freeRanges.end() && it->first + it->second == next->first) {
    it->second += next->second;
    block->freeRanges.erase(next);
  }
  if (it != block->freeRanges.begin()) {
    auto prev = std::prev(it);
    if (prev->first + prev->second == it->first) {
      prev->second += it->second;
      block->freeRanges.erase(it);
    }
  }
}

MemoryAllocator::Stats MemoryAllocator::stats() const {
  std::lock_guard lock(mutex_);
  Stats s;
  s.blocks = blocks_.size();
  for (const auto& b : blocks_) {
    s.reservedBytes += b->size;
    VkDeviceSize free = 0;
    for (const auto& [o, sz] : b->freeRanges) free += sz;
    s.usedBytes += b->size - free;
    s.allocations += b->live;
  }
  return s;
}

}  // namespace osd_cull::vulkan
