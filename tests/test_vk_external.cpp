// The application's device lent to osd_cull: adopted without ownership, checked for the
// features osd_cull needs (the error names each missing one), and usable by osd_cull.
#include "app_vulkan.h"
#include "lend.h"
#include "osd_cull/error.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/external_device.h"
#include "osd_cull/vk/transfer.h"

#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

// The integration sample's application device, with validation (and every message kept).
struct AppDevice : app::Device {
  explicit AppDevice(app::DeviceOptions options = {}) : app::Device(validated(options)) {}
  static app::DeviceOptions validated(app::DeviceOptions o) {
    o.validation = true;
    return o;
  }
  vulkan::ExternalDevice lend() const { return app::lendDevice(*this); }
  std::string summary() const {
    std::string out;
    for (const std::string& m : validationMessages) out += m + "\n";
    return out;
  }
};
using AppDeviceOptions = app::DeviceOptions;

std::string adoptionError(const vulkan::ExternalDevice& lent) {
  try {
    vulkan::Context context(lent);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(VkExternalDevice, AdoptedContextWorksAndDestroysNeitherDeviceNorInstance) {
  AppDevice app;
  {
    vulkan::Context context(app.lend());
    EXPECT_FALSE(context.ownsDevice());
    EXPECT_EQ(context.device(), app.device);
    EXPECT_EQ(context.queue(), app.queue);
    EXPECT_EQ(context.validationLog(), nullptr);
    std::vector<uint32_t> values(1000);
    std::iota(values.begin(), values.end(), 7u);
    vulkan::Buffer buffer(context, values.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vulkan::upload<uint32_t>(context, buffer, values);
    EXPECT_EQ(vulkan::readback<uint32_t>(context, buffer), values);
  }
  // The application's device is still alive and usable.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 256;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  EXPECT_EQ(vkCreateBuffer(app.device, &info, nullptr, &buffer), VK_SUCCESS);
  vkDestroyBuffer(app.device, buffer, nullptr);
  EXPECT_EQ(vkDeviceWaitIdle(app.device), VK_SUCCESS);
  EXPECT_TRUE(app.validationMessages.empty()) << app.summary();
}

TEST(VkExternalDevice, AdoptionNamesEveryFeatureTheApplicationDidNotEnable) {
  AppDeviceOptions options;
  options.tessellationShader = false;
  options.drawIndirectCount = false;
  AppDevice app(options);
  const std::string error = adoptionError(app.lend());
  EXPECT_NE(error.find("tessellationShader"), std::string::npos) << error;
  EXPECT_NE(error.find("drawIndirectCount"), std::string::npos) << error;
  EXPECT_EQ(error.find("multiDrawIndirect"), std::string::npos) << error;  // it was enabled
  EXPECT_TRUE(app.validationMessages.empty()) << app.summary();
}

TEST(VkExternalDevice, AdoptionNamesMissingHandlesAndAnOldInstance) {
  const std::string error = adoptionError(vulkan::ExternalDevice{});
  for (const char* name :
       {"instance", "physicalDevice", "device", "queue", "apiVersion", "enabledFeatures"})
    EXPECT_NE(error.find(name), std::string::npos) << name << " in: " << error;

  AppDevice app;
  vulkan::ExternalDevice lent = app.lend();
  lent.apiVersion = VK_API_VERSION_1_1;
  EXPECT_NE(adoptionError(lent).find("Vulkan 1.2"), std::string::npos) << adoptionError(lent);
  lent = app.lend();
  lent.queueFamily = 99;
  EXPECT_NE(adoptionError(lent).find("queue family 99"), std::string::npos);
}

TEST(VkExternalDevice, DynamicRenderingIsUsedOnlyWhenTheApplicationEnabledIt) {
  {
    AppDevice app;
    vulkan::Context context(app.lend());
    EXPECT_TRUE(context.info().optional.dynamicRendering);
    EXPECT_NE(context.cmdBeginRendering(), nullptr);
    EXPECT_NE(context.cmdEndRendering(), nullptr);
  }
  AppDeviceOptions options;
  options.dynamicRendering = false;
  AppDevice app(options);
  vulkan::Context context(app.lend());
  EXPECT_FALSE(context.info().optional.dynamicRendering);
  EXPECT_EQ(context.cmdBeginRendering(), nullptr);
}

}  // namespace
}  // namespace osd_cull
