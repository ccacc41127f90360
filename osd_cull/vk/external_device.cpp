#include "osd_cull/vk/external_device.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/device_features.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace osd_cull::vulkan {

namespace {

void requireHandles(const ExternalDevice& lent) {
  std::vector<std::string> nulls;
  if (!lent.instance) nulls.push_back("instance");
  if (!lent.physicalDevice) nulls.push_back("physicalDevice");
  if (!lent.device) nulls.push_back("device");
  if (!lent.queue) nulls.push_back("queue");
  if (lent.apiVersion == 0)
    nulls.push_back("apiVersion (the instance's VkApplicationInfo::apiVersion)");
  if (!lent.enabledFeatures)
    nulls.push_back(
        "enabledFeatures (the VkPhysicalDeviceFeatures2 chain given to vkCreateDevice)");
  if (!nulls.empty()) throw Error("vulkan::Context(ExternalDevice): missing " + joinNames(nulls));
  if (lent.enabledFeatures->sType != VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)
    throw Error(
        "vulkan::Context(ExternalDevice): enabledFeatures is not a VkPhysicalDeviceFeatures2 "
        "(sType " +
        std::to_string(static_cast<int>(lent.enabledFeatures->sType)) + ")");
}

bool enabled(std::span<const char* const> extensions, const char* name) {
  for (const char* e : extensions)
    if (e && std::strcmp(e, name) == 0) return true;
  return false;
}

}  // namespace

Context::Context(const ExternalDevice& lent)
    : printValidation_(false), blockSize_(lent.memoryBlockSize) {
  requireHandles(lent);
  ownsDevice_ = false;
  instance_ = lent.instance;
  physicalDevice_ = lent.physicalDevice;
  device_ = lent.device;
  queue_ = lent.queue;
  queueFamily_ = lent.queueFamily;
  info_ = describeDevice(physicalDevice_, 0);

  const FeatureChain chain = findFeatures(*lent.enabledFeatures);
  info_.apiVersion = std::min(info_.apiVersion, lent.apiVersion);
  std::vector<std::string> missing = missingRequiredFeatures(chain, info_.apiVersion, info_.limits);
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  if (queueFamily_ >= familyCount)
    missing.push_back("queue family " + std::to_string(queueFamily_) + " (the device has " +
                      std::to_string(familyCount) + ")");
  else if ((families[queueFamily_].queueFlags & need) != need)
    missing.push_back("graphics and compute on the queue's family " + std::to_string(queueFamily_));
  else
    info_.timestampValidBits = families[queueFamily_].timestampValidBits;
  if (!missing.empty())
    throw Error("the application's Vulkan device '" + info_.name +
                "' was not created with what osd_cull needs: " + joinNames(missing) +
                " (enable them in the VkDeviceCreateInfo and pass that chain as "
                "ExternalDevice::enabledFeatures)");
  info_.optional = optionalFeaturesOf(
      chain, enabled(lent.enabledExtensions, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME));
  try {
    createOwnObjects();
  } catch (...) {
    destroy();
    throw;
  }
}

}  // namespace osd_cull::vulkan
