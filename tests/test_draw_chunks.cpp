// Draw splitting against lavapipe's batch overflow, and the host mirror of tess levels.
#include "osd_cull/frame/camera.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/draw/draw_chunks.h"
#include "osd_cull/frame/draw/tess_levels.h"

#include <gtest/gtest.h>

#include <random>

namespace osd_cull {
namespace {

using frame::planDrawChunks;

void expectValidPlan(const std::vector<frame::DrawChunk>& chunks, std::span<const uint32_t> bounds,
                     uint32_t controlPoints) {
  const uint32_t window = (4096 + controlPoints - 1) / controlPoints;
  uint32_t next = 0;
  for (const auto& c : chunks) {
    ASSERT_EQ(c.first, next);  // contiguous, in order
    ASSERT_GT(c.count, 0u);
    for (uint32_t s = c.first; s < c.first + c.count; ++s) {
      uint64_t sum = 0;
      for (uint32_t k = s; k < std::min(s + window, c.first + c.count); ++k) sum += bounds[k];
      ASSERT_LE(sum, 65535u) << "window at slot " << s;
    }
    next += c.count;
  }
  EXPECT_EQ(next, bounds.size());
}

TEST(DrawChunks, LowLevelsNeedOneDraw) {
  const std::vector<uint32_t> bounds(10000, 15 * 15);  // level 14: 256 * 225 < 65,535
  const auto chunks = planDrawChunks(bounds, 16);
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_EQ(chunks[0].count, 10000u);
}

TEST(DrawChunks, Level16SplitsBezierDrawsEvery226Patches) {
  const std::vector<uint32_t> bounds(1000, 17 * 17);
  const auto chunks = planDrawChunks(bounds, 16);
  ASSERT_EQ(chunks.size(), 5u);  // 65,535 / 289 = 226 per draw
  EXPECT_EQ(chunks[0].count, 226u);
  EXPECT_EQ(chunks[4].count, 1000u - 4 * 226u);
  expectValidPlan(chunks, bounds, 16);
}

TEST(DrawChunks, GregoryBatchesHoldFewerPatches) {
  // 4096 / 20 -> windows of 205 patches: level 16 (205 * 289 = 59,245) needs no split.
  const std::vector<uint32_t> bounds(1000, 17 * 17);
  EXPECT_EQ(planDrawChunks(bounds, 20).size(), 1u);
  const std::vector<uint32_t> level64(100, 65 * 65);
  const auto chunks = planDrawChunks(level64, 20);
  EXPECT_EQ(chunks[0].count, 15u);  // 65,535 / 4,225
  expectValidPlan(chunks, level64, 20);
}

TEST(DrawChunks, MixedBoundsKeepEveryWindowUnderTheLimit) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> level(1, 64);
  std::vector<uint32_t> bounds(3000);
  for (auto& b : bounds) {
    const uint32_t l = level(rng);
    b = (l + 1) * (l + 1);
  }
  expectValidPlan(planDrawChunks(bounds, 16), bounds, 16);
  expectValidPlan(planDrawChunks(bounds, 20), bounds, 20);
  EXPECT_TRUE(planDrawChunks({}, 16).empty());
}

TEST(TessLevels, UniformLevelsAreTheLevelAndTransitionEdgesHoldTwo) {
  scene::TorusOptions o;
  o.refinePatch = 9;
  const PatchSet torus = scene::bsplineTorus(o);
  frame::TessellationOptions t;
  t.uniformLevel = 5;
  uint32_t transitionEdges = 0;
  for (uint32_t p = 0; p < torus.patchCount(); ++p) {
    const auto levels = frame::patchTessLevels(torus, p, glm::dmat4(1.0), {64, 64}, t);
    for (int e = 0; e < 4; ++e) {
      EXPECT_EQ(levels.lo[e], 5.0);
      transitionEdges += levels.hi[e] == 5.0;
    }
  }
  EXPECT_EQ(transitionEdges, 4u);  // the refined patch's four neighbours
}

TEST(TessLevels, AdaptiveLevelOfASharedEdgeIsTheSameFromBothSides) {
  // Two patches sharing an edge traversed in opposite directions.
  auto a = scene::flatBezierPatch({0, 0, -5}, {1, 0, 0}, {0, 1, 0});
  a[7].z = -4.5;  // curve the shared edge a little
  auto b = scene::flatBezierPatch({1, 1, -5}, {0, -1, 0}, {1, 0, 0});
  // b's v=0 edge is a's u=1 edge, reversed: the same points, bit for bit.
  for (int i = 0; i < 4; ++i) b[i] = a[4 * (3 - i) + 3];
  const std::array patches{a, b};
  const PatchSet set = scene::bezierPatchSet(patches, "test:pair");
  const auto camera =
      frame::Camera::lookAt({0.3, 0.2, 0}, {0.5, 0.5, -5}, {0, 1, 0}, 50, 200, 100, 0.1, 20);
  frame::TessellationOptions t;
  t.mode = frame::TessellationOptions::Mode::Adaptive;
  t.pixelsPerSegment = 3.0;
  const auto la = frame::patchTessLevels(set, 0, camera.viewProjection(), {200, 100}, t);
  const auto lb = frame::patchTessLevels(set, 1, camera.viewProjection(), {200, 100}, t);
  // a's u=1 edge (outer 2) is b's v=0 edge (outer 1).
  EXPECT_EQ(la.lo[2], lb.lo[1]);
  EXPECT_GT(la.lo[2], 1.0);
  EXPECT_LE(la.lo[2], 32.0);
}

}  // namespace
}  // namespace osd_cull
