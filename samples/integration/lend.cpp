#include "lend.h"

namespace app {

osd_cull::vulkan::ExternalDevice lendDevice(const Device& d) {
  osd_cull::vulkan::ExternalDevice lent;
  lent.instance = d.instance;
  lent.physicalDevice = d.physical;
  lent.device = d.device;
  lent.queue = d.queue;
  lent.queueFamily = d.family;
  lent.apiVersion = VK_API_VERSION_1_3;
  lent.enabledFeatures = &d.features;
  return lent;
}

osd_cull::frame::ExternalTarget lendTarget(const Target& t) {
  osd_cull::frame::ExternalTarget lent;
  lent.width = t.width;
  lent.height = t.height;
  lent.colorImage = t.color.image;
  lent.colorView = t.color.view;
  lent.colorFormat = t.color.format;
  lent.colorUsage = t.color.usage;
  lent.colorLayout = Target::kColorLayout;
  lent.depthImage = t.depth.image;
  lent.depthView = t.depth.view;
  lent.depthFormat = t.depth.format;
  lent.depthUsage = t.depth.usage;
  lent.depthLayout = Target::kDepthLayout;
  lent.clearPass = t.clearPass;
  lent.loadPass = t.loadPass;
  lent.framebuffer = t.framebuffer;
  return lent;
}

}  // namespace app
