// Drawing tessellated Bézier and Gregory patches: coverage, evaluation, statistics, PNG.
#include "osd_cull/error.h"
#include "osd_cull/scene/demo_shapes.h"
#include "adapters/image_png.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"
#include "support/vk_test_eval.h"
#include "support/vk_test_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace osd_cull {
namespace {

using frame::RenderOptions;
using frame::TessellationOptions;

class DrawTest : public test::VkTest {};

// A flat patch covering pixel columns [16, 48) and rows [8, 40) at depth z = -3.
PatchSet flatRectangle() {
  const auto p = scene::flatBezierPatch({16.0, -40.0, -3.0}, {32.0, 0.0, 0.0}, {0.0, 32.0, 0.0});
  return scene::bezierPatchSet(std::span(&p, 1), "test:flat-rectangle");
}

void expectRectangle(const std::vector<uint32_t>& items, uint32_t width, uint32_t height) {
  const auto histogram = test::itemHistogram(items);
  ASSERT_EQ(histogram.size(), 2u);
  EXPECT_EQ(histogram.at(1), 32u * 32u);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool inside = x >= 16 && x < 48 && y >= 8 && y < 40;
      ASSERT_EQ(items[y * width + x], inside ? 1u : 0u) << "pixel " << x << "," << y;
    }
}

TEST_F(DrawTest, FlatBezierPatchCoversExactlyItsRectangle) {
  const PatchSet set = flatRectangle();
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 64, 48);
  frame::Renderer renderer(context());
  RenderOptions options;
  options.tessellation.uniformLevel = 3;
  const auto stats = renderer.render(target, test::pixelCamera(64, 48), gpu, &set, options);
  expectRectangle(target.readItems(context()), 64, 48);
  // Orthographic depth of z = -3 with near 0.5, far 10.5.
  const auto depth = target.readDepth(context());
  EXPECT_NEAR(depth[20 * 64 + 20], 0.25f, 1e-6f);
  EXPECT_EQ(depth[0], 1.0f);
  EXPECT_EQ(stats.statistics.tessControlPatches, 1u);
  EXPECT_EQ(stats.statistics.tessEvaluationInvocations, 16u);  // (3 + 1)^2
  EXPECT_EQ(stats.patchesDrawn, 1u);
}

TEST_F(DrawTest, FlatGregoryPatchCoversExactlyItsRectangle) {
  const PatchSet set = scene::convertToGregory(flatRectangle(), [](uint32_t) { return true; });
  ASSERT_EQ(set.gregoryCount, 1u);
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 64, 48);
  frame::Renderer renderer(context());
  RenderOptions options;
  options.tessellation.uniformLevel = 5;
  const auto stats = renderer.render(target, test::pixelCamera(64, 48), gpu, &set, options);
  expectRectangle(target.readItems(context()), 64, 48);
  EXPECT_EQ(stats.statistics.tessEvaluationInvocations, 36u);
}

TEST_F(DrawTest, PointsCanComeFromAnotherBufferWithAnyStride) {
  // As an evaluator writes them: packed x, y, z after 5 floats of something else.
  const PatchSet set = flatRectangle();
  frame::GpuPatchSet gpu(context(), set);
  std::vector<float> packed(5, -1.0f);
  for (const auto& p : set.points)
    packed.insert(packed.end(), {float(p.x), float(p.y), float(p.z)});
  vulkan::Buffer external(context(), packed.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context(), external, packed);
  // Poison the set's own copy, so a draw that read it would miss the rectangle.
  std::vector<glm::dvec3> elsewhere(set.points.size(), glm::dvec3(100.0, 100.0, -3.0));
  gpu.updatePoints(context(), elsewhere);
  gpu.readPointsFrom(context(), external, 3, 5);
  EXPECT_EQ(&gpu.points(), &external);
  frame::RenderTarget target(context(), 64, 48);
  frame::Renderer renderer(context());
  renderer.render(target, test::pixelCamera(64, 48), gpu, &set, {});
  expectRectangle(target.readItems(context()), 64, 48);
  EXPECT_THROW(gpu.updatePoints(context(), set.points), Error);
  EXPECT_THROW(gpu.readPointsFrom(context(), external, 4, 5), Error);  // too small for stride 4
}

TEST_F(DrawTest, UniformLevelGivesPatchesTimesLevelPlusOneSquaredEvaluations) {
  const PatchSet sphere = scene::convertToGregory(scene::bezierSphere({0, 0, 0}, 1.0, 2),
                                                  [](uint32_t p) { return p % 3 == 0; });
  ASSERT_EQ(sphere.patchCount(), 24u);
  ASSERT_EQ(sphere.gregoryCount, 8u);
  frame::GpuPatchSet gpu(context(), sphere);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  const auto camera = frame::Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 45.0, 64, 64, 0.1, 10);
  for (uint32_t level : {1u, 2u, 7u}) {
    RenderOptions options;
    options.tessellation.uniformLevel = level;
    const auto stats = renderer.render(target, camera, gpu, &sphere, options);
    EXPECT_EQ(stats.statistics.tessControlPatches, 24u);
    EXPECT_EQ(stats.statistics.tessEvaluationInvocations, 24u * (level + 1) * (level + 1)) << level;
    EXPECT_EQ(stats.statistics.vertexShaderInvocations, 16u * 16u + 8u * 20u);
    EXPECT_GT(stats.statistics.fragmentShaderInvocations, 0u);
    EXPECT_GE(stats.wallMs, 0.0);
  }
}

// Height field over pixels [8, 56) x [8, 56): x, y of every point on the Bézier grid (so
// x = 8 + 48u, y = -(8 + 48v) exactly), z = -3 + h with Fp and Fm of different heights.
PatchSet gregoryHeightField() {
  auto grid = [](int i, int j, double h) {
    return glm::dvec3(8.0 + 16.0 * i, -(8.0 + 16.0 * j), -3.0 + h);
  };
  std::vector<glm::dvec3> g = {
      grid(0, 0, 0.0), grid(1, 0, 0.3), grid(0, 1, -0.2), grid(1, 1, 1.0),  grid(1, 1, -1.0),
      grid(3, 0, 0.1), grid(3, 1, 0.2), grid(2, 0, -0.3), grid(2, 1, -0.8), grid(2, 1, 0.9),
      grid(3, 3, 0.0), grid(2, 3, 0.4), grid(3, 2, -0.1), grid(2, 2, 1.1),  grid(2, 2, -0.7),
      grid(0, 3, 0.2), grid(0, 2, 0.0), grid(1, 3, -0.4), grid(1, 2, -1.0), grid(1, 2, 0.8)};
  PatchSet set;
  set.source = "test:gregory-height-field";
  set.gregoryCount = 1;
  set.points = g;
  set.params.resize(1);
  set.origins = {PatchOrigin::Gregory};
  return set;
}

TEST_F(DrawTest, GregoryPatchBlendsInteriorPointsAsOpenSubdiv) {
  const PatchSet set = gregoryHeightField();
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  RenderOptions options;
  options.tessellation.uniformLevel = 48;
  options.frontFacesWinTies = false;  // exact depths: this patch faces away from the camera
  renderer.render(target, test::pixelCamera(64, 64), gpu, &set, options);
  const auto depth = target.readDepth(context());
  const auto cp = set.controlPoints(0);
  // The same points with Fp and Fm averaged: a plain Bézier patch that a renderer
  // ignoring the Gregory blend would draw.
  std::vector<glm::dvec3> averaged(cp.begin(), cp.end());
  for (int c = 0; c < 4; ++c)
    averaged[5 * c + 3] = averaged[5 * c + 4] = 0.5 * (cp[5 * c + 3] + cp[5 * c + 4]);
  double maxError = 0.0, maxBlendEffect = 0.0;
  for (uint32_t y = 8; y < 56; ++y)
    for (uint32_t x = 8; x < 56; ++x) {
      const double u = (x + 0.5 - 8.0) / 48.0, v = (y + 0.5 - 8.0) / 48.0;
      const glm::dvec3 p = test::evalGregory(cp, u, v);
      ASSERT_NEAR(p.x, x + 0.5, 1e-9);  // linear precision: the pixel center is (u, v)
      const double expected = (-p.z - 0.5) / 10.0;
      maxError = std::max(maxError, std::abs(depth[y * 64 + x] - expected));
      const double plain = (-test::evalGregory(averaged, u, v).z - 0.5) / 10.0;
      maxBlendEffect = std::max(maxBlendEffect, std::abs(plain - expected));
    }
  EXPECT_LT(maxError, 2e-4);        // tessellation at level 48 plus fp32
  EXPECT_GT(maxBlendEffect, 5e-3);  // the blend matters: 25x the error
}

TEST_F(DrawTest, GregoryPatchesFromBezierDrawTheSameSurface) {
  const PatchSet bezier = scene::bezierSphere({0, 0, 0}, 1.0, 1);
  const PatchSet gregory = scene::convertToGregory(bezier, [](uint32_t) { return true; });
  frame::GpuPatchSet gpuB(context(), bezier), gpuG(context(), gregory);
  frame::RenderTarget target(context(), 96, 96);
  frame::Renderer renderer(context());
  const auto camera =
      frame::Camera::lookAt({1.5, 2.0, 2.5}, {0, 0, 0}, {0, 1, 0}, 50.0, 96, 96, 0.5, 10);
  RenderOptions options;
  options.tessellation.uniformLevel = 6;
  renderer.render(target, camera, gpuB, &bezier, options);
  const auto depthB = target.readDepth(context());
  renderer.render(target, camera, gpuG, &gregory, options);
  const auto depthG = target.readDepth(context());
  uint32_t covered = 0, differ = 0;
  double maxDiff = 0.0;
  for (size_t i = 0; i < depthB.size(); ++i) {
    if (depthB[i] < 1.0f && depthG[i] < 1.0f) {
      ++covered;
      maxDiff = std::max(maxDiff, double(std::abs(depthB[i] - depthG[i])));
    } else if ((depthB[i] < 1.0f) != (depthG[i] < 1.0f)) {
      ++differ;
    }
  }
  EXPECT_GT(covered, 2000u);
  EXPECT_LT(maxDiff, 1e-5);
  EXPECT_LE(differ, covered / 500);  // at most a few silhouette pixels from fp32 rounding
}

TEST_F(DrawTest, BackFaceCullingKeepsTheSideFacingTheEye) {
  const PatchSet sphere = scene::bezierSphere({0, 0, 0}, 1.0, 1);
  frame::GpuPatchSet gpu(context(), sphere);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  const auto camera =
      frame::Camera::lookAt({0.3, 0.4, 3.0}, {0, 0, 0}, {0, 1, 0}, 50.0, 64, 64, 0.5, 10);
  RenderOptions options;
  options.tessellation.uniformLevel = 4;
  const auto all = renderer.render(target, camera, gpu, &sphere, options);
  const auto depthAll = target.readDepth(context());
  options.cullBackFaces = true;
  const auto culled = renderer.render(target, camera, gpu, &sphere, options);
  const auto depthCulled = target.readDepth(context());
  EXPECT_EQ(depthAll, depthCulled);  // the visible (near) side is drawn, the far side culled
  EXPECT_LT(culled.statistics.fragmentShaderInvocations, all.statistics.fragmentShaderInvocations);

  // A single flat patch whose normal (dP/du x dP/dv) points away from the eye vanishes.
  const auto away = scene::flatBezierPatch({16.0, -48.0, -3.0}, {0.0, 32.0, 0.0}, {32.0, 0.0, 0.0});
  const auto toward =
      scene::flatBezierPatch({16.0, -48.0, -3.0}, {32.0, 0.0, 0.0}, {0.0, 32.0, 0.0});
  for (const auto& [patch, visible] : {std::pair{away, false}, std::pair{toward, true}}) {
    const PatchSet one = scene::bezierPatchSet(std::span(&patch, 1), "test:one");
    frame::GpuPatchSet gpuOne(context(), one);
    renderer.render(target, test::pixelCamera(64, 64), gpuOne, &one, options);
    EXPECT_EQ(test::itemHistogram(target.readItems(context())).count(1), visible ? 1u : 0u);
  }
}

TEST_F(DrawTest, DegeneratePatchesDoNotDisturbTheOthers) {
  // Patch 0: NaN point; 1: collapsed to one point; 2: one edge collapsed (like the teapot
  // lid), its normal at the apex comes from slightly inside; 3: an ordinary square.
  auto nan = scene::flatBezierPatch({2, -14, -3}, {12, 0, 0}, {0, 12, 0});
  nan[5].x = std::numeric_limits<double>::quiet_NaN();
  std::array<glm::dvec3, 16> point;
  point.fill({20.0, -8.0, -3.0});
  auto lid = scene::flatBezierPatch({34, -30, -3}, {28, 0, 0}, {0, 28, 0});
  for (int i = 0; i < 4; ++i) lid[12 + i] = {48.0, -2.0, -2.0};  // v = 1 edge -> apex
  const auto square = scene::flatBezierPatch({2, -62, -3}, {24, 0, 0}, {0, 24, 0});
  const std::array patches{nan, point, lid, square};
  const PatchSet set = scene::bezierPatchSet(patches, "test:degenerate");
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  for (auto mode : {TessellationOptions::Mode::Uniform, TessellationOptions::Mode::Adaptive}) {
    RenderOptions options;
    options.tessellation.mode = mode;
    options.tessellation.uniformLevel = 6;
    renderer.render(target, test::pixelCamera(64, 64), gpu, &set, options);
    const auto items = target.readItems(context());
    const auto color = target.readColor(context());
    const auto histogram = test::itemHistogram(items);
    EXPECT_EQ(histogram.count(2), 0u);                                // a point covers nothing
    EXPECT_EQ(histogram.count(4) ? histogram.at(4) : 0u, 24u * 24u);  // rows 38..61, columns 2..25
    ASSERT_GT(histogram.count(3) ? histogram.at(3) : 0u, 100u);
    for (size_t i = 0; i < items.size(); ++i)
      if (items[i] == 3) {  // lit: a NaN or zero normal would shade black
        ASSERT_GT(int(color[4 * i]) + color[4 * i + 1] + color[4 * i + 2], 30) << "pixel " << i;
      }
  }
}

// A k x k grid of flat patches, each covering `size` x `size` pixels.
PatchSet patchGrid(uint32_t k, double size) {
  std::vector<std::array<glm::dvec3, 16>> patches;
  for (uint32_t j = 0; j < k; ++j)
    for (uint32_t i = 0; i < k; ++i)
      patches.push_back(
          scene::flatBezierPatch({size * i, -size * (j + 1), -3.0}, {size, 0, 0}, {0, size, 0}));
  return scene::bezierPatchSet(patches, "test:grid");
}

TEST_F(DrawTest, NoPatchIsMissingAtHighLevelsWhenDrawsAreChunked) {
  // 256 patches at level 18: one draw would exceed lavapipe's 65,535 vertices per batch
  // of 4096 control points (256 Bézier * 19^2 = 92,416; 205 Gregory * 19^2 = 74,005) and
  // lose patches.
  for (bool gregory : {false, true}) {
    SCOPED_TRACE(gregory ? "Gregory" : "Bezier");
    PatchSet grid = patchGrid(16, 8.0);
    if (gregory) grid = scene::convertToGregory(grid, [](uint32_t) { return true; });
    frame::GpuPatchSet gpu(context(), grid);
    frame::RenderTarget target(context(), 128, 128);
    frame::Renderer renderer(context());
    RenderOptions options;
    options.tessellation.uniformLevel = 18;
    const auto stats = renderer.render(target, test::pixelCamera(128, 128), gpu, &grid, options);
    EXPECT_GE(stats.drawCalls, 2u);
    const auto histogram = test::itemHistogram(target.readItems(context()));
    ASSERT_EQ(histogram.count(0), 0u);  // every pixel covered
    for (uint32_t p = 0; p < grid.patchCount(); ++p)
      ASSERT_EQ(histogram.count(p + 1) ? histogram.at(p + 1) : 0u, 64u) << "patch " << p;
    EXPECT_EQ(stats.statistics.tessEvaluationInvocations, 256u * 19u * 19u);
  }
}

TEST_F(DrawTest, IndirectDrawsOfACulledListDrawExactlyThoseSlots) {
  // What a cull pass produces: a compact draw list of surviving patches and indirect
  // draw commands over its slots, with the command count in a buffer.
  const PatchSet grid = patchGrid(4, 16.0);
  frame::GpuPatchSet gpu(context(), grid);
  const std::vector<uint32_t> survivors = {3, 7, 12, 0, 9};
  vulkan::Buffer list(context(), survivors.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<uint32_t>(context(), list, survivors);
  const std::vector<VkDrawIndirectCommand> commands = {
      {2 * 16, 1, 0 * 16, 0}, {2 * 16, 1, 2 * 16, 0}, {1 * 16, 1, 4 * 16, 0}};
  vulkan::Buffer commandBuffer(context(), sizeof(VkDrawIndirectCommand) * commands.size(),
                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  vulkan::upload<VkDrawIndirectCommand>(context(), commandBuffer, commands);
  vulkan::Buffer count(context(), 4, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  const uint32_t two = 2;  // the third command (slot 4, patch 9) is not counted
  vulkan::upload<uint32_t>(context(), count, std::span(&two, 1));

  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  frame::PatchDraw draw{&gpu, &grid, 0, gpu.descriptorSetWithDrawList(context(), list)};
  const auto camera = test::pixelCamera(64, 64);
  RenderOptions options;
  context().submit([&](VkCommandBuffer cmd) {
    renderer.beginPass(cmd, target, options);
    renderer.recordIndirect(cmd, camera, draw, PatchType::Bezier, commandBuffer, 0, count, 0, 3,
                            options);
    renderer.endPass(cmd);
  });
  const auto histogram = test::itemHistogram(target.readItems(context()));
  EXPECT_EQ(histogram.size(), 5u);  // background and four patches
  for (uint32_t p : {3u, 7u, 12u, 0u})
    EXPECT_EQ(histogram.count(p + 1) ? histogram.at(p + 1) : 0u, 256u) << p;
  EXPECT_EQ(histogram.count(10), 0u);
}

TEST_F(DrawTest, AdaptiveLevelsGrowWithScreenSizeAndMatchTheHostMirror) {
  const PatchSet sphere = scene::bezierSphere({0, 0, 0}, 1.0, 2);
  frame::GpuPatchSet gpu(context(), sphere);
  frame::RenderTarget target(context(), 128, 128);
  frame::Renderer renderer(context());
  RenderOptions options;
  options.tessellation.mode = TessellationOptions::Mode::Adaptive;
  options.tessellation.pixelsPerSegment = 6.0;
  uint64_t previous = 0;
  for (double distance : {12.0, 6.0, 3.0}) {
    const auto camera =
        frame::Camera::lookAt({0.2, 0.3, distance}, {0, 0, 0}, {0, 1, 0}, 40.0, 128, 128, 0.1, 20);
    const auto stats = renderer.render(target, camera, gpu, &sphere, options);
    // Expected evaluations from the host mirror of the levels.
    uint64_t expected = 0;
    for (uint32_t p = 0; p < sphere.patchCount(); ++p)
      expected += frame::patchTessLevels(sphere, p, camera.viewProjection(), {128.0, 128.0},
                                         options.tessellation)
                      .vertexCount();
    EXPECT_EQ(stats.statistics.tessEvaluationInvocations, expected) << "distance " << distance;
    EXPECT_GT(stats.statistics.tessEvaluationInvocations, previous);
    previous = stats.statistics.tessEvaluationInvocations;
  }
}

TEST_F(DrawTest, TransitionEdgesTessellateAsTheHostMirrorPredicts) {
  scene::TorusOptions o;
  o.refinePatch = 10;
  const PatchSet torus = scene::bsplineTorus(o);
  frame::GpuPatchSet gpu(context(), torus);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  const auto camera =
      frame::Camera::lookAt({0, -3, 2}, {0, 0, 0}, {0, 0, 1}, 45.0, 64, 64, 0.1, 10);
  ASSERT_TRUE(gpu.hasTransitionEdges());
  for (uint32_t level : {1u, 3u, 6u, 40u}) {
    RenderOptions options;
    options.tessellation.uniformLevel = level;
    const auto stats = renderer.render(target, camera, gpu, &torus, options);
    // Above half the maximum level (64) the set's uniform level is clamped to 32, so that
    // transition edges hold two halves that match their finer neighbours.
    const auto effective = frame::effectiveOptions(options.tessellation, true);
    const uint32_t used = std::min(level, 32u);
    EXPECT_EQ(effective.uniformLevel, used);
    uint64_t expected = 0;
    for (uint32_t p = 0; p < torus.patchCount(); ++p)
      expected += frame::patchTessLevels(torus, p, camera.viewProjection(), {64, 64}, effective)
                      .vertexCount();
    // 51 patches at (level + 1)^2, plus the transition edges' extra segments.
    EXPECT_GT(expected, 51u * (used + 1) * (used + 1));
    EXPECT_EQ(stats.statistics.tessEvaluationInvocations, expected) << "level " << level;
  }
}

TEST_F(DrawTest, ImagesRoundTripThroughPng) {
  const PatchSet sphere = scene::bezierSphere({0, 0, 0}, 1.0, 1);
  frame::GpuPatchSet gpu(context(), sphere);
  frame::RenderTarget target(context(), 48, 32);
  frame::Renderer renderer(context());
  RenderOptions options;
  options.debugColors = true;
  const auto camera =
      frame::Camera::lookAt({0, 0, 3.5}, {0, 0, 0}, {0, 1, 0}, 45.0, 48, 32, 0.5, 10);
  renderer.render(target, camera, gpu, &sphere, options);
  const auto dir = std::filesystem::path(OSD_CULL_BINARY_DIR) / "test_output";
  std::filesystem::create_directories(dir);
  const auto color = target.readColor(context());
  const auto items = target.readItems(context());
  const auto depth = target.readDepth(context());
  adapters::writePng(dir / "sphere_color.png", adapters::colorImage(48, 32, color));
  adapters::writePng(dir / "sphere_items.png", adapters::itemImage(48, 32, items));
  adapters::writePng(dir / "sphere_depth.png", adapters::depthImage(48, 32, depth));
  const auto c = adapters::readPng(dir / "sphere_color.png");
  EXPECT_EQ(c.samples8, color);
  const auto it = adapters::readPng(dir / "sphere_items.png");
  ASSERT_EQ(it.channels, 3);
  for (size_t i = 0; i < items.size(); ++i)
    ASSERT_EQ(uint32_t(it.samples8[3 * i]) | uint32_t(it.samples8[3 * i + 1]) << 8 |
                  uint32_t(it.samples8[3 * i + 2]) << 16,
              items[i]);
  const auto d = adapters::readPng(dir / "sphere_depth.png");
  ASSERT_EQ(d.bitDepth, 16);
  for (size_t i = 0; i < depth.size(); ++i) ASSERT_EQ(d.samples16[i] == 65535, depth[i] >= 1.0f);
  EXPECT_THROW(adapters::writePng(dir / "no_such_dir" / "x.png", adapters::colorImage(48, 32, color)),
               Error);
}

}  // namespace
}  // namespace osd_cull
