#pragma once
/// \file context.h
/// \brief The Vulkan instance, device and queue osd_cull works with: its own headless one
/// (device choice, feature checks, validation) or the application's, adopted without
/// ownership (external_device.h); memory and one-shot command submission either way.

#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/memory.h"
#include "osd_cull/vk/validation.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace osd_cull::vulkan {

struct DeviceInfo;

/// \brief How to create a Context.
struct ContextOptions {
  /// Device to use: an index into the list of devices, or a case-insensitive substring of
  /// the device name ("llvmpipe", "NVIDIA"). Empty: $OSD_CULL_DEVICE, and if that is unset
  /// too, the first discrete GPU, else the first integrated GPU, else the first virtual
  /// GPU, else the first CPU device (lavapipe), else device 0 (selectDevice()).
  std::string device;
  /// Receives one line naming the device chosen and why. Unset: the line goes to stderr.
  std::function<void(const std::string&)> log;
  /// Enables VK_LAYER_KHRONOS_validation with synchronization validation; warnings and
  /// errors go to `validationLog`.
  bool validation = false;
  /// Where validation messages are recorded (created when null and validation is on).
  /// Kept outside the Context so messages emitted while it is destroyed are seen too.
  std::shared_ptr<ValidationLog> validationLog;
  /// Also print validation messages to stderr as they arrive.
  bool printValidationMessages = true;
  /// Size of the memory blocks resources are sub-allocated from.
  VkDeviceSize memoryBlockSize = VkDeviceSize{64} << 20;
  /// For tests of limit checks: edits the device facts after they are read and before the
  /// device is created, e.g. a small maxStorageBufferRange or a hidden optional feature (a
  /// hidden feature is not enabled). Lowering a limit or hiding a feature is always safe;
  /// raising one makes the Context promise what the device cannot do.
  std::function<void(DeviceInfo&)> adjustDeviceInfo;
  /// Further instance extensions to enable, e.g. a window system's surface extensions
  /// (glfwGetRequiredInstanceExtensions) for a viewer. Missing ones are an error naming them.
  std::vector<std::string> instanceExtensions;
  /// Further device extensions to enable, e.g. VK_KHR_swapchain. The device check names
  /// any the chosen device lacks.
  std::vector<std::string> deviceExtensions;
};

/// \brief Optional device features; enabled when the device has them.
struct OptionalFeatures {
  bool shaderFloat64 = false;
  bool samplerFilterMinmax = false;
  bool bufferDeviceAddress = false;
  bool hostQueryReset = false;
  bool vertexPipelineStoresAndAtomics = false;
  bool fragmentStoresAndAtomics = false;
  bool fillModeNonSolid = false;
  bool geometryShader = false;  ///< used by tests that capture the tessellator's triangles
  /// Vulkan 1.3 dynamicRendering or VK_KHR_dynamic_rendering: draws without a VkRenderPass
  /// (Context::cmdBeginRendering()).
  bool dynamicRendering = false;
  /// VK_EXT_conditional_rendering (our own device only): CullFrame's second pass skips its
  /// draws on the GPU when no patch became newly visible (Context::cmdBeginConditionalRendering()).
  bool conditionalRendering = false;
};

/// \brief Facts about the chosen device.
struct DeviceInfo {
  uint32_t index = 0;  ///< index in vkEnumeratePhysicalDevices order
  std::string name;
  std::string driver;  ///< driver name and info, e.g. "llvmpipe Mesa 22.3.6"
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t apiVersion = 0;
  VkPhysicalDeviceLimits limits{};
  uint32_t timestampValidBits = 0;  ///< of the queue used; 0: no timestamps
  OptionalFeatures optional;
};

/// \brief Names of the Vulkan devices present, in enumeration order (for --device help).
std::vector<std::string> listDevices();

/// \brief A device as selectDevice() sees it.
struct DeviceCandidate {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
};

/// \brief Picks a device: `selector` is an index ("1") or a case-insensitive name substring;
/// empty picks the first discrete GPU, else integrated GPU, else virtual GPU, else CPU
/// device (lavapipe), else device 0.
/// \throws osd_cull::Error listing the devices when nothing matches.
uint32_t selectDevice(std::span<const DeviceCandidate> devices, std::string_view selector);

struct ExternalDevice;

/// \brief The Vulkan instance, the chosen device and its queue, memory allocator and a
/// command pool for one-shot submissions. Every other vk/ object borrows a Context and
/// must be destroyed before it. Not thread-safe for submission.
///
/// Required features (checked at start, the error names every missing one):
/// Vulkan 1.2, tessellationShader, pipelineStatisticsQuery, multiDrawIndirect,
/// drawIndirectCount, a queue with graphics and compute.
class Context {
 public:
  /// \brief Creates its own instance and device (and destroys them with itself).
  explicit Context(const ContextOptions& options = {});
  /// \brief Adopts the application's instance, device and queue: creates only its memory
  /// allocator and command pool on that device, destroys neither device nor instance.
  /// \throws osd_cull::Error naming every required feature the application did not
  /// enable (see ExternalDevice).
  explicit Context(const ExternalDevice& device);
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const DeviceInfo& info() const { return info_; }
  MemoryAllocator& memory() { return *allocator_; }
  /// \brief The validation log, or nullptr when validation is off (always for an adopted
  /// device: the application's own debug messenger sees osd_cull's calls).
  ValidationLog* validationLog() const { return validationLog_.get(); }
  /// \brief True when this Context created (and will destroy) instance and device.
  bool ownsDevice() const { return ownsDevice_; }
  /// \brief vkCmdBeginRendering (core 1.3 or the KHR extension's), or null without
  /// OptionalFeatures::dynamicRendering.
  PFN_vkCmdBeginRenderingKHR cmdBeginRendering() const { return beginRendering_; }
  /// \brief vkCmdEndRendering, or null without OptionalFeatures::dynamicRendering.
  PFN_vkCmdEndRenderingKHR cmdEndRendering() const { return endRendering_; }
  /// \brief vkCmdBeginConditionalRenderingEXT, or null without
  /// OptionalFeatures::conditionalRendering.
  PFN_vkCmdBeginConditionalRenderingEXT cmdBeginConditionalRendering() const {
    return beginConditional_;
  }
  /// \brief vkCmdEndConditionalRenderingEXT, or null without it.
  PFN_vkCmdEndConditionalRenderingEXT cmdEndConditionalRendering() const {
    return endConditional_;
  }

  /// \brief Records commands into a fresh primary command buffer, submits it and waits
  /// for it to finish.
  void submit(const std::function<void(VkCommandBuffer)>& record);
  /// \brief vkDeviceWaitIdle.
  void waitIdle();
  /// \brief How many queue submissions submit() has made since the Context was created
  /// (lets tests check how many round trips a frame costs).
  uint64_t submissionCount() const { return submissions_; }

 private:
  void createInstance(const ContextOptions& options);
  void pickDevice(const ContextOptions& options);
  void createDevice();
  void createOwnObjects();  // allocator, command pool, dynamic-rendering entry points
  void destroy();

  std::shared_ptr<ValidationLog> validationLog_;
  bool printValidation_ = true;
  std::unique_ptr<std::pair<ValidationLog*, bool>> sink_;  // debug messenger user data
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  DeviceInfo info_;
  std::unique_ptr<MemoryAllocator> allocator_;
  UniqueCommandPool commandPool_;
  VkDeviceSize blockSize_ = 0;
  bool ownsDevice_ = true;
  PFN_vkCmdBeginRenderingKHR beginRendering_ = nullptr;
  PFN_vkCmdEndRenderingKHR endRendering_ = nullptr;
  PFN_vkCmdBeginConditionalRenderingEXT beginConditional_ = nullptr;
  PFN_vkCmdEndConditionalRenderingEXT endConditional_ = nullptr;
  uint64_t submissions_ = 0;
  std::vector<std::string> deviceExtensions_;
};

}  // namespace osd_cull::vulkan
