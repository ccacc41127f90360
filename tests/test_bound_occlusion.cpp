// Hi-Z pyramid and occlusion test, double-precision references (Niessner & Loop §4.1, §4.1.1).
#include "osd_cull/bound/occlusion.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/demo_shapes.h"
#include "support/vk_test_images.h"
#include "test_bound_fixtures.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <limits>

namespace osd_cull::bound {
namespace {

using test::Rng;

// pixelCamera: world (x, -y, z) is pixel (x, y); depth = (-z - 0.5) / 10 (near 0.5, far 10.5).
double depthAt(double z) { return (-z - 0.5) / 10.0; }

// A flat patch covering pixels [x, x + w) x [y, y + h) at world depth z.
std::array<glm::dvec3, 16> square(double x, double y, double w, double h, double z) {
  return scene::flatBezierPatch({x, -(y + h), z}, {w, 0, 0}, {0, h, 0});
}

std::vector<float> constantDepth(uint32_t w, uint32_t h, float d) {
  return std::vector<float>(size_t{w} * h, d);
}

TEST(BoundOcclusion, LayoutPadsToPowersOfTwoWithHalfResolutionTopLevel) {
  const HiZLayout half = HiZLayout::make(333, 517, false);
  EXPECT_EQ(half.paddedWidth, 512u);
  EXPECT_EQ(half.paddedHeight, 1024u);
  EXPECT_EQ(half.levelWidth(0), 256u);
  EXPECT_EQ(half.levelHeight(0), 512u);
  EXPECT_EQ(half.levelCount, 10u);  // 256x512 ... 1x2, 1x1
  EXPECT_EQ(half.levelWidth(8), 1u);
  EXPECT_EQ(half.levelHeight(8), 2u);
  EXPECT_EQ(half.levelHeight(9), 1u);
  const HiZLayout full = HiZLayout::make(333, 517, true);
  EXPECT_EQ(full.levelWidth(0), 512u);
  EXPECT_EQ(full.levelHeight(0), 1024u);
  EXPECT_EQ(full.levelCount, 11u);
}

TEST(BoundOcclusion, LayoutOfTinyImages) {
  const HiZLayout one = HiZLayout::make(1, 1, false);
  EXPECT_EQ(one.paddedWidth, 2u);  // a half-resolution texel covers 2x2 pixels
  EXPECT_EQ(one.levelCount, 1u);
  EXPECT_EQ(one.levelWidth(0), 1u);
  const HiZLayout oneFull = HiZLayout::make(1, 1, true);
  EXPECT_EQ(oneFull.paddedWidth, 1u);
  EXPECT_EQ(oneFull.levelCount, 1u);
  const HiZLayout small = HiZLayout::make(2, 3, false);
  EXPECT_EQ(small.levelWidth(0), 1u);
  EXPECT_EQ(small.levelHeight(0), 2u);
  EXPECT_EQ(small.levelCount, 2u);
  EXPECT_THROW(HiZLayout::make(0, 4, false), Error);
}

TEST(BoundOcclusion, PyramidOfAPlaneIsThePlaneAndPaddingIsFar) {
  // 3x3 pixels at depth 0.25, full resolution: padded to 4x4; the padded texels are far,
  // and every coarser texel that contains padding is far too.
  const HiZPyramid p = buildHiZPyramid(constantDepth(3, 3, 0.25f), 3, 3, true);
  ASSERT_EQ(p.layout.levelCount, 3u);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      EXPECT_EQ(p.texel(0, x, y), (x < 3 && y < 3) ? 0.25 : 1.0) << x << "," << y;
  EXPECT_EQ(p.texel(1, 0, 0), 0.25);
  EXPECT_EQ(p.texel(1, 1, 0), 1.0);
  EXPECT_EQ(p.texel(1, 0, 1), 1.0);
  EXPECT_EQ(p.texel(2, 0, 0), 1.0);
  // 4x4: no padding, the plane all the way up.
  const HiZPyramid q = buildHiZPyramid(constantDepth(4, 4, 0.25f), 4, 4, false);
  for (uint32_t l = 0; l < q.layout.levelCount; ++l)
    for (double t : q.levels[l]) EXPECT_EQ(t, 0.25);
}

TEST(BoundOcclusion, PyramidTexelIsTheFarthestDepthOfItsFootprint) {
  // A step: columns < 5 at 0.2, the others at 0.7, one far pixel (1.0) at (9, 6); 16 x 8.
  const uint32_t w = 16, h = 8;
  std::vector<float> d(w * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) d[y * w + x] = x < 5 ? 0.2f : 0.7f;
  d[6 * w + 9] = 1.0f;
  const HiZPyramid p = buildHiZPyramid(d, w, h, false);
  ASSERT_EQ(p.layout.levelCount, 4u);         // 8x4, 4x2, 2x1, 1x1
  EXPECT_EQ(p.texel(0, 0, 0), double{0.2f});  // pixels 0..1
  EXPECT_EQ(p.texel(0, 1, 0), double{0.2f});  // pixels 2..3
  EXPECT_EQ(p.texel(0, 2, 0), double{0.7f});  // pixels 4..5 straddle the step
  EXPECT_EQ(p.texel(0, 4, 3), 1.0);           // pixels (8..9, 6..7) hold the far pixel
  EXPECT_EQ(p.texel(1, 0, 0), double{0.2f});  // pixels 0..3 x 0..3
  EXPECT_EQ(p.texel(1, 1, 0), double{0.7f});  // pixels 4..7
  EXPECT_EQ(p.texel(1, 2, 1), 1.0);           // pixels 8..11 x 4..7
  EXPECT_EQ(p.texel(2, 0, 0), double{0.7f});  // pixels 0..7 x 0..7
  EXPECT_EQ(p.texel(2, 1, 0), 1.0);
  EXPECT_EQ(p.texel(3, 0, 0), 1.0);
}

TEST(BoundOcclusion, FootprintIsAtMostTwoByTwoTexelsAndCoversTheBox) {
  // Every box of a 37 x 21 image, at both resolutions: <= 2 texels per axis, and the
  // texels' pixels contain the box.
  for (bool full : {false, true})
    for (HiZLookup lookup : {HiZLookup::Paper, HiZLookup::Tight}) {
      const HiZLayout l = HiZLayout::make(37, 21, full);
      for (uint32_t x0 = 0; x0 < l.width; ++x0)
        for (uint32_t x1 = x0; x1 < l.width; ++x1)
          for (uint32_t y0 = 0; y0 < l.height; y0 += 3)
            for (uint32_t y1 = y0; y1 < l.height; y1 += 2) {
              HiZScreenBox box;
              box.valid = true;
              box.x0 = x0, box.x1 = x1, box.y0 = y0, box.y1 = y1;
              const HiZFootprint f = hizFootprint(l, box, lookup);
              ASSERT_LT(f.level, l.levelCount);
              ASSERT_LE(f.level, hizFootprint(l, box).level);
              ASSERT_LE(f.x1 - f.x0, 1u) << x0 << ".." << x1 << " full " << full;
              ASSERT_LE(f.y1 - f.y0, 1u) << y0 << ".." << y1 << " full " << full;
              const uint32_t s = l.texelShift(f.level);
              const bool lastX = f.x1 + 1 == l.levelWidth(f.level);
              const bool lastY = f.y1 + 1 == l.levelHeight(f.level);
              ASSERT_LE(f.x0 << s, x0);
              ASSERT_LE(f.y0 << s, y0);
              ASSERT_TRUE(lastX || ((f.x1 + 1) << s) > x1);
              ASSERT_TRUE(lastY || ((f.y1 + 1) << s) > y1);
            }
    }
}

TEST(BoundOcclusion, LevelIsCeilLog2OfTheBoxSizeInTexelsOfTheTopLevel) {
  const HiZLayout full = HiZLayout::make(64, 64, true);
  const HiZLayout half = HiZLayout::make(64, 64, false);
  struct Case {
    uint32_t pixels, fullLevel, halfLevel;
  } cases[] = {{1, 0, 0}, {2, 1, 0}, {3, 2, 1},  {4, 2, 1}, {5, 3, 2},
               {8, 3, 2}, {9, 4, 3}, {33, 6, 5}, {64, 6, 5}};
  for (const Case& c : cases) {
    HiZScreenBox box;
    box.valid = true;
    box.x0 = 0, box.x1 = c.pixels - 1, box.y0 = 3, box.y1 = 3;
    EXPECT_EQ(hizFootprint(full, box).level, c.fullLevel) << c.pixels;
    EXPECT_EQ(hizFootprint(half, box).level, c.halfLevel) << c.pixels;
  }
}

TEST(BoundOcclusion, PatchBehindAWallIsCulledInFrontOrBesideItIsNot) {
  const uint32_t w = 64, h = 32;
  // A wall at z = -3 over columns 0..39; background (far) elsewhere.
  std::vector<float> d(w * h, 1.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < 40; ++x) d[y * w + x] = float(depthAt(-3));
  const glm::dmat4 vp = osd_cull::test::pixelCamera(w, h).viewProjection();
  for (bool full : {false, true}) {
    const HiZPyramid p = buildHiZPyramid(d, w, h, full);
    const auto behind = square(4, 4, 16, 16, -5);
    const OcclusionResult r = hizOcclusionTest(behind, vp, p);
    EXPECT_TRUE(r.tested);
    EXPECT_TRUE(r.culled);
    EXPECT_NEAR(r.nearestDepth, depthAt(-5), 1e-5);
    EXPECT_EQ(r.hizDepth, double{float(depthAt(-3))});
    EXPECT_FALSE(hizOcclusionTest(square(4, 4, 16, 16, -2), vp, p).culled);   // in front
    EXPECT_FALSE(hizOcclusionTest(square(30, 4, 16, 16, -5), vp, p).culled);  // half beside
    EXPECT_FALSE(hizOcclusionTest(square(44, 4, 16, 16, -5), vp, p).culled);  // beside
    // Coplanar with the wall: ties keep the patch (depth bias).
    EXPECT_FALSE(hizOcclusionTest(square(4, 4, 16, 16, -3), vp, p).culled);
    // Pixels 16..31: one texel of 16 pixels, all wall: culled. Reaching pixel 40 (past the
    // wall) needs 32-pixel texels, and [32, 64) holds background: kept.
    EXPECT_TRUE(hizOcclusionTest(square(16.1, 4.1, 15.8, 7.8, -5), vp, p).culled);
    EXPECT_FALSE(hizOcclusionTest(square(16.1, 4.1, 24.5, 7.8, -5), vp, p).culled);
    // Pixels 24..39: 16 pixels, but texels [16, 32) and [32, 48); the second holds
    // background (the paper's conservative 2x2 lookup). The tight lookup finds that 8-pixel
    // texels [24, 32) and [32, 40) cover the box too, and culls.
    const auto straddling = square(24.1, 4.1, 15.8, 7.8, -5);
    EXPECT_FALSE(hizOcclusionTest(straddling, vp, p).culled);
    const OcclusionResult tight = hizOcclusionTest(straddling, vp, p, HiZLookup::Tight);
    EXPECT_TRUE(tight.culled);
    EXPECT_EQ(tight.footprint.level + 1, hizOcclusionTest(straddling, vp, p).footprint.level);
  }
}

TEST(BoundOcclusion, PointsBehindTheEyeOrOffScreenOrNonFiniteAreNeverTested) {
  const uint32_t w = 32, h = 32;
  const HiZPyramid p = buildHiZPyramid(constantDepth(w, h, 0.0f), w, h, false);  // all near
  const glm::dmat4 persp = glm::perspective(glm::radians(90.0), 1.0, 0.1, 100.0);
  // A patch crossing the eye plane z = 0 (points with w <= 0).
  const auto crossing = scene::flatBezierPatch({-1, -1, -3}, {2, 0, 0}, {0, 0, 4});
  const OcclusionResult r = hizOcclusionTest(crossing, persp, p);
  EXPECT_FALSE(r.tested);
  EXPECT_FALSE(r.culled);
  // Entirely behind the eye.
  EXPECT_FALSE(
      hizOcclusionTest(scene::flatBezierPatch({-1, -1, 3}, {2, 0, 0}, {0, 2, 0}), persp, p).tested);
  // Off screen to the right (a frustum cull, not an occlusion decision).
  const glm::dmat4 vp = osd_cull::test::pixelCamera(w, h).viewProjection();
  EXPECT_FALSE(hizOcclusionTest(square(40, 4, 8, 8, -5), vp, p).tested);
  auto nan = square(4, 4, 8, 8, -5);
  nan[5].x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(hizOcclusionTest(nan, vp, p).tested);
  auto inf = square(4, 4, 8, 8, -5);
  inf[0].z = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(hizOcclusionTest(inf, vp, p).tested);
  // On screen, in front of the eye: tested and (everything at depth 0) culled.
  EXPECT_TRUE(hizOcclusionTest(square(4, 4, 8, 8, -5), vp, p).culled);
}

TEST(BoundOcclusion, PatchCrossingTheNearPlaneIsNotCulled) {
  const uint32_t w = 32, h = 32;
  const HiZPyramid p = buildHiZPyramid(constantDepth(w, h, 0.0f), w, h, false);
  const glm::dmat4 persp = glm::perspective(glm::radians(90.0), 1.0, 0.1, 100.0);
  // From z = -0.05 (in front of the near plane, w > 0) to z = -2.
  const auto crossing = scene::flatBezierPatch({-0.5, -0.5, -0.05}, {1, 0, 0}, {0, 0, -2});
  const OcclusionResult r = hizOcclusionTest(crossing, persp, p);
  EXPECT_TRUE(r.tested);
  EXPECT_LT(r.nearestDepth, 0.0);
  EXPECT_FALSE(r.culled);
}

TEST(BoundOcclusion, CulledPatchesHaveNoPixelNearerThanTheDepthImage) {
  // Random depth images (steps and noise) and random patches under random perspective
  // views: whenever the test culls, every pixel of the box (the region the patch can
  // cover) holds a depth <= the patch's nearest depth.
  Rng rng(7);
  int culled = 0, tested = 0;
  for (int image = 0; image < 24; ++image) {
    const uint32_t w = uint32_t(rng.integer(1, 70)), h = uint32_t(rng.integer(1, 70));
    std::vector<float> d(size_t{w} * h);
    const double base = rng.uniform(0.3, 0.9);
    const uint32_t stepX = uint32_t(rng.integer(0, int(w)));
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x)
        d[y * w + x] = float(std::min(1.0, (x < stepX ? base : base * 0.7) + rng.uniform(0, 0.02)));
    const bool full = image % 2 == 0;
    const HiZPyramid p = buildHiZPyramid(d, w, h, full);
    const glm::dmat4 vp =
        glm::perspective(glm::radians(60.0), double(w) / h, 0.5, 20.0) *
        glm::lookAt(glm::dvec3(0, 0, 5), glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), 0),
                    glm::dvec3(0, 1, 0));
    for (int k = 0; k < 300; ++k) {
      test::Bezier b = test::transformed(
          scene::flatBezierPatch({-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}), rng, rng.uniform(0.1, 2));
      for (auto& q : b) q += glm::dvec3(0, 0, rng.uniform(-12, 2));
      const OcclusionResult r =
          hizOcclusionTest(b, vp, p, k % 2 ? HiZLookup::Tight : HiZLookup::Paper);
      // A finer texel's depth is never farther: the tight lookup culls whatever the paper's does.
      const OcclusionResult paper = hizOcclusionTest(b, vp, p, HiZLookup::Paper);
      const OcclusionResult tight = hizOcclusionTest(b, vp, p, HiZLookup::Tight);
      ASSERT_LE(tight.hizDepth, paper.hizDepth);
      ASSERT_TRUE(!paper.culled || tight.culled);
      if (!r.tested) continue;
      ++tested;
      if (!r.culled) continue;
      ++culled;
      const HiZScreenBox box = hizScreenBox(b, vp, w, h);
      for (uint32_t y = box.y0; y <= box.y1; ++y)
        for (uint32_t x = box.x0; x <= box.x1; ++x)
          ASSERT_LE(double{d[y * w + x]}, r.nearestDepth) << "image " << image << " patch " << k;
    }
  }
  // The sweep must exercise both outcomes.
  EXPECT_GT(culled, 200);
  EXPECT_GT(tested - culled, 200);
}

TEST(BoundOcclusion, ScreenBoxContainsEveryProjectedSurfacePoint) {
  Rng rng(11);
  const uint32_t w = 97, h = 61;
  const glm::dmat4 vp = glm::perspective(glm::radians(50.0), double(w) / h, 0.2, 30.0) *
                        glm::lookAt(glm::dvec3(1, 2, 6), glm::dvec3(0), glm::dvec3(0, 1, 0));
  int checked = 0;
  for (int k = 0; k < 200; ++k) {
    const test::Bezier b =
        test::transformed(test::randomBezier(rng, test::PatchKind::RandomNet), rng, 0.7);
    const HiZScreenBox box = hizScreenBox(b, vp, w, h);
    if (!box.valid) continue;
    ++checked;
    for (double u = 0; u <= 1.0; u += 0.125)
      for (double v = 0; v <= 1.0; v += 0.125) {
        const glm::dvec4 c = vp * glm::dvec4(evaluateBezier(b, u, v).position, 1.0);
        const glm::dvec3 ndc = glm::dvec3(c) / c.w;
        const double px = (ndc.x * 0.5 + 0.5) * w, py = (ndc.y * 0.5 + 0.5) * h;
        EXPECT_GE(ndc.z, box.nearestDepth);
        if (px < 0 || py < 0 || px >= w || py >= h) continue;  // clamped away
        EXPECT_GE(px, double(box.x0));
        EXPECT_LT(px, double(box.x1) + 1.0);
        EXPECT_GE(py, double(box.y0));
        EXPECT_LT(py, double(box.y1) + 1.0);
      }
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace osd_cull::bound
