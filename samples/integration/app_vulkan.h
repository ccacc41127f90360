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

/// The device with what osd_cull needs enabled (docs/integration.md lists it).
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
  uint32_t validationMessages = 0;  // warnings and errors of the validation layer

  /// `validation`: enable VK_LAYER_KHRONOS_validation and count its messages.
  explicit Device(bool validation);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
};

/// A 2D image with its own memory and one view.
struct Image {
  VkDevice device = VK_NULL_HANDLE;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageUsageFlags usage = 0;
  Image(const Device& device, uint32_t width, uint32_t height, VkFormat format,
        VkImageUsageFlags usage, VkImageAspectFlags aspect);
  ~Image();
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
};

/// The application's attachments and passes: B8G8R8A8 color, D32 depth (sampled, for the
/// Hi-Z pyramid), a clearing and a loading render pass, one framebuffer.
struct Target {
  static constexpr VkFormat kColor = VK_FORMAT_B8G8R8A8_UNORM;
  static constexpr VkFormat kDepth = VK_FORMAT_D32_SFLOAT;
  static constexpr VkImageLayout kColorLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  static constexpr VkImageLayout kDepthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  const Device& device;
  uint32_t width, height;
  Image color, depth;
  VkRenderPass clearPass = VK_NULL_HANDLE, loadPass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  Target(const Device& device, uint32_t width, uint32_t height);
  ~Target();
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
  /// The color image's pixels, 4 bytes (B, G, R, A) each, rows top to bottom (waits).
  std::vector<uint8_t> readColor(struct Commands& commands) const;
};

/// One primary command buffer and a fence: record, submit, wait.
struct Commands {
  const Device& device;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  explicit Commands(const Device& device);
  ~Commands();
  Commands(const Commands&) = delete;
  Commands& operator=(const Commands&) = delete;
  VkCommandBuffer begin();
  /// Ends, submits and waits for the fence.
  void submitAndWait();
};

}  // namespace app
