// Buffers beyond maxStorageBufferRange (issue 9, "a million patches"): control points read
// through a buffer device address draw and cull exactly as the bound points, and every limit
// that is not lifted is an error naming it before anything is recorded. The limits are
// lowered through ContextOptions::adjustDeviceInfo, so a small mesh exercises the paths that
// a million patches takes on lavapipe (128 MiB: 524,288 Bezier patches).
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/limits.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"

#include <shared/bounds_layout.h>
#include <shared/cull_layout.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>

namespace osd_cull {
namespace {

const bound::BackPatchValidity kClosed{true, "closed test surface"};

// A closed sphere of Bezier patches, some of them Gregory.
PatchSet sphere() {
  const PatchSet s = scene::bezierSphere({0.2, -0.1, 0.3}, 1.5, 6);
  return scene::convertToGregory(s, [](uint32_t p) { return p % 5 == 2; });
}

VkDeviceSize pointBytes(const PatchSet& s) {
  return VkDeviceSize{s.points.size()} * frame::GpuPatchSet::kOwnPointStride * sizeof(float);
}

// A validated context whose device facts `adjust` edits; fails the test on any validation
// message when it goes away.
class AdjustedContext {
 public:
  explicit AdjustedContext(std::function<void(vulkan::DeviceInfo&)> adjust)
      : log_(std::make_shared<vulkan::ValidationLog>()) {
    vulkan::ContextOptions options = test::validatedContextOptions(log_);
    options.adjustDeviceInfo = std::move(adjust);
    context_ = std::make_unique<vulkan::Context>(options);
  }
  ~AdjustedContext() {
    context_.reset();
    EXPECT_EQ(log_->count(), 0u) << "Vulkan validation reported:\n" << log_->summary();
  }
  vulkan::Context& operator*() { return *context_; }

 private:
  std::shared_ptr<vulkan::ValidationLog> log_;
  std::unique_ptr<vulkan::Context> context_;
};

void withoutDeviceAddress(vulkan::DeviceInfo& info) { info.optional.bufferDeviceAddress = false; }

// What one context draws and culls over a few views.
struct Outcome {
  std::vector<std::vector<uint32_t>> items;
  std::vector<std::vector<float>> depth;
  std::vector<uint64_t> tessEvaluations;
  std::vector<std::vector<uint32_t>> results;
  std::vector<uint32_t> survivors;
};

Outcome drawAndCull(vulkan::Context& context, const PatchSet& set, const std::string& backPatch,
                    bool expectAddress) {
  frame::GpuPatchSet gpu(context, set);
  EXPECT_EQ(gpu.pointsByAddress(), expectAddress);
  frame::CullSettings settings;
  settings.backPatch = backPatch;
  settings.backPatchValidity = kClosed;
  frame::CullPass pass(context, gpu, set, settings);
  frame::Renderer renderer(context);
  frame::ViewSetOptions vo;
  vo.count = 3;
  vo.width = 96;
  vo.height = 64;
  frame::RenderTarget target(context, vo.width, vo.height);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 3;
  Outcome out;
  for (const auto& camera : frame::randomViews(frame::boundsOf(set.points), vo)) {
    const auto stats = renderer.render(target, camera, gpu, &set, options);
    out.items.push_back(target.readItems(context));
    out.depth.push_back(target.readDepth(context));
    out.tessEvaluations.push_back(stats.statistics.tessEvaluationInvocations);
    pass.run(camera, options.tessellation);
    out.results.emplace_back(pass.results().begin(), pass.results().end());
    out.survivors.push_back(pass.counts().survivors());
  }
  return out;
}

void expectSame(const Outcome& a, const Outcome& b) {
  ASSERT_EQ(a.items.size(), b.items.size());
  for (size_t v = 0; v < a.items.size(); ++v) {
    EXPECT_EQ(a.items[v], b.items[v]) << "view " << v;
    EXPECT_EQ(a.depth[v], b.depth[v]) << "view " << v;
    EXPECT_EQ(a.tessEvaluations[v], b.tessEvaluations[v]) << "view " << v;
    EXPECT_EQ(a.results[v], b.results[v]) << "view " << v;
    EXPECT_EQ(a.survivors[v], b.survivors[v]) << "view " << v;
  }
}

// Points read through their address, from a buffer larger than the (lowered) storage range,
// with the cull dispatch spread over y (a lowered maxComputeWorkGroupCount[0]), give the
// same images, work and cull results as points bound as a descriptor.
TEST(LargeBuffers, AddressPathDrawsAndCullsLikeTheBoundPath) {
  const PatchSet set = sphere();
  const uint32_t n = set.patchCount();
  // Below the points, above everything else the draw and the cull pass bind (cones: 64 B
  // per patch, the tangent-plane table, indirect commands).
  const VkDeviceSize range = std::max<VkDeviceSize>(64 * VkDeviceSize{n}, 8192);
  ASSERT_GT(pointBytes(set), range);
  for (const std::string method : {"tcone", "tangent-plane-16"}) {
    Outcome bound, address;
    {
      AdjustedContext context(withoutDeviceAddress);
      bound = drawAndCull(*context, set, method, false);
    }
    {
      AdjustedContext context([&](vulkan::DeviceInfo& info) {
        info.limits.maxStorageBufferRange = static_cast<uint32_t>(range);
        info.limits.maxComputeWorkGroupCount[0] = 5;  // tangent-plane-16: 4 patches a group
      });
      if (!(*context).info().optional.bufferDeviceAddress)
        GTEST_SKIP() << "the device lacks bufferDeviceAddress";
      address = drawAndCull(*context, set, method, true);
    }
    expectSame(bound, address);
    // Something was drawn and something culled, so the comparison says something.
    EXPECT_GT(std::count_if(bound.items[0].begin(), bound.items[0].end(),
                            [](uint32_t i) { return i != 0; }),
              100)
        << method;
    EXPECT_LT(bound.survivors[0], n) << method;
  }
}

TEST(LargeBuffers, PointsBeyondTheStorageRangeWithoutDeviceAddressAreANamedError) {
  const PatchSet set = sphere();
  AdjustedContext context([&](vulkan::DeviceInfo& info) {
    withoutDeviceAddress(info);
    info.limits.maxStorageBufferRange = static_cast<uint32_t>(pointBytes(set) - 16);
  });
  try {
    frame::GpuPatchSet gpu(*context, set);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("maxStorageBufferRange"), std::string::npos) << what;
    EXPECT_NE(what.find("bufferDeviceAddress"), std::string::npos) << what;
    EXPECT_NE(what.find("control points"), std::string::npos) << what;
  }
}

// Runs `make` and expects an osd_cull::Error whose text contains every one of `words`.
void expectErrorNaming(const std::function<void()>& make,
                       std::initializer_list<const char*> words) {
  try {
    make();
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const char* w : words) EXPECT_NE(what.find(w), std::string::npos) << what;
  }
}

TEST(LargeBuffers, CullBuffersBeyondTheStorageRangeAreANamedError) {
  const PatchSet set = sphere();
  const uint32_t n = set.patchCount();
  // The patch set fits (params 8 B per patch), the cones (64 B per patch) do not.
  AdjustedContext context(
      [&](vulkan::DeviceInfo& info) { info.limits.maxStorageBufferRange = 32 * n; });
  if (!(*context).info().optional.bufferDeviceAddress)
    GTEST_SKIP() << "the device lacks bufferDeviceAddress";
  frame::GpuPatchSet gpu(*context, set);
  expectErrorNaming([&] { frame::CullPass pass(*context, gpu, set, {}); },
                    {"cones", "maxStorageBufferRange", std::to_string(32 * n).c_str()});
}

TEST(LargeBuffers, DispatchesBeyondTheWorkGroupCountAreANamedError) {
  const PatchSet set = sphere();
  AdjustedContext context([&](vulkan::DeviceInfo& info) {
    info.limits.maxComputeWorkGroupCount[0] = 2;
    info.limits.maxComputeWorkGroupCount[1] = 2;
  });
  frame::GpuPatchSet gpu(*context, set);
  frame::CullSettings settings;
  settings.backPatch = "tangent-plane-16";  // 4 patches per group: more than 2 x 2 groups
  settings.backPatchValidity = kClosed;
  ASSERT_GT(set.patchCount(), 16u);
  expectErrorNaming([&] { frame::CullPass pass(*context, gpu, set, settings); },
                    {"cull dispatch", "maxComputeWorkGroupCount"});
  EXPECT_EQ(vulkan::checkedGroups2D(*context, 3, "three").x, 2u);
  EXPECT_EQ(vulkan::checkedGroups2D(*context, 3, "three").y, 2u);
}

// The bounds pass's output of `pass` after one run (raw floats).
std::vector<float> boundsOutput(vulkan::Context& context, frame::BoundsPass& pass) {
  pass.run(1.01 * 2.0 / 16777216.0);  // |coordinate| < 2 on the sphere
  EXPECT_GT(pass.dispatchCount(), 0u);
  return vulkan::readback<float>(context, pass.cullData());
}

// The bounds pass past its old limit (issue 10): its 1 KiB-per-patch scratch buffer is gone
// (the working vectors live in shared memory), so with maxStorageBufferRange lowered to its
// output (64 B per patch, 16 times less than the scratch needed) and the work-group count
// to 2 x 16 (the dispatch spread over x and y), a small mesh takes the path of a
// 2-million-patch mesh and writes exactly what an unrestricted device writes. Below the
// output the error names the limit.
TEST(LargeBuffers, BoundsPassNeedsOnlyItsOutputInOneDescriptor) {
  const PatchSet set = sphere();
  const uint32_t n = set.patchCount();
  const uint32_t output = n * shader::kConeVec4s * 16;
  ASSERT_GT(n, 2u * shader::kBoundsGroupSize);  // more than two groups: the 2D dispatch
  std::vector<bound::DisplacementRange> ranges(n, bound::DisplacementRange{-0.1, 0.2});
  std::vector<std::vector<float>> outputs[2];
  for (int restricted = 0; restricted < 2; ++restricted) {
    AdjustedContext context([&](vulkan::DeviceInfo& info) {
      if (!restricted) return;
      info.limits.maxStorageBufferRange = output;
      info.limits.maxComputeWorkGroupCount[0] = 2;
    });
    if (!(*context).info().optional.bufferDeviceAddress)
      GTEST_SKIP() << "the device lacks bufferDeviceAddress";
    frame::GpuPatchSet gpu(*context, set);
    frame::BoundsPass tcone(*context, gpu, bound::BackPatchMethod::TCone);
    outputs[restricted].push_back(boundsOutput(*context, tcone));
    frame::BoundsPass con(*context, gpu, bound::DisplacedExtension::CoN, ranges);
    outputs[restricted].push_back(boundsOutput(*context, con));
  }
  ASSERT_EQ(outputs[0].size(), outputs[1].size());
  for (size_t k = 0; k < outputs[0].size(); ++k)
    EXPECT_EQ(outputs[0][k], outputs[1][k]) << "output " << k;
  AdjustedContext small(
      [&](vulkan::DeviceInfo& info) { info.limits.maxStorageBufferRange = output - 16; });
  frame::GpuPatchSet gpu(*small, set);
  expectErrorNaming([&] { frame::BoundsPass pass(*small, gpu, bound::BackPatchMethod::NCone); },
                    {"BoundsPass", "cull data", "maxStorageBufferRange"});
}

TEST(LargeBuffers, IndirectDrawsBeyondMaxDrawIndirectCountAreANamedError) {
  const PatchSet set = sphere();
  AdjustedContext context([&](vulkan::DeviceInfo& info) { info.limits.maxDrawIndirectCount = 4; });
  frame::GpuPatchSet gpu(*context, set);
  expectErrorNaming([&] { frame::CullPass pass(*context, gpu, set, {}); },
                    {"indirect draws", "maxDrawIndirectCount"});
}

TEST(LargeBuffers, DescriptorsBeyondTheStorageRangeAreANamedError) {
  AdjustedContext context(
      [&](vulkan::DeviceInfo& info) { info.limits.maxStorageBufferRange = 1024; });
  const vulkan::Buffer big(*context, 2048, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::DescriptorWriter writer;
  writer.buffer(3, big, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0, 1024);  // a range that fits
  expectErrorNaming([&] { writer.buffer(4, big); },
                    {"binding 4", "2048", "maxStorageBufferRange of 1024"});
}

TEST(LargeBuffers, AllocationsBeyondTheMemoryHeapAreANamedError) {
  AdjustedContext context(nullptr);
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties((*context).physicalDevice(), &memory);
  VkDeviceSize largest = 0;
  for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
    largest = std::max(largest, memory.memoryHeaps[h].size);
  expectErrorNaming(
      [&] { vulkan::Buffer huge(*context, largest + 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT); },
      {"memory heap", std::to_string(largest).c_str()});
}

}  // namespace
}  // namespace osd_cull
