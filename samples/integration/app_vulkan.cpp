#include "app_vulkan.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace app {

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(call) + " failed with VkResult " + std::to_string(result));
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data,
                                         void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    static_cast<std::vector<std::string>*>(user)->push_back(data->pMessage);
    std::fprintf(stderr, "[validation] %s\n", data->pMessage);
  }
  return VK_FALSE;
}

uint32_t memoryType(VkPhysicalDevice physical, uint32_t bits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want) return i;
  throw std::runtime_error("no suitable memory type");
}

VkRenderPass makePass(VkDevice device, VkFormat color, VkFormat depth, bool clear) {
  VkAttachmentDescription a[2]{};
  a[0].format = color;
  a[1].format = depth;
  const VkImageLayout layouts[2] = {Target::kColorLayout, Target::kDepthLayout};
  for (int i = 0; i < 2; ++i) {
    a[i].samples = VK_SAMPLE_COUNT_1_BIT;
    a[i].loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a[i].initialLayout = clear ? VK_IMAGE_LAYOUT_UNDEFINED : layouts[i];
    a[i].finalLayout = layouts[i];
  }
  const VkAttachmentReference colorRef{0, Target::kColorLayout};
  const VkAttachmentReference depthRef{1, Target::kDepthLayout};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  subpass.pDepthStencilAttachment = &depthRef;
  // Earlier work on the images (osd_cull's Hi-Z build reads depth between the passes)
  // before this pass, this pass before later work.
  VkSubpassDependency deps[2]{};
  deps[0] = {VK_SUBPASS_EXTERNAL,
             0,
             VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
             VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT,
             VK_ACCESS_MEMORY_WRITE_BIT,
             VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
             0};
  deps[1] = {0,
             VK_SUBPASS_EXTERNAL,
             VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT,
             VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
             VK_ACCESS_MEMORY_WRITE_BIT,
             VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
             0};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = a;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  APP_VK(vkCreateRenderPass(device, &info, nullptr, &pass));
  return pass;
}

}  // namespace

Device::Device(const DeviceOptions& options) {
  const bool validation = options.validation;
  VkApplicationInfo appInfo{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  appInfo.pApplicationName = "osd_cull integration sample";
  appInfo.apiVersion = VK_API_VERSION_1_3;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                  VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  messengerInfo.pfnUserCallback = onMessage;
  messengerInfo.pUserData = &validationMessages;
  const VkValidationFeatureEnableEXT sync =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT validationFeatures{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  validationFeatures.enabledValidationFeatureCount = 1;
  validationFeatures.pEnabledValidationFeatures = &sync;
  validationFeatures.pNext = &messengerInfo;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &appInfo;
  if (validation) {
    info.pNext = &validationFeatures;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &debugUtils;
  }
  APP_VK(vkCreateInstance(&info, nullptr, &instance));
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    APP_VK(create(instance, &messengerInfo, nullptr, &messenger));
  }

  // A GPU if there is one, else the first device (lavapipe on a machine without a GPU).
  uint32_t count = 0;
  APP_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  APP_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  if (devices.empty()) throw std::runtime_error("no Vulkan device");
  physical = devices[0];
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
        p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU) {
      physical = d;
      break;
    }
  }
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical, &props);
  name = props.deviceName;
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
  std::vector<VkQueueFamilyProperties> familyProps(families);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, familyProps.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  while (family < families && (familyProps[family].queueFlags & need) != need) ++family;
  if (family == families) throw std::runtime_error("no graphics + compute queue");

  // What osd_cull needs; the same chain is handed to it.
  features.pNext = &features12;
  features12.pNext = &features13;
  features.features.tessellationShader = options.tessellationShader;
  features.features.pipelineStatisticsQuery = VK_TRUE;
  features.features.multiDrawIndirect = VK_TRUE;
  features12.drawIndirectCount = options.drawIndirectCount;
  features12.samplerFilterMinmax = VK_TRUE;
  features12.hostQueryReset = VK_TRUE;
  features13.dynamicRendering = options.dynamicRendering;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  APP_VK(vkCreateDevice(physical, &deviceInfo, nullptr, &device));
  vkGetDeviceQueue(device, family, 0, &queue);
}

Device::~Device() {
  vkDestroyDevice(device, nullptr);
  if (messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance, messenger, nullptr);
  }
  vkDestroyInstance(instance, nullptr);
}

Image::Image(VkPhysicalDevice physical, VkDevice d, uint32_t w, uint32_t h, VkFormat f,
             VkImageUsageFlags u, VkImageAspectFlags aspect)
    : device(d), width(w), height(h), format(f), usage(u) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  APP_VK(vkCreateImage(device, &info, nullptr, &image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      memoryType(physical, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  APP_VK(vkAllocateMemory(device, &alloc, nullptr, &memory));
  APP_VK(vkBindImageMemory(device, image, memory, 0));
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = format;
  viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
  APP_VK(vkCreateImageView(device, &viewInfo, nullptr, &view));
}

Image::~Image() {
  vkDestroyImageView(device, view, nullptr);
  vkDestroyImage(device, image, nullptr);
  vkFreeMemory(device, memory, nullptr);
}

Target::Target(VkPhysicalDevice p, VkDevice d, uint32_t w, uint32_t h, VkFormat colorFormat,
               VkFormat depthFormat, bool renderPasses)
    : physical(p),
      device(d),
      width(w),
      height(h),
      color(p, d, w, h, colorFormat,
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
            VK_IMAGE_ASPECT_COLOR_BIT),
      depth(p, d, w, h, depthFormat,
            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
            VK_IMAGE_ASPECT_DEPTH_BIT) {
  if (!renderPasses) return;
  clearPass = makePass(d, colorFormat, depthFormat, true);
  loadPass = makePass(d, colorFormat, depthFormat, false);
  const VkImageView views[2] = {color.view, depth.view};
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = clearPass;
  info.attachmentCount = 2;
  info.pAttachments = views;
  info.width = w;
  info.height = h;
  info.layers = 1;
  APP_VK(vkCreateFramebuffer(d, &info, nullptr, &framebuffer));
}

Target::~Target() {
  vkDestroyFramebuffer(device, framebuffer, nullptr);
  vkDestroyRenderPass(device, loadPass, nullptr);
  vkDestroyRenderPass(device, clearPass, nullptr);
}

std::vector<uint8_t> Target::readColor(Commands& commands) const {
  const VkDeviceSize size = VkDeviceSize{width} * height * 4;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  APP_VK(vkCreateBuffer(device, &info, nullptr, &buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      memoryType(physical, req.memoryTypeBits,
                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  APP_VK(vkAllocateMemory(device, &alloc, nullptr, &memory));
  APP_VK(vkBindBufferMemory(device, buffer, memory, 0));

  VkCommandBuffer cmd = commands.begin();
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  barrier.oldLayout = kColorLayout;
  barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = color.image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &barrier);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width, height, 1};
  vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1,
                         &region);
  std::swap(barrier.oldLayout, barrier.newLayout);
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  barrier.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0, nullptr, 0, nullptr, 1,
                       &barrier);
  VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toHost.buffer = buffer;
  toHost.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                       nullptr, 1, &toHost, 0, nullptr);
  commands.submitAndWait();

  std::vector<uint8_t> pixels(size);
  void* mapped = nullptr;
  APP_VK(vkMapMemory(device, memory, 0, size, 0, &mapped));
  std::memcpy(pixels.data(), mapped, size);
  vkUnmapMemory(device, memory);
  vkDestroyBuffer(device, buffer, nullptr);
  vkFreeMemory(device, memory, nullptr);
  return pixels;
}

Commands::Commands(VkDevice d, VkQueue q, uint32_t family) : device(d), queue(q) {
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = family;
  APP_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  APP_VK(vkAllocateCommandBuffers(device, &alloc, &cmd));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  APP_VK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
}

Commands::~Commands() {
  vkDestroyFence(device, fence, nullptr);
  vkDestroyCommandPool(device, pool, nullptr);
}

VkCommandBuffer Commands::begin() {
  APP_VK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  APP_VK(vkBeginCommandBuffer(cmd, &begin));
  return cmd;
}

void Commands::submitAndWait() {
  APP_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  APP_VK(vkResetFences(device, 1, &fence));
  APP_VK(vkQueueSubmit(queue, 1, &submit, fence));
  APP_VK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
}

}  // namespace app
