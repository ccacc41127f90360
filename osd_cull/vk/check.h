#pragma once
/// \file check.h
/// \brief VkResult checking: every Vulkan call's result goes through check().

#include <vulkan/vulkan.h>

#include <source_location>
#include <string>

namespace osd_cull::vulkan {

/// \brief The enumerator name of a VkResult, e.g. "VK_ERROR_DEVICE_LOST".
const char* toString(VkResult result);

/// \brief Throws osd_cull::Error naming the call, its result and the caller's file:line
/// when `result` is not VK_SUCCESS (other non-error codes are errors too unless the
/// caller handles them before calling this).
void check(VkResult result, const char* call,
           std::source_location where = std::source_location::current());

}  // namespace osd_cull::vulkan

/// Checks a Vulkan call: OSD_CULL_VK(vkCreateBuffer(device, &info, nullptr, &buffer)).
/// The error message names the call text.
#define OSD_CULL_VK(call) ::osd_cull::vulkan::check((call), #call)
