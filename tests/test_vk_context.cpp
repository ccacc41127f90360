// Device layer: device choice, feature checks, validation wiring, memory sub-allocation.
#include "osd_cull/error.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/device_features.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <numeric>

namespace osd_cull {
namespace {

using test::VkTest;

using vulkan::DeviceCandidate;
constexpr auto kCpu = VK_PHYSICAL_DEVICE_TYPE_CPU;
constexpr auto kDiscrete = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
constexpr auto kIntegrated = VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;

TEST(VkDeviceSelection, EmptySelectorPrefersADiscreteThenAnIntegratedGpuThenLavapipe) {
  const std::vector<DeviceCandidate> all = {{"llvmpipe (LLVM 15.0.6, 256 bits)", kCpu},
                                            {"Intel UHD", kIntegrated},
                                            {"AMD Radeon", kDiscrete}};
  EXPECT_EQ(vulkan::selectDevice(all, ""), 2u);
  const std::vector<DeviceCandidate> noDiscrete = {{"llvmpipe", kCpu}, {"Intel UHD", kIntegrated}};
  EXPECT_EQ(vulkan::selectDevice(noDiscrete, ""), 1u);
  const std::vector<DeviceCandidate> cpuOnly = {{"llvmpipe", kCpu}};
  EXPECT_EQ(vulkan::selectDevice(cpuOnly, ""), 0u);
}

TEST(VkDeviceSelection, IndexAndCaseInsensitiveNameSubstring) {
  const std::vector<DeviceCandidate> names = {
      {"AMD Radeon", kDiscrete}, {"llvmpipe (LLVM 15)", kCpu}, {"Intel UHD", kIntegrated}};
  EXPECT_EQ(vulkan::selectDevice(names, "2"), 2u);
  EXPECT_EQ(vulkan::selectDevice(names, "intel"), 2u);
  EXPECT_EQ(vulkan::selectDevice(names, "RADEON"), 0u);
  EXPECT_EQ(vulkan::selectDevice(names, "llvmpipe"), 1u);
}

TEST(VkDeviceSelection, NoMatchListsTheDevices) {
  const std::vector<DeviceCandidate> names = {{"AMD Radeon", kDiscrete}, {"llvmpipe", kCpu}};
  try {
    vulkan::selectDevice(names, "nvidia");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nvidia"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("1: llvmpipe (CPU)"), std::string::npos);
  }
  EXPECT_THROW(vulkan::selectDevice(names, "7"), Error);
  EXPECT_THROW(vulkan::selectDevice({}, ""), Error);
}

TEST(VkDeviceSelection, TheChoiceIsReportedThroughTheLogCallback) {
  std::vector<std::string> lines;
  vulkan::ContextOptions options;
  options.log = [&](const std::string& line) { lines.push_back(line); };
  vulkan::Context context(options);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find(context.info().name), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(vulkan::toString(context.info().type)), std::string::npos) << lines[0];
}

TEST_F(VkTest, ContextReportsTheChosenDeviceAndItsLimits) {
  const vulkan::DeviceInfo& info = context().info();
  EXPECT_FALSE(info.name.empty());
  EXPECT_GE(info.apiVersion, VK_API_VERSION_1_2);
  EXPECT_GE(info.limits.maxTessellationPatchSize, 20u);
  EXPECT_GE(info.limits.maxTessellationGenerationLevel, 64u);
  EXPECT_NE(context().device(), VK_NULL_HANDLE);
  EXPECT_NE(context().validationLog(), nullptr);
}

TEST_F(VkTest, ValidationLayerReportsMisuse) {
  // A buffer with no usage bits is invalid (VUID-VkBufferCreateInfo-usage-requiredbitmask);
  // the layer must see it, which proves every other test runs with validation live.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 256;
  info.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(context().device(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS) vkDestroyBuffer(context().device(), buffer, nullptr);
  ASSERT_GE(validationLog().count(), 1u);
  EXPECT_NE(validationLog().summary().find("usage"), std::string::npos);
  validationLog().clear();
}

TEST_F(VkTest, SynchronizationValidationReportsAHazard) {
  // A copy reads a buffer that a fill just wrote, with no barrier between: a
  // read-after-write hazard only synchronization validation sees.
  vulkan::Buffer a(context(), 1024, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::Buffer b(context(), 1024, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  context().submit([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, a.handle(), 0, VK_WHOLE_SIZE, 1);
    const VkBufferCopy region{0, 0, 1024};
    vkCmdCopyBuffer(cmd, a.handle(), b.handle(), 1, &region);
  });
  ASSERT_GE(validationLog().count(), 1u);
  EXPECT_NE(validationLog().summary().find("SYNC-HAZARD-READ"), std::string::npos)
      << validationLog().summary();
  validationLog().clear();
}

TEST_F(VkTest, BuffersShareLargeMemoryBlocks) {
  const auto before = context().memory().stats();
  {
    std::vector<vulkan::Buffer> buffers;
    for (int i = 0; i < 50; ++i)
      buffers.emplace_back(context(), 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const auto during = context().memory().stats();
    EXPECT_EQ(during.allocations - before.allocations, 50u);
    EXPECT_LE(during.blocks - before.blocks, 1u);  // all 50 in one block
    EXPECT_GE(during.usedBytes - before.usedBytes, 50u * 4096u);
  }
  const auto after = context().memory().stats();
  EXPECT_EQ(after.allocations, before.allocations);
  EXPECT_EQ(after.usedBytes, before.usedBytes);  // freed ranges coalesce back
}

TEST_F(VkTest, LargeBufferGetsItsOwnBlockFreedWithIt) {
  const auto before = context().memory().stats();
  {
    vulkan::Buffer big(context(), VkDeviceSize{48} << 20, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    EXPECT_EQ(context().memory().stats().blocks, before.blocks + 1);
  }
  EXPECT_EQ(context().memory().stats().blocks, before.blocks);
}

TEST_F(VkTest, UploadThenReadbackRoundTrips) {
  std::vector<uint32_t> values(1000);
  std::iota(values.begin(), values.end(), 7u);
  vulkan::Buffer buffer(context(), values.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<uint32_t>(context(), buffer, values);
  EXPECT_EQ(vulkan::readback<uint32_t>(context(), buffer), values);
  std::vector<uint32_t> part = {1, 2, 3};
  vulkan::upload<uint32_t>(context(), buffer, part, 10);
  const auto back = vulkan::readback<uint32_t>(context(), buffer);
  EXPECT_EQ(back[9], 16u);
  EXPECT_EQ(back[10], 1u);
  EXPECT_EQ(back[12], 3u);
  EXPECT_EQ(back[13], 20u);
  EXPECT_THROW(vulkan::upload<uint32_t>(context(), buffer, values, 1), Error);
}

// A fresh buffer filled by initializeGenerated holds what the pieces wrote, through the
// direct path where the memory is host-coherent (lavapipe: device-local memory is) and
// through staging otherwise (an Upload buffer is coherent too; the staging path is what
// uploadGenerated tests above); the pieces are whole kUploadChunkBytes from offset 0.
TEST_F(VkTest, InitializeGeneratedFillsAFreshBufferPieceByPiece) {
  const VkDeviceSize bytes = vulkan::kUploadChunkBytes + 4096;  // two pieces
  vulkan::Buffer buffer(context(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  std::vector<VkDeviceSize> offsets;
  vulkan::initializeGenerated(context(), buffer, bytes,
                              [&](std::span<std::byte> piece, VkDeviceSize offset) {
                                offsets.push_back(offset);
                                auto* words = reinterpret_cast<uint32_t*>(piece.data());
                                for (size_t i = 0; i < piece.size() / 4; ++i)
                                  words[i] = uint32_t(offset / 4 + i) * 3u + 1u;
                              });
  EXPECT_EQ(offsets, (std::vector<VkDeviceSize>{0, vulkan::kUploadChunkBytes}));
  const auto back = vulkan::readback<uint32_t>(context(), buffer);
  ASSERT_EQ(back.size(), bytes / 4);
  size_t wrong = 0;
  for (size_t i = 0; i < back.size(); ++i) wrong += back[i] != uint32_t(i) * 3u + 1u;
  EXPECT_EQ(wrong, 0u);
  // lavapipe's single memory type is host-visible and coherent: the direct path ran.
  if (context().info().name.find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(buffer.hostCoherent());
  }
  EXPECT_THROW(vulkan::initializeGenerated(context(), buffer, bytes + 4,
                                           [](std::span<std::byte>, VkDeviceSize) {}),
               Error);
}

TEST_F(VkTest, FailedVulkanCallNamesTheCallAndResult) {
  try {
    vulkan::check(VK_ERROR_DEVICE_LOST, "vkQueueSubmit(queue, ...)");
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("vkQueueSubmit"), std::string::npos);
    EXPECT_NE(what.find("VK_ERROR_DEVICE_LOST"), std::string::npos);
    EXPECT_NE(what.find("test_vk_context.cpp"), std::string::npos);
  }
}

}  // namespace
}  // namespace osd_cull
