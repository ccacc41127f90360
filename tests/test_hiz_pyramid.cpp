// The Hi-Z pyramid built in compute equals the double-precision reference texel for texel:
// blocked (three levels a dispatch, the top level from a copy of the depth or from the
// depth image, the others with the min/max sampler or four fetches), in one dispatch
// (single pass) and per level with the min/max sampler reduction and with four texel
// fetches, at half and full resolution, for power-of-two, odd and tiny sizes.
#include "osd_cull/bound/occlusion.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/image.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

namespace osd_cull {
namespace {

using frame::HiZReduction;

class HiZPyramidTest : public test::VkTest {
 protected:
  // A sampled D32_SFLOAT image holding `depth` (rows top to bottom), left in GENERAL.
  vulkan::Image depthImage(uint32_t w, uint32_t h, const std::vector<float>& depth) {
    vulkan::Image image(context(),
                        {w, h, VK_FORMAT_D32_SFLOAT,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    upload(image, depth, VK_IMAGE_LAYOUT_UNDEFINED);
    return image;
  }

  // Replaces the image's contents; it goes from `layout` to GENERAL.
  void upload(const vulkan::Image& image, const std::vector<float>& depth, VkImageLayout layout) {
    vulkan::Buffer staging(context(), depth.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                           vulkan::MemoryUse::Upload);
    std::memcpy(staging.mapped(), depth.data(), depth.size() * 4);
    context().submit([&](VkCommandBuffer cmd) {
      vulkan::imageBarrier(cmd, image, layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           vulkan::scope::kAll, vulkan::scope::kTransferWrite);
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
      region.imageExtent = {image.width(), image.height(), 1};
      vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(),
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
      vulkan::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_IMAGE_LAYOUT_GENERAL, vulkan::scope::kTransferWrite,
                           vulkan::scope::kAll);
    });
  }

  static std::vector<float> randomDepth(uint32_t w, uint32_t h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> d(size_t{w} * h);
    // Steps with noise: a few distinct regions, so coarse levels differ.
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x)
        d[size_t{y} * w + x] = (x * 3 < w ? 0.3f : (y * 2 < h ? 0.6f : 0.45f)) * u(rng) + 0.1f;
    return d;
  }

  // Builds on the GPU and compares every texel with the reference; returns the levels.
  std::vector<std::vector<float>> buildAndCompare(uint32_t w, uint32_t h,
                                                  const std::vector<float>& depth, bool full,
                                                  HiZReduction reduction,
                                                  frame::HiZOptions options = {}) {
    const vulkan::Image image = depthImage(w, h, depth);
    options.fullResolution = full;
    options.reduction = reduction;
    frame::HiZPyramid pyramid(context(), image, options);
    const bool blocked = reduction == HiZReduction::Blocked || reduction == HiZReduction::Auto;
    EXPECT_EQ(pyramid.usesSampler(),
              reduction == HiZReduction::Sampler ||
                  (blocked && !options.fourTapLevels && frame::supportsMinmaxReduction(context())));
    EXPECT_EQ(pyramid.singlePass(), reduction == HiZReduction::SinglePass);
    EXPECT_EQ(pyramid.blocked(), blocked);
    EXPECT_EQ(pyramid.copiesDepth(), blocked && !options.readDepthImage);
    pyramid.build(context(), VK_IMAGE_LAYOUT_GENERAL);
    const auto levels = pyramid.readLevels(context());
    const bound::HiZPyramid ref = bound::buildHiZPyramid(depth, w, h, full);
    EXPECT_EQ(levels.size(), ref.levels.size());
    for (size_t l = 0; l < std::min(levels.size(), ref.levels.size()); ++l) {
      EXPECT_EQ(levels[l].size(), ref.levels[l].size()) << "level " << l;
      const uint32_t lw = ref.layout.levelWidth(uint32_t(l));
      size_t mismatches = 0;
      for (size_t i = 0; i < std::min(levels[l].size(), ref.levels[l].size()); ++i)
        if (double{levels[l][i]} != ref.levels[l][i] && mismatches++ < 5)
          ADD_FAILURE() << w << "x" << h << (full ? " full" : " half") << " level " << l
                        << " texel (" << i % lw << ", " << i / lw << "): gpu " << levels[l][i]
                        << ", reference " << ref.levels[l][i];
    }
    return levels;
  }

  // Every level equals the reference's texel for texel (stops at the first difference).
  static void expectReference(const std::vector<std::vector<float>>& levels,
                              const std::vector<float>& depth, uint32_t w, uint32_t h, bool full,
                              const std::string& what) {
    const bound::HiZPyramid ref = bound::buildHiZPyramid(depth, w, h, full);
    ASSERT_EQ(levels.size(), ref.levels.size()) << what;
    for (size_t l = 0; l < levels.size(); ++l)
      for (size_t i = 0; i < levels[l].size(); ++i)
        ASSERT_EQ(double{levels[l][i]}, ref.levels[l][i])
            << what << (full ? " full" : " half") << " level " << l << " texel " << i;
  }

  void requireSampler() {
    if (!frame::supportsMinmaxReduction(context()))
      GTEST_SKIP() << "device has no min/max sampler reduction";
  }
};

struct Size {
  uint32_t w, h;
};
const Size kSizes[] = {{1, 1}, {2, 3}, {5, 5}, {64, 64}, {1, 17}, {40, 1}, {333, 517}};

TEST_F(HiZPyramidTest, BlockedBuildEqualsTheReference) {
  // Every source of the first dispatch (the depth copied as RGBA rows, or read from the
  // image) and of the others (MAX sampler, four fetches); widths that are and are not
  // multiples of the four pixels of a row texel, sizes below and above one block; 4000 x 8
  // has 12 levels: blocked 0-2 and 3-5, the tail 6-11.
  const Size sizes[] = {{1, 1},  {2, 3},     {5, 5},   {64, 64}, {1, 17},
                        {40, 1}, {333, 517}, {130, 7}, {4000, 8}};
  for (const Size& s : sizes)
    for (bool full : {false, true})
      for (bool image : {false, true})
        for (bool fourTap : {false, true}) {
          frame::HiZOptions o;
          o.readDepthImage = image;
          o.fourTapLevels = fourTap;
          buildAndCompare(s.w, s.h, randomDepth(s.w, s.h, s.w * 7 + s.h), full,
                          HiZReduction::Blocked, o);
        }
}

TEST_F(HiZPyramidTest, BlockedBuildNeedsTwoDispatchesAt720pAnd1080p) {
  // Levels 0-2 blocked, 3-10 in the tail's workgroup; more levels, more blocked dispatches.
  const struct {
    Size size;
    uint32_t levels, dispatches;
  } cases[] = {{{1280, 720}, 11, 2}, {{1920, 1080}, 11, 2}, {{4000, 8}, 12, 3}, {{5, 5}, 3, 1}};
  for (const auto& c : cases) {
    const vulkan::Image image =
        depthImage(c.size.w, c.size.h, std::vector<float>(size_t{c.size.w} * c.size.h, 0.5f));
    const frame::HiZPyramid pyramid(context(), image);
    EXPECT_TRUE(pyramid.blocked());
    EXPECT_TRUE(pyramid.copiesDepth());
    EXPECT_EQ(pyramid.layout().levelCount, c.levels) << c.size.w << "x" << c.size.h;
    EXPECT_EQ(pyramid.dispatchCount(), c.dispatches) << c.size.w << "x" << c.size.h;
  }
}

TEST_F(HiZPyramidTest, BlockedBuildReadsADepthImageWithoutTransferUsage) {
  // An application's depth attachment may lack TRANSFER_SRC: no copy, gathers instead.
  const uint32_t w = 70, h = 45;
  const std::vector<float> depth = randomDepth(w, h, 5);
  const vulkan::Image owned = depthImage(w, h, depth);
  vulkan::ImageDesc desc = owned.desc();
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  const vulkan::Image borrowed = vulkan::Image::borrow(context(), owned.handle(), desc);
  frame::HiZPyramid pyramid(context(), borrowed);
  EXPECT_FALSE(pyramid.copiesDepth());
  pyramid.build(context(), VK_IMAGE_LAYOUT_GENERAL);
  expectReference(pyramid.readLevels(context()), depth, w, h, false, "borrowed");
}

TEST_F(HiZPyramidTest, FourTapReductionEqualsTheReference) {
  for (const Size s : kSizes)
    for (bool full : {false, true})
      buildAndCompare(s.w, s.h, randomDepth(s.w, s.h, s.w * 31 + s.h), full, HiZReduction::FourTap);
}

TEST_F(HiZPyramidTest, SinglePassBuildEqualsTheReference) {
  for (const Size s : kSizes)
    for (bool full : {false, true})
      buildAndCompare(s.w, s.h, randomDepth(s.w, s.h, s.w * 31 + s.h), full,
                      HiZReduction::SinglePass);
}

TEST_F(HiZPyramidTest, SinglePassBuildsLargeAndElongatedImagesInOneDispatch) {
  // 1280x720: many 64x64 tiles, the last workgroup builds levels 7-11. 4100x9: level 0 is
  // 8192x16 at full resolution, one row of tiles, the top levels one texel high.
  for (const Size s : {Size{1280, 720}, Size{4100, 9}, Size{130, 300}})
    for (bool full : {false, true}) {
      const vulkan::Image image = depthImage(s.w, s.h, randomDepth(s.w, s.h, s.w + 7 * s.h));
      EXPECT_EQ(
          frame::HiZPyramid(context(), image, {full, HiZReduction::SinglePass}).dispatchCount(),
          1u);
      buildAndCompare(s.w, s.h, randomDepth(s.w, s.h, s.w + 7 * s.h), full,
                      HiZReduction::SinglePass);
    }
}

TEST_F(HiZPyramidTest, SinglePassAndPerLevelBuildsAgree) {
  const uint32_t w = 300, h = 200;
  const std::vector<float> d = randomDepth(w, h, 5);
  for (bool full : {false, true})
    EXPECT_EQ(buildAndCompare(w, h, d, full, HiZReduction::SinglePass),
              buildAndCompare(w, h, d, full, HiZReduction::FourTap));
}

TEST_F(HiZPyramidTest, MinmaxSamplerReductionEqualsTheReference) {
  requireSampler();
  for (const Size s : kSizes)
    for (bool full : {false, true})
      buildAndCompare(s.w, s.h, randomDepth(s.w, s.h, s.w * 31 + s.h), full, HiZReduction::Sampler);
}

TEST_F(HiZPyramidTest, SamplerAndFourTapAgreeOnARenderedStep) {
  requireSampler();
  // A step with one far pixel in the last row and column of an odd-sized image: the
  // border texels must come out far in both.
  const uint32_t w = 37, h = 23;
  std::vector<float> d(w * h, 0.25f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = w / 2; x < w; ++x) d[y * w + x] = 0.75f;
  d[(h - 1) * w + (w - 1)] = 1.0f;
  for (bool full : {false, true}) {
    const auto a = buildAndCompare(w, h, d, full, HiZReduction::Sampler);
    const auto b = buildAndCompare(w, h, d, full, HiZReduction::FourTap);
    EXPECT_EQ(a, b);
  }
}

TEST_F(HiZPyramidTest, PlaneGivesThePlaneDepthInsideAndFarInThePadding) {
  const uint32_t w = 48, h = 32;  // padded to 64 x 32
  const std::vector<float> d(w * h, 0.5f);
  const auto levels = buildAndCompare(w, h, d, false, HiZReduction::Auto);
  ASSERT_EQ(levels.size(), 6u);  // 32x16 ... 1x1
  EXPECT_EQ(levels[0][0], 0.5f);
  EXPECT_EQ(levels[0][23], 0.5f);  // pixels 46..47: the last real column pair
  EXPECT_EQ(levels[0][24], 1.0f);  // pixels 48..49: padding
  EXPECT_EQ(levels[3][0], 0.5f);   // pixels 0..15
  EXPECT_EQ(levels[3][2], 0.5f);   // pixels 32..47
  EXPECT_EQ(levels[3][3], 1.0f);   // pixels 48..63
  EXPECT_EQ(levels[5][0], 1.0f);
}

TEST_F(HiZPyramidTest, RebuildsUpdateTheImageAndKeepThePaddingFar) {
  // Later builds skip the texels that cover only padding: they must still read far.
  const uint32_t w = 300, h = 70;
  const std::vector<float> first = randomDepth(w, h, 1), second = randomDepth(w, h, 2);
  for (HiZReduction r : {HiZReduction::Blocked, HiZReduction::SinglePass, HiZReduction::FourTap,
                         HiZReduction::Sampler})
    for (bool full : {false, true}) {
      if (r == HiZReduction::Sampler && !frame::supportsMinmaxReduction(context())) continue;
      const vulkan::Image image = depthImage(w, h, first);
      frame::HiZPyramid pyramid(context(), image, {full, r});
      pyramid.build(context(), VK_IMAGE_LAYOUT_GENERAL);
      upload(image, second, VK_IMAGE_LAYOUT_GENERAL);
      pyramid.build(context(), VK_IMAGE_LAYOUT_GENERAL);
      expectReference(pyramid.readLevels(context()), second, w, h, full, toString(r));
    }
}

TEST_F(HiZPyramidTest, RebuildAfterTheDepthChangedUsesTheNewDepth) {
  const uint32_t w = 16, h = 16;
  const vulkan::Image image = depthImage(w, h, std::vector<float>(w * h, 0.25f));
  frame::HiZPyramid pyramid(context(), image, {});
  pyramid.build(context(), VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(pyramid.readLevels(context()).back()[0], 0.25f);
  upload(image, std::vector<float>(w * h, 0.75f), VK_IMAGE_LAYOUT_GENERAL);
  pyramid.build(context(), VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(pyramid.readLevels(context()).back()[0], 0.75f);
}

}  // namespace
}  // namespace osd_cull
