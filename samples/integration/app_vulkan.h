#pragma once
// The application's own Vulkan, written as any Vulkan program would, without osd_cull:
// instance, device and queue, its color and depth images with their memory, its render
// passes and framebuffer, one command buffer and fence. osd_cull borrows these handles
// (integration.cpp) and owns none of them.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace app {

/// Throws std::runtime_error naming the call when a Vulkan call fails.
void check(VkResult result, const char* call);
#define APP_VK(call) ::app::check((call), #call)

/// What the program enables on its device: what osd_cull needs by default
/// (docs/integration.md); tests switch features off to see osd_cull name them.
struct DeviceOptions {
  bool validation = false;  ///< VK_LAYER_KHRONOS_validation with synchronization validation
  bool tessellationShader = true;
  bool drawIndirectCount = true;
  bool dynamicRendering = true;  ///< Vulkan 1.3 core feature
};

/// The device, a GPU when there is one.
struct Device {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  std::string name;
  // The feature chain given to vkCreateDevice, kept for osd_cull to check.
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan12Features features12{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features features13{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  std::vector<std::string> validationMessages;  // warnings and errors of the layer

  explicit Device(const DeviceOptions& options);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
};

/// A 2D image with its own memory and one view.
struct Image {
  VkDevice device = VK_NULL_HANDLE;
  uint32_t width = 0, height = 0;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageUsageFlags usage = 0;
  Image(VkPhysicalDevice physical, VkDevice device, uint32_t width, uint32_t height,
        VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect);
  ~Image();
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
};

/// The application's attachments and passes: color (B8G8R8A8 by default, readable by
/// transfers), depth (D32 by default, sampled: osd_cull's Hi-Z pyramid reads it), and either
/// a clearing and a loading render pass with one framebuffer, or none (dynamic rendering).
struct Target {
  static constexpr VkImageLayout kColorLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  static constexpr VkImageLayout kDepthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  VkPhysicalDevice physical;
  VkDevice device;
  uint32_t width, height;
  Image color, depth;
  VkRenderPass clearPass = VK_NULL_HANDLE, loadPass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  Target(VkPhysicalDevice physical, VkDevice device, uint32_t width, uint32_t height,
         VkFormat colorFormat = VK_FORMAT_B8G8R8A8_UNORM,
         VkFormat depthFormat = VK_FORMAT_D32_SFLOAT, bool renderPasses = true);
  ~Target();
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
  /// The color image's pixels, 4 bytes in its format's order, rows top to bottom (waits).
  std::vector<uint8_t> readColor(struct Commands& commands) const;
};

/// One primary command buffer and a fence: record, submit, wait.
struct Commands {
  VkDevice device;
  VkQueue queue;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  Commands(VkDevice device, VkQueue queue, uint32_t family);
  ~Commands();
  Commands(const Commands&) = delete;
  Commands& operator=(const Commands&) = delete;
  VkCommandBuffer begin();
  /// Ends, submits and waits for the fence.
  void submitAndWait();
};

}  // namespace app
