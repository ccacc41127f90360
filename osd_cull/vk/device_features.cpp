#include "osd_cull/vk/device_features.h"

#include "osd_cull/vk/check.h"

#include <cstring>

namespace osd_cull::vulkan {

FeatureChain findFeatures(const VkPhysicalDeviceFeatures2& features) {
  FeatureChain chain;
  chain.core = &features.features;
  for (auto* s = static_cast<const VkBaseInStructure*>(features.pNext); s; s = s->pNext) {
    switch (s->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
        chain.vulkan12 = reinterpret_cast<const VkPhysicalDeviceVulkan12Features*>(s);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
        chain.vulkan13 = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
        chain.dynamicRendering =
            reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(s);
        break;
      default:
        break;
    }
  }
  return chain;
}

std::vector<std::string> missingRequiredFeatures(const FeatureChain& chain, uint32_t apiVersion,
                                                 const VkPhysicalDeviceLimits& limits) {
  std::vector<std::string> missing;
  if (apiVersion < VK_API_VERSION_1_2)
    missing.push_back("Vulkan 1.2 (device reports " +
                      std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." +
                      std::to_string(VK_API_VERSION_MINOR(apiVersion)) + ")");
  const VkPhysicalDeviceFeatures& f = *chain.core;
  if (!f.tessellationShader) missing.push_back("tessellationShader");
  if (!f.pipelineStatisticsQuery) missing.push_back("pipelineStatisticsQuery");
  if (!f.multiDrawIndirect) missing.push_back("multiDrawIndirect");
  if (!chain.vulkan12 || !chain.vulkan12->drawIndirectCount)
    missing.push_back("drawIndirectCount (VkPhysicalDeviceVulkan12Features)");
  if (limits.maxTessellationPatchSize < 20)
    missing.push_back("maxTessellationPatchSize >= 20 (has " +
                      std::to_string(limits.maxTessellationPatchSize) + ")");
  return missing;
}

OptionalFeatures optionalFeaturesOf(const FeatureChain& chain, bool dynamicRenderingExtension) {
  OptionalFeatures o;
  const VkPhysicalDeviceFeatures& f = *chain.core;
  o.shaderFloat64 = f.shaderFloat64;
  o.vertexPipelineStoresAndAtomics = f.vertexPipelineStoresAndAtomics;
  o.fragmentStoresAndAtomics = f.fragmentStoresAndAtomics;
  o.fillModeNonSolid = f.fillModeNonSolid;
  o.geometryShader = f.geometryShader;
  if (const auto* f12 = chain.vulkan12) {
    o.samplerFilterMinmax = f12->samplerFilterMinmax;
    o.bufferDeviceAddress = f12->bufferDeviceAddress;
    o.hostQueryReset = f12->hostQueryReset;
  }
  o.dynamicRendering = (chain.vulkan13 && chain.vulkan13->dynamicRendering) ||
                       (dynamicRenderingExtension && chain.dynamicRendering &&
                        chain.dynamicRendering->dynamicRendering);
  return o;
}

DeviceInfo describeDevice(VkPhysicalDevice device, uint32_t index) {
  DeviceInfo info;
  info.index = index;
  VkPhysicalDeviceProperties base;
  vkGetPhysicalDeviceProperties(device, &base);
  VkPhysicalDeviceVulkan12Properties props12{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  const bool is12 = base.apiVersion >= VK_API_VERSION_1_2;
  if (is12) props.pNext = &props12;
  vkGetPhysicalDeviceProperties2(device, &props);
  info.name = props.properties.deviceName;
  info.type = props.properties.deviceType;
  info.apiVersion = props.properties.apiVersion;
  info.limits = props.properties.limits;
  if (is12) info.driver = std::string(props12.driverName) + " " + props12.driverInfo;
  return info;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  OSD_CULL_VK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  OSD_CULL_VK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
  for (const VkExtensionProperties& e : extensions)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

const char* toString(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace osd_cull::vulkan
