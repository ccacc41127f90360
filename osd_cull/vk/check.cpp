#include "osd_cull/vk/check.h"

#include "osd_cull/error.h"

#include <filesystem>

namespace osd_cull::vulkan {

const char* toString(VkResult result) {
  switch (result) {
#define OSD_CULL_CASE(x) \
  case x:                \
    return #x;
    OSD_CULL_CASE(VK_SUCCESS)
    OSD_CULL_CASE(VK_NOT_READY)
    OSD_CULL_CASE(VK_TIMEOUT)
    OSD_CULL_CASE(VK_EVENT_SET)
    OSD_CULL_CASE(VK_EVENT_RESET)
    OSD_CULL_CASE(VK_INCOMPLETE)
    OSD_CULL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    OSD_CULL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    OSD_CULL_CASE(VK_ERROR_INITIALIZATION_FAILED)
    OSD_CULL_CASE(VK_ERROR_DEVICE_LOST)
    OSD_CULL_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    OSD_CULL_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    OSD_CULL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    OSD_CULL_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    OSD_CULL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    OSD_CULL_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    OSD_CULL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    OSD_CULL_CASE(VK_ERROR_FRAGMENTED_POOL)
    OSD_CULL_CASE(VK_ERROR_UNKNOWN)
    OSD_CULL_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    OSD_CULL_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    OSD_CULL_CASE(VK_ERROR_FRAGMENTATION)
    OSD_CULL_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    OSD_CULL_CASE(VK_PIPELINE_COMPILE_REQUIRED)
    OSD_CULL_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef OSD_CULL_CASE
    default:
      return "VK_RESULT_UNKNOWN";
  }
}

void check(VkResult result, const char* call, std::source_location where) {
  if (result == VK_SUCCESS) return;
  throw Error(std::filesystem::path(where.file_name()).filename().string() + ":" +
              std::to_string(where.line()) + ": " + call + " returned " + toString(result) + " (" +
              std::to_string(static_cast<int>(result)) + ")");
}

}  // namespace osd_cull::vulkan
