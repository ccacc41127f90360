#include "osd_cull/vk/context.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/device_features.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <iostream>

namespace osd_cull::vulkan {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string deviceList(std::span<const DeviceCandidate> devices) {
  std::string out;
  for (size_t i = 0; i < devices.size(); ++i)
    out += "\n  " + std::to_string(i) + ": " + devices[i].name + " (" + toString(devices[i].type) +
           ")";
  return devices.empty() ? std::string("\n  (none)") : out;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  auto* sink = static_cast<std::pair<ValidationLog*, bool>*>(user);
  ValidationMessage m;
  m.severity = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT
                   ? ValidationMessage::Severity::Error
                   : ValidationMessage::Severity::Warning;
  m.id = data->pMessageIdName ? data->pMessageIdName : "";
  m.text = data->pMessage ? data->pMessage : "";
  if (sink->second) std::cerr << "[vulkan validation] " << m.text << "\n";
  sink->first->record(std::move(m));
  return VK_FALSE;
}

bool hasLayer(const char* name) {
  uint32_t count = 0;
  OSD_CULL_VK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  OSD_CULL_VK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

VkInstance createBareInstance() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "osd_cull";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateInstance(&info, nullptr, &instance));
  return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  OSD_CULL_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  OSD_CULL_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  devices.resize(count);
  return devices;
}

std::vector<DeviceCandidate> deviceCandidates(VkInstance instance) {
  std::vector<DeviceCandidate> out;
  for (VkPhysicalDevice d : physicalDevices(instance)) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    out.push_back({p.deviceName, p.deviceType});
  }
  return out;
}

// Rank of a device type for the default choice (lower is preferred).
int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

}  // namespace

std::vector<std::string> listDevices() {
  VkInstance instance = createBareInstance();
  std::vector<std::string> names;
  try {
    for (const DeviceCandidate& d : deviceCandidates(instance)) names.push_back(d.name);
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return names;
}

uint32_t selectDevice(std::span<const DeviceCandidate> devices, std::string_view selector) {
  if (devices.empty()) throw Error("no Vulkan device found (is mesa-vulkan-drivers installed?)");
  if (selector.empty()) {
    size_t best = 0;
    for (size_t i = 1; i < devices.size(); ++i)
      if (typeRank(devices[i].type) < typeRank(devices[best].type)) best = i;
    return static_cast<uint32_t>(best);
  }
  if (std::all_of(selector.begin(), selector.end(),
                  [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
    const unsigned long index = std::stoul(std::string(selector));
    if (index >= devices.size())
      throw Error("Vulkan device index " + std::string(selector) +
                  " is out of range; devices:" + deviceList(devices));
    return static_cast<uint32_t>(index);
  }
  const std::string needle = lower(selector);
  for (size_t i = 0; i < devices.size(); ++i)
    if (lower(devices[i].name).find(needle) != std::string::npos) return static_cast<uint32_t>(i);
  throw Error("no Vulkan device name contains '" + std::string(selector) +
              "'; devices:" + deviceList(devices));
}

Context::Context(const ContextOptions& options)
    : printValidation_(options.printValidationMessages), blockSize_(options.memoryBlockSize) {
  try {
    createInstance(options);
    pickDevice(options);
    if (options.adjustDeviceInfo) options.adjustDeviceInfo(info_);
    createDevice();
  } catch (...) {
    destroy();
    throw;
  }
}

Context::~Context() { destroy(); }

void Context::destroy() {
  commandPool_.reset();
  allocator_.reset();
  if (!ownsDevice_) return;  // the application's device and instance stay
  if (device_) vkDestroyDevice(device_, nullptr);
  device_ = VK_NULL_HANDLE;
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

void Context::createInstance(const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "osd_cull";
  app.pEngineName = "osd_cull";
  app.apiVersion = VK_API_VERSION_1_2;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;

  const char* layer = "VK_LAYER_KHRONOS_validation";
  std::vector<const char*> extensions;
  for (const std::string& e : options.instanceExtensions) extensions.push_back(e.c_str());
  if (!extensions.empty()) {
    uint32_t count = 0;
    OSD_CULL_VK(vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> present(count);
    OSD_CULL_VK(vkEnumerateInstanceExtensionProperties(nullptr, &count, present.data()));
    std::string missing;
    for (const std::string& e : options.instanceExtensions) {
      bool found = false;
      for (const auto& p : present) found |= e == p.extensionName;
      if (!found) missing += (missing.empty() ? "" : ", ") + e;
    }
    if (!missing.empty()) throw Error("the Vulkan instance lacks required extensions: " + missing);
  }
  VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};

  if (options.validation) {
    if (!hasLayer(layer))
      throw Error(std::string("validation requested but ") + layer +
                  " is not installed (Debian package vulkan-validationlayers)");
    validationLog_ =
        options.validationLog ? options.validationLog : std::make_shared<ValidationLog>();
    sink_ =
        std::make_unique<std::pair<ValidationLog*, bool>>(validationLog_.get(), printValidation_);
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = onDebugMessage;
    messengerInfo.pUserData = sink_.get();
    // Chain: instance info -> validation features -> messenger (covers instance creation).
    features.pNext = &messengerInfo;
    info.pNext = &features;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &layer;
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  OSD_CULL_VK(vkCreateInstance(&info, nullptr, &instance_));
  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) throw Error("vkCreateDebugUtilsMessengerEXT is not available");
    OSD_CULL_VK(create(instance_, &messengerInfo, nullptr, &messenger_));
  }
}

void Context::pickDevice(const ContextOptions& options) {
  const std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);
  const std::vector<DeviceCandidate> candidates = deviceCandidates(instance_);
  std::string selector = options.device;
  const char* how = "given by the caller";
  if (selector.empty())
    if (const char* env = std::getenv("OSD_CULL_DEVICE")) {
      selector = env;
      how = "from OSD_CULL_DEVICE";
    }
  if (selector.empty()) how = "default: discrete, then integrated GPU, then CPU";
  const uint32_t index = selectDevice(candidates, selector);
  physicalDevice_ = devices[index];
  info_ = describeDevice(physicalDevice_, index);

  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceDynamicRenderingFeatures dynamic{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  const bool is12 = info_.apiVersion >= VK_API_VERSION_1_2;
  const bool dynamicExtension =
      hasDeviceExtension(physicalDevice_, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
  if (is12) f.pNext = &f12;
  if (is12 && dynamicExtension) f12.pNext = &dynamic;
  vkGetPhysicalDeviceFeatures2(physicalDevice_, &f);
  std::vector<std::string> missing =
      missingRequiredFeatures(findFeatures(f), info_.apiVersion, info_.limits);

  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  bool found = false;
  for (uint32_t i = 0; i < familyCount && !found; ++i) {
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if ((families[i].queueFlags & need) == need) {
      queueFamily_ = i;
      info_.timestampValidBits = families[i].timestampValidBits;
      found = true;
    }
  }
  if (!found) missing.push_back("a queue family with graphics and compute");
  if (!options.deviceExtensions.empty()) {
    uint32_t count = 0;
    OSD_CULL_VK(vkEnumerateDeviceExtensionProperties(physicalDevice_, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> present(count);
    OSD_CULL_VK(
        vkEnumerateDeviceExtensionProperties(physicalDevice_, nullptr, &count, present.data()));
    for (const std::string& e : options.deviceExtensions) {
      bool has = false;
      for (const auto& p : present) has |= e == p.extensionName;
      if (!has) missing.push_back("extension " + e);
    }
  }
  deviceExtensions_ = options.deviceExtensions;

  if (!missing.empty())
    throw Error("Vulkan device " + std::to_string(info_.index) + " '" + info_.name +
                "' lacks required features: " + joinNames(missing) +
                " (choose another device with --device or OSD_CULL_DEVICE; devices:" +
                deviceList(candidates) + ")");
  info_.optional = optionalFeaturesOf(findFeatures(f), dynamicExtension);
  if (hasDeviceExtension(physicalDevice_, VK_EXT_CONDITIONAL_RENDERING_EXTENSION_NAME)) {
    VkPhysicalDeviceConditionalRenderingFeaturesEXT conditional{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CONDITIONAL_RENDERING_FEATURES_EXT};
    VkPhysicalDeviceFeatures2 fc{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    fc.pNext = &conditional;
    vkGetPhysicalDeviceFeatures2(physicalDevice_, &fc);
    info_.optional.conditionalRendering = conditional.conditionalRendering == VK_TRUE;
  }
  const std::string line = "osd_cull: Vulkan device " + std::to_string(index) + " '" + info_.name +
                           "' (" + toString(info_.type) + ", " + how + ")";
  if (options.log)
    options.log(line);
  else
    std::cerr << line << "\n";
}

void Context::createDevice() {
  const auto& opt = info_.optional;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.drawIndirectCount = VK_TRUE;
  f12.samplerFilterMinmax = opt.samplerFilterMinmax;
  f12.bufferDeviceAddress = opt.bufferDeviceAddress;
  f12.hostQueryReset = opt.hostQueryReset;
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f.pNext = &f12;
  f.features.tessellationShader = VK_TRUE;
  f.features.pipelineStatisticsQuery = VK_TRUE;
  f.features.multiDrawIndirect = VK_TRUE;
  f.features.shaderFloat64 = opt.shaderFloat64;
  f.features.vertexPipelineStoresAndAtomics = opt.vertexPipelineStoresAndAtomics;
  f.features.fragmentStoresAndAtomics = opt.fragmentStoresAndAtomics;
  f.features.fillModeNonSolid = opt.fillModeNonSolid;
  f.features.geometryShader = opt.geometryShader;
  // Dynamic rendering through the extension: the instance asks for Vulkan 1.2 only.
  VkPhysicalDeviceDynamicRenderingFeatures dynamic{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  dynamic.dynamicRendering = VK_TRUE;
  if (opt.dynamicRendering) f12.pNext = &dynamic;
  VkPhysicalDeviceConditionalRenderingFeaturesEXT conditional{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CONDITIONAL_RENDERING_FEATURES_EXT};
  conditional.conditionalRendering = VK_TRUE;
  if (opt.conditionalRendering) {
    conditional.pNext = f12.pNext;
    f12.pNext = &conditional;
  }

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  std::vector<const char*> extensions;
  for (const std::string& e : deviceExtensions_)
    if (e != VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME) extensions.push_back(e.c_str());
  if (opt.dynamicRendering) extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
  if (opt.conditionalRendering &&
      std::find(deviceExtensions_.begin(), deviceExtensions_.end(),
                VK_EXT_CONDITIONAL_RENDERING_EXTENSION_NAME) == deviceExtensions_.end())
    extensions.push_back(VK_EXT_CONDITIONAL_RENDERING_EXTENSION_NAME);
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &f;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  OSD_CULL_VK(vkCreateDevice(physicalDevice_, &info, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  createOwnObjects();
}

void Context::createOwnObjects() {
  if (info_.optional.dynamicRendering) {
    // The extension's entry points first (how our own device enables it), then core 1.3's
    // (an application's 1.3 device without the extension).
    for (const char* suffix : {"KHR", ""}) {
      beginRendering_ = reinterpret_cast<PFN_vkCmdBeginRenderingKHR>(
          vkGetDeviceProcAddr(device_, (std::string("vkCmdBeginRendering") + suffix).c_str()));
      endRendering_ = reinterpret_cast<PFN_vkCmdEndRenderingKHR>(
          vkGetDeviceProcAddr(device_, (std::string("vkCmdEndRendering") + suffix).c_str()));
      if (beginRendering_ && endRendering_) break;
    }
    if (!beginRendering_ || !endRendering_)
      throw Error("dynamic rendering is enabled but vkCmdBeginRendering is not available");
  }
  if (info_.optional.conditionalRendering) {
    beginConditional_ = reinterpret_cast<PFN_vkCmdBeginConditionalRenderingEXT>(
        vkGetDeviceProcAddr(device_, "vkCmdBeginConditionalRenderingEXT"));
    endConditional_ = reinterpret_cast<PFN_vkCmdEndConditionalRenderingEXT>(
        vkGetDeviceProcAddr(device_, "vkCmdEndConditionalRenderingEXT"));
    if (!beginConditional_ || !endConditional_)
      throw Error("conditional rendering is enabled but its commands are not available");
  }
  allocator_ = std::make_unique<MemoryAllocator>(physicalDevice_, device_, blockSize_,
                                                 info_.optional.bufferDeviceAddress);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VkCommandPool pool = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool));
  commandPool_ = UniqueCommandPool(device_, pool);
}

void Context::submit(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = commandPool_.get();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  OSD_CULL_VK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
  struct Free {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } freeLater{device_, commandPool_.get(), cmd};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  OSD_CULL_VK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  OSD_CULL_VK(vkEndCommandBuffer(cmd));

  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateFence(device_, &fenceInfo, nullptr, &fence));
  UniqueFence fenceOwner(device_, fence);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  OSD_CULL_VK(vkQueueSubmit(queue_, 1, &submit, fence));
  ++submissions_;
  OSD_CULL_VK(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
}

void Context::waitIdle() { OSD_CULL_VK(vkDeviceWaitIdle(device_)); }

}  // namespace osd_cull::vulkan
