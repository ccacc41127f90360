#include "support/app_device.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"

#include <cstdlib>
#include <string>

namespace osd_cull::test {

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL appDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                               VkDebugUtilsMessageTypeFlagsEXT,
                                               const VkDebugUtilsMessengerCallbackDataEXT* data,
                                               void* user) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  vulkan::ValidationMessage m;
  m.id = data->pMessageIdName ? data->pMessageIdName : "";
  m.text = data->pMessage ? data->pMessage : "";
  static_cast<vulkan::ValidationLog*>(user)->record(std::move(m));
  return VK_FALSE;
}

}  // namespace

AppDevice::AppDevice(const AppDeviceOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "osd_cull test application";
  app.apiVersion = VK_API_VERSION_1_3;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkDebugUtilsMessengerCreateInfoEXT messenger{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  messenger.pfnUserCallback = appDebugMessage;
  messenger.pUserData = log_.get();
  const VkValidationFeatureEnableEXT sync =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT validation{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  validation.enabledValidationFeatureCount = 1;
  validation.pEnabledValidationFeatures = &sync;
  validation.pNext = &messenger;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = &validation;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = 1;
  info.ppEnabledLayerNames = &layer;
  info.enabledExtensionCount = 1;
  info.ppEnabledExtensionNames = &extension;
  OSD_CULL_VK(vkCreateInstance(&info, nullptr, &instance_));
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
  OSD_CULL_VK(create(instance_, &messenger, nullptr, &messenger_));

  uint32_t count = 0;
  OSD_CULL_VK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  OSD_CULL_VK(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));
  std::vector<vulkan::DeviceCandidate> candidates;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    candidates.push_back({p.deviceName, p.deviceType});
  }
  const char* env = std::getenv("OSD_CULL_DEVICE");
  physicalDevice_ = devices[vulkan::selectDevice(candidates, env ? env : "")];

  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &families, props.data());
  while (family_ < families && !(props[family_].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++family_;
  if (family_ == families) throw Error("AppDevice: no graphics queue");

  features_.pNext = &features12_;
  features12_.pNext = &features13_;
  features_.features.tessellationShader = options.tessellationShader;
  features_.features.pipelineStatisticsQuery = VK_TRUE;
  features_.features.multiDrawIndirect = VK_TRUE;
  features12_.drawIndirectCount = options.drawIndirectCount;
  features12_.samplerFilterMinmax = VK_TRUE;
  features12_.hostQueryReset = VK_TRUE;
  features13_.dynamicRendering = options.dynamicRendering;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = family_;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features_;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queue;
  OSD_CULL_VK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
  vkGetDeviceQueue(device_, family_, 0, &queue_);
}

AppDevice::~AppDevice() {
  if (device_) vkDestroyDevice(device_, nullptr);
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
  if (messenger_ && destroy) destroy(instance_, messenger_, nullptr);
  vkDestroyInstance(instance_, nullptr);
}

vulkan::ExternalDevice AppDevice::lend() const {
  vulkan::ExternalDevice lent;
  lent.instance = instance_;
  lent.physicalDevice = physicalDevice_;
  lent.device = device_;
  lent.queue = queue_;
  lent.queueFamily = family_;
  lent.apiVersion = VK_API_VERSION_1_3;
  lent.enabledFeatures = &features_;
  return lent;
}

}  // namespace osd_cull::test
