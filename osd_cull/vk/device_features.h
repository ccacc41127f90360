#pragma once
/// \file device_features.h
/// \brief What osd_cull needs from a Vulkan device, checked the same way for a device it
/// creates and for one an application lends it (external_device.h).

#include "osd_cull/vk/context.h"

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace osd_cull::vulkan {

/// \brief The Vulkan 1.2 and 1.3 feature structs found in a VkPhysicalDeviceFeatures2
/// chain (null when absent). Dynamic rendering is also found in the extension's struct
/// (VkPhysicalDeviceDynamicRenderingFeaturesKHR, same sType as the 1.3 alias).
struct FeatureChain {
  const VkPhysicalDeviceFeatures* core = nullptr;
  const VkPhysicalDeviceVulkan12Features* vulkan12 = nullptr;
  const VkPhysicalDeviceVulkan13Features* vulkan13 = nullptr;
  const VkPhysicalDeviceDynamicRenderingFeatures* dynamicRendering = nullptr;
};

/// \brief Walks `features.pNext` for the structs of FeatureChain.
FeatureChain findFeatures(const VkPhysicalDeviceFeatures2& features);

/// \brief The required features `chain` lacks, by name (empty: all there):
/// Vulkan 1.2 (`apiVersion`), tessellationShader, pipelineStatisticsQuery,
/// multiDrawIndirect, drawIndirectCount (VkPhysicalDeviceVulkan12Features) and
/// maxTessellationPatchSize >= 20.
std::vector<std::string> missingRequiredFeatures(const FeatureChain& chain, uint32_t apiVersion,
                                                 const VkPhysicalDeviceLimits& limits);

/// \brief The optional features `chain` has (or, for a lent device, has enabled).
/// `dynamicRenderingExtension`: VK_KHR_dynamic_rendering is available/enabled.
OptionalFeatures optionalFeaturesOf(const FeatureChain& chain, bool dynamicRenderingExtension);

/// \brief Name, driver, type, API version and limits of `device` (index `index`).
DeviceInfo describeDevice(VkPhysicalDevice device, uint32_t index);

/// \brief True when `device` offers the device extension `name`.
bool hasDeviceExtension(VkPhysicalDevice device, const char* name);

/// \brief "integrated GPU", "discrete GPU", "virtual GPU", "CPU" or "other".
const char* toString(VkPhysicalDeviceType type);

/// \brief Joins names with ", ".
std::string joinNames(const std::vector<std::string>& names);

}  // namespace osd_cull::vulkan
