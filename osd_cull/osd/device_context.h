#pragma once
/// \file device_context.h
/// \brief The DEVICE_CONTEXT of osd_cull's OpenSubdiv-style Vulkan backend: a vulkan::Context
/// plus a stream of asynchronous submissions that can be waited on one by one.
///
/// Osd::Mesh passes a `DEVICE_CONTEXT*` to every backend call (Create, UpdateData,
/// EvalStencils, Synchronize). OpenGL needs no such object; Vulkan does, because work is
/// recorded into command buffers and completes asynchronously. Each submission made
/// through a DeviceContext gets a ticket (1, 2, 3, ...); wait(ticket) blocks until that
/// submission and every earlier one of this DeviceContext have finished, by waiting on
/// their fences — never on the whole device.

#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/handle.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace osd_cull::osd {

class DeviceContext;

/// \brief A command buffer being recorded for one DeviceContext submission, with
/// descriptor sets and keep-alive references that live until the submission completes.
class Batch {
 public:
  VkCommandBuffer commandBuffer() const { return commandBuffer_; }
  /// \brief The ticket this batch's submission will have.
  uint64_t ticket() const { return ticket_; }
  /// \brief A descriptor set of `layout` (storage-buffer bindings only, at most
  /// DeviceContext::kMaxBindingsPerSet), valid until the submission completes.
  VkDescriptorSet allocateDescriptorSet(VkDescriptorSetLayout layout);
  /// \brief Keeps `object` alive until the submission completes (pipelines of temporary
  /// evaluators, staging buffers).
  void keepAlive(std::shared_ptr<const void> object);

 private:
  friend class DeviceContext;
  struct Slot;
  Batch(DeviceContext& owner, Slot& slot, VkCommandBuffer cmd, uint64_t ticket)
      : owner_(owner), slot_(slot), commandBuffer_(cmd), ticket_(ticket) {}
  DeviceContext& owner_;
  Slot& slot_;
  VkCommandBuffer commandBuffer_;
  uint64_t ticket_;
};

/// \brief vulkan::Context + asynchronous, individually awaitable submissions (see file comment).
///
/// Not thread-safe. The vulkan::Context must outlive it; every backend object created with
/// a DeviceContext (buffers, tables, evaluators) must be destroyed before it.
class DeviceContext {
 public:
  /// Storage-buffer bindings a descriptor set allocated from a Batch may have.
  static constexpr uint32_t kMaxBindingsPerSet = 12;

  explicit DeviceContext(vulkan::Context& context);
  DeviceContext(const DeviceContext&) = delete;
  DeviceContext& operator=(const DeviceContext&) = delete;
  /// \brief Waits for this DeviceContext's own submissions, then frees its objects.
  ~DeviceContext();

  vulkan::Context& context() const { return context_; }
  VkDevice device() const { return context_.device(); }

  /// \brief Records commands with `record` and submits them without waiting.
  /// \returns the submission's ticket.
  uint64_t submit(const std::function<void(Batch&)>& record);

  /// \brief Blocks until submission `ticket` and all earlier ones have completed
  /// (returns at once for 0 or for tickets already known complete).
  void wait(uint64_t ticket);
  /// \brief Blocks until every submission made so far has completed.
  void waitAll() { wait(lastTicket_); }
  /// \brief True when `ticket` is known to be complete (polls the fences).
  bool isComplete(uint64_t ticket);
  /// \brief The ticket of the latest submission (0 before the first).
  uint64_t lastTicket() const { return lastTicket_; }

  /// \brief An object shared by everything on this DeviceContext under `key` (compiled
  /// kernels, for example), made by `make` on first use.
  template <class T, class Make>
  std::shared_ptr<T> shared(const std::string& key, Make&& make) {
    auto it = shared_.find(key);
    if (it == shared_.end()) it = shared_.emplace(key, std::shared_ptr<T>(make())).first;
    return std::static_pointer_cast<T>(it->second);
  }

 private:
  friend class Batch;
  Batch::Slot& acquireSlot();
  void retire(Batch::Slot& slot);
  void retireCompleted();

  vulkan::Context& context_;
  vulkan::UniqueCommandPool commandPool_;
  std::vector<std::unique_ptr<Batch::Slot>> slots_;
  uint64_t lastTicket_ = 0;
  std::map<std::string, std::shared_ptr<void>> shared_;
};

}  // namespace osd_cull::osd
