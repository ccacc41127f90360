#pragma once
/// \file app_device.h
/// \brief A stand-in for an application's own Vulkan setup: its instance (Vulkan 1.3, with
/// the validation layer reporting into a ValidationLog), device and queue, created without
/// osd_cull, to be lent to it through vulkan::ExternalDevice.

#include "osd_cull/vk/external_device.h"
#include "osd_cull/vk/validation.h"

#include <memory>
#include <vector>

namespace osd_cull::test {

/// \brief What the application enables on its device.
struct AppDeviceOptions {
  bool tessellationShader = true;
  bool drawIndirectCount = true;
  bool dynamicRendering = true;  ///< Vulkan 1.3 core feature
};

/// \brief Instance, device and queue owned by the "application"; destroyed by it.
class AppDevice {
 public:
  explicit AppDevice(const AppDeviceOptions& options = {});
  ~AppDevice();
  AppDevice(const AppDevice&) = delete;
  AppDevice& operator=(const AppDevice&) = delete;

  /// \brief The handles and enabled features, as osd_cull takes them.
  vulkan::ExternalDevice lend() const;
  VkDevice device() const { return device_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return family_; }
  /// \brief Validation messages about anything done on this instance (osd_cull's calls on
  /// the lent device included).
  vulkan::ValidationLog& log() { return *log_; }

 private:
  std::shared_ptr<vulkan::ValidationLog> log_ = std::make_shared<vulkan::ValidationLog>();
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t family_ = 0;
  VkPhysicalDeviceFeatures2 features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan12Features features12_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features features13_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
};

}  // namespace osd_cull::test
