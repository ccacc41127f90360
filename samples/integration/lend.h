#pragma once
// What the program lends osd_cull: its device (with the feature chain it enabled) and its
// attachments with their render passes. Plain copies of handles; osd_cull owns none.
#include "app_vulkan.h"
#include "osd_cull/frame/draw/render_target.h"
#include "osd_cull/vk/external_device.h"

namespace app {

/// The device, queue and enabled features as osd_cull::vulkan::Context takes them.
osd_cull::vulkan::ExternalDevice lendDevice(const Device& device);

/// The attachments as osd_cull::frame::RenderTarget takes them (render passes when the
/// target has them, else dynamic rendering), resting in Target::kColorLayout and
/// Target::kDepthLayout.
osd_cull::frame::ExternalTarget lendTarget(const Target& target);

}  // namespace app
