#include "osd_cull/osd/device_context.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"

#include <algorithm>

namespace osd_cull::osd {
namespace {

// Submissions in flight before submit() waits for the oldest one.
constexpr size_t kMaxSlots = 8;
// Descriptor sets per pool; a batch that needs more gets another pool.
constexpr uint32_t kSetsPerPool = 8;

const std::vector<vulkan::DescriptorBinding>& poolBindings() {
  static const std::vector<vulkan::DescriptorBinding> bindings = [] {
    std::vector<vulkan::DescriptorBinding> b;
    for (uint32_t i = 0; i < DeviceContext::kMaxBindingsPerSet; ++i)
      b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
    return b;
  }();
  return bindings;
}

}  // namespace

// One submission's command buffer, fence, descriptor pools and keep-alive list.
struct Batch::Slot {
  VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
  vulkan::UniqueFence fence;
  std::vector<std::unique_ptr<vulkan::DescriptorPool>> pools;
  size_t currentPool = 0;
  uint32_t setsInCurrentPool = 0;
  std::vector<std::shared_ptr<const void>> keepAlive;
  uint64_t ticket = 0;
  bool pending = false;
};

VkDescriptorSet Batch::allocateDescriptorSet(VkDescriptorSetLayout layout) {
  if (slot_.pools.empty() || slot_.setsInCurrentPool == kSetsPerPool) {
    if (!slot_.pools.empty()) ++slot_.currentPool;
    if (slot_.currentPool == slot_.pools.size())
      slot_.pools.push_back(
          std::make_unique<vulkan::DescriptorPool>(owner_.context(), kSetsPerPool, poolBindings()));
    slot_.setsInCurrentPool = 0;
  }
  ++slot_.setsInCurrentPool;
  return slot_.pools[slot_.currentPool]->allocate(layout);
}

void Batch::keepAlive(std::shared_ptr<const void> object) {
  slot_.keepAlive.push_back(std::move(object));
}

DeviceContext::DeviceContext(vulkan::Context& context) : context_(context) {
  VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  info.queueFamilyIndex = context.queueFamily();
  VkCommandPool pool = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateCommandPool(context.device(), &info, nullptr, &pool));
  commandPool_ = vulkan::UniqueCommandPool(context.device(), pool);
}

DeviceContext::~DeviceContext() {
  // Waiting cannot be skipped: the slots' command buffers, pools and kept-alive objects
  // must not be destroyed while the device still uses them.
  // Errors are ignored here: a destructor cannot throw, and the device is lost anyway.
  for (auto& slot : slots_) {
    if (!slot->pending) continue;
    const VkFence fence = slot->fence.get();
    vkWaitForFences(device(), 1, &fence, VK_TRUE, UINT64_MAX);
  }
}

Batch::Slot& DeviceContext::acquireSlot() {
  retireCompleted();
  for (auto& slot : slots_)
    if (!slot->pending) return *slot;
  if (slots_.size() < kMaxSlots) {
    auto slot = std::make_unique<Batch::Slot>();
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = commandPool_.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    OSD_CULL_VK(vkAllocateCommandBuffers(device(), &alloc, &slot->commandBuffer));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateFence(device(), &fenceInfo, nullptr, &fence));
    slot->fence = vulkan::UniqueFence(device(), fence);
    slots_.push_back(std::move(slot));
    return *slots_.back();
  }
  // Every slot is in flight: wait for the oldest submission.
  auto oldest = std::min_element(slots_.begin(), slots_.end(), [](const auto& a, const auto& b) {
    return a->ticket < b->ticket;
  });
  wait((*oldest)->ticket);
  return **oldest;
}

void DeviceContext::retire(Batch::Slot& slot) {
  const VkFence fence = slot.fence.get();
  OSD_CULL_VK(vkResetFences(device(), 1, &fence));
  for (auto& pool : slot.pools) pool->reset();
  slot.currentPool = 0;
  slot.setsInCurrentPool = 0;
  slot.keepAlive.clear();
  slot.pending = false;
}

void DeviceContext::retireCompleted() {
  for (auto& slot : slots_) {
    if (!slot->pending) continue;
    const VkResult status = vkGetFenceStatus(device(), slot->fence.get());
    if (status == VK_SUCCESS)
      retire(*slot);
    else if (status != VK_NOT_READY)
      OSD_CULL_VK(status);
  }
}

uint64_t DeviceContext::submit(const std::function<void(Batch&)>& record) {
  Batch::Slot& slot = acquireSlot();
  const uint64_t ticket = lastTicket_ + 1;
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  OSD_CULL_VK(vkBeginCommandBuffer(slot.commandBuffer, &begin));
  Batch batch(*this, slot, slot.commandBuffer, ticket);
  try {
    record(batch);
  } catch (...) {
    vkEndCommandBuffer(slot.commandBuffer);
    for (auto& pool : slot.pools) pool->reset();
    slot.currentPool = 0;
    slot.setsInCurrentPool = 0;
    slot.keepAlive.clear();
    throw;
  }
  OSD_CULL_VK(vkEndCommandBuffer(slot.commandBuffer));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &slot.commandBuffer;
  OSD_CULL_VK(vkQueueSubmit(context_.queue(), 1, &submit, slot.fence.get()));
  slot.ticket = ticket;
  slot.pending = true;
  lastTicket_ = ticket;
  return ticket;
}

void DeviceContext::wait(uint64_t ticket) {
  for (auto& slot : slots_) {
    if (!slot->pending || slot->ticket > ticket) continue;
    const VkFence fence = slot->fence.get();
    OSD_CULL_VK(vkWaitForFences(device(), 1, &fence, VK_TRUE, UINT64_MAX));
    retire(*slot);
  }
}

bool DeviceContext::isComplete(uint64_t ticket) {
  retireCompleted();
  return std::none_of(slots_.begin(), slots_.end(),
                      [&](const auto& s) { return s->pending && s->ticket <= ticket; });
}

}  // namespace osd_cull::osd
