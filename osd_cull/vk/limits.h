#pragma once
/// \file limits.h
/// \brief Device-limit checks that name the limit, for callers to run before recording.
///
/// Every check throws osd_cull::Error with what was asked, the limit's Vulkan name and its
/// value on this device (Context::info().limits, which tests may lower through
/// ContextOptions::adjustDeviceInfo).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string_view>

namespace osd_cull::vulkan {

class Context;

/// \brief Checks that one storage-buffer descriptor of `bytes` fits maxStorageBufferRange.
/// `what` names the buffer ("the cones of 1000000 patches").
void checkStorageBufferRange(const Context& context, VkDeviceSize bytes, std::string_view what);

/// \brief Workgroup counts of a dispatch over `groups` groups, spread over x and y when
/// `groups` exceeds maxComputeWorkGroupCount[0] (the shader flattens gl_WorkGroupID as
/// y * gl_NumWorkGroups.x + x and skips the groups past the end). At least one group.
struct DispatchSize {
  uint32_t x = 1;
  uint32_t y = 1;
};

/// \brief A 1D dispatch of `groups` groups; x only.
/// \throws osd_cull::Error naming maxComputeWorkGroupCount[0] when it does not fit.
uint32_t checkedGroups1D(const Context& context, uint64_t groups, std::string_view what);

/// \brief A dispatch of `groups` groups over x and y (see DispatchSize).
/// \throws osd_cull::Error naming maxComputeWorkGroupCount[0] and [1] when even x * y
/// cannot hold them.
DispatchSize checkedGroups2D(const Context& context, uint64_t groups, std::string_view what);

/// \brief A dispatch of exactly `x` by `y` groups (e.g. y = one row per instance).
/// \throws osd_cull::Error naming maxComputeWorkGroupCount[0] or [1] when one does not fit.
DispatchSize checkedGroupsXY(const Context& context, uint64_t x, uint64_t y, std::string_view what);

/// \brief Checks that an indirect draw call of up to `drawCount` commands fits
/// maxDrawIndirectCount.
void checkDrawIndirectCount(const Context& context, uint64_t drawCount, std::string_view what);

}  // namespace osd_cull::vulkan
