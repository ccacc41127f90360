#include "osd_cull/vk/limits.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/context.h"

#include <algorithm>
#include <string>

namespace osd_cull::vulkan {

namespace {

[[noreturn]] void exceeded(std::string_view what, uint64_t asked, std::string_view unit,
                           std::string_view limit, uint64_t value) {
  throw Error(std::string(what) + ": " + std::to_string(asked) + " " + std::string(unit) +
              " exceed the device's " + std::string(limit) + " of " + std::to_string(value));
}

}  // namespace

void checkStorageBufferRange(const Context& context, VkDeviceSize bytes, std::string_view what) {
  const VkDeviceSize limit = context.info().limits.maxStorageBufferRange;
  if (bytes > limit) exceeded(what, bytes, "bytes", "maxStorageBufferRange", limit);
}

uint32_t checkedGroups1D(const Context& context, uint64_t groups, std::string_view what) {
  const uint32_t limit = context.info().limits.maxComputeWorkGroupCount[0];
  if (groups > limit) exceeded(what, groups, "workgroups", "maxComputeWorkGroupCount[0]", limit);
  return static_cast<uint32_t>(std::max<uint64_t>(1, groups));
}

DispatchSize checkedGroups2D(const Context& context, uint64_t groups, std::string_view what) {
  const auto& limits = context.info().limits;
  const uint64_t maxX = limits.maxComputeWorkGroupCount[0];
  const uint64_t maxY = limits.maxComputeWorkGroupCount[1];
  if (groups > maxX * maxY)
    exceeded(what, groups, "workgroups",
             "maxComputeWorkGroupCount[0] x [1] (" + std::to_string(maxX) + " x " +
                 std::to_string(maxY) + ")",
             maxX * maxY);
  DispatchSize d;
  d.x = static_cast<uint32_t>(std::clamp<uint64_t>(groups, 1, maxX));
  d.y = static_cast<uint32_t>(std::max<uint64_t>(1, (groups + d.x - 1) / d.x));
  return d;
}

DispatchSize checkedGroupsXY(const Context& context, uint64_t x, uint64_t y,
                             std::string_view what) {
  const auto& limits = context.info().limits;
  if (x > limits.maxComputeWorkGroupCount[0])
    exceeded(what, x, "workgroups in x", "maxComputeWorkGroupCount[0]",
             limits.maxComputeWorkGroupCount[0]);
  if (y > limits.maxComputeWorkGroupCount[1])
    exceeded(what, y, "workgroups in y", "maxComputeWorkGroupCount[1]",
             limits.maxComputeWorkGroupCount[1]);
  return {static_cast<uint32_t>(std::max<uint64_t>(1, x)),
          static_cast<uint32_t>(std::max<uint64_t>(1, y))};
}

void checkDrawIndirectCount(const Context& context, uint64_t drawCount, std::string_view what) {
  const uint32_t limit = context.info().limits.maxDrawIndirectCount;
  if (drawCount > limit) exceeded(what, drawCount, "draws", "maxDrawIndirectCount", limit);
}

}  // namespace osd_cull::vulkan
