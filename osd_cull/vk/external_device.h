#pragma once
/// \file external_device.h
/// \brief The application's Vulkan instance, device and queue, lent to osd_cull.
///
/// \code
///   osd_cull::vulkan::ExternalDevice lent;
///   lent.instance = instance;  lent.physicalDevice = gpu;  lent.device = device;
///   lent.queue = queue;        lent.queueFamily = family;
///   lent.apiVersion = VK_API_VERSION_1_3;  // the instance's VkApplicationInfo::apiVersion
///   lent.enabledFeatures = &features2;  // the chain given to vkCreateDevice
///   lent.enabledExtensions = deviceExtensions;
///   osd_cull::vulkan::Context context(lent);  // destroys neither device nor instance
/// \endcode
///
/// What the application must enable at vkCreateDevice (the Context's constructor names
/// whatever is missing): Vulkan 1.2 (VkApplicationInfo::apiVersion and the device),
/// tessellationShader, pipelineStatisticsQuery, multiDrawIndirect in
/// VkPhysicalDeviceFeatures, and drawIndirectCount in a VkPhysicalDeviceVulkan12Features
/// on the chain; hostQueryReset (1.2 struct) for frame::CullFrame. Used when enabled:
/// samplerFilterMinmax, bufferDeviceAddress (1.2 struct), shaderFloat64, and dynamic
/// rendering (Vulkan 1.3 feature or VK_KHR_dynamic_rendering with its features struct) for
/// targets without a VkRenderPass. The queue must support graphics and compute.
///
/// What the application must keep alive: instance, device and queue until the Context
/// and every osd_cull object made with it are destroyed. osd_cull submits to the queue
/// only from Context::submit() (setup, uploads, read-backs; never from a recorded frame):
/// the application must not use the queue from another thread at the same time.

#include "osd_cull/vk/context.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

namespace osd_cull::vulkan {

/// \brief Handles and enabled features of an application's device (see the file comment).
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;  ///< family of `queue`
  /// VkApplicationInfo::apiVersion of the instance (the lower of it and the device's
  /// version is what osd_cull may use). Required.
  uint32_t apiVersion = 0;
  /// The VkPhysicalDeviceFeatures2 chain the application passed to vkCreateDevice: what is
  /// enabled, not what the device could do. Required.
  const VkPhysicalDeviceFeatures2* enabledFeatures = nullptr;
  /// The device extensions the application enabled (VK_KHR_dynamic_rendering counts).
  std::span<const char* const> enabledExtensions;
  /// Size of the memory blocks osd_cull's own resources are sub-allocated from.
  VkDeviceSize memoryBlockSize = VkDeviceSize{64} << 20;
};

}  // namespace osd_cull::vulkan
