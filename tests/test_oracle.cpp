// The item-buffer oracle: per-patch visible pixel counts, exact on scenes whose visible
// set is known by construction.
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "support/vk_test_context.h"
#include "support/vk_test_images.h"

#include <gtest/gtest.h>

namespace osd_cull {
namespace {

using frame::TessellationOptions;

class OracleTest : public test::VkTest {
 protected:
  // A w x h pixel square whose top-left pixel is (x, y), at depth z (pixelCamera coordinates).
  static std::array<glm::dvec3, 16> square(double x, double y, double w, double h, double z) {
    return scene::flatBezierPatch({x, -(y + h), z}, {w, 0, 0}, {0, h, 0});
  }
};

TEST_F(OracleTest, PatchesBehindAnOpaqueWallHaveZeroPixels) {
  // Four 16 x 16 patches in a row at z = -5; a wall at z = -3 hides the first two
  // completely and the left half of the third.
  std::vector<std::array<glm::dvec3, 16>> row;
  for (int i = 0; i < 4; ++i) row.push_back(square(16.0 * i, 8, 16, 16, -5));
  const PatchSet set = scene::bezierPatchSet(row, "test:row");
  frame::GpuPatchSet gpu(context(), set);
  frame::GpuTriangleMesh wall(
      context(), frame::quadMesh({-4, 4, -3}, {40, 4, -3}, {40, -40, -3}, {-4, -40, -3}));
  const frame::GpuTriangleMesh* occluders[] = {&wall};
  frame::RenderTarget target(context(), 64, 32);
  frame::Renderer renderer(context());
  frame::VisibilityOracle oracle(context());
  const auto counts =
      oracle.query(renderer, target, test::pixelCamera(64, 32), gpu, &set, occluders, {});
  ASSERT_EQ(counts.patchCount(), 4u);
  EXPECT_EQ(counts.pixels[0], 0u);
  EXPECT_EQ(counts.pixels[1], 0u);
  EXPECT_EQ(counts.pixels[2], 8u * 16u);  // columns 40..47 of 32..47
  EXPECT_EQ(counts.pixels[3], 16u * 16u);
  EXPECT_EQ(counts.visiblePatchCount(), 2u);
  EXPECT_EQ(counts.occluderPixels, 40u * 32u);  // the wall covers columns 0..39, all rows
  EXPECT_EQ(counts.backgroundPixels + counts.occluderPixels + counts.pixels[2] + counts.pixels[3],
            64u * 32u);
  EXPECT_EQ(counts.unknownPixels, 0u);
}

TEST_F(OracleTest, PatchesOutsideTheViewHaveZeroPixels) {
  const std::vector<std::array<glm::dvec3, 16>> patches = {
      square(-40, 4, 16, 16, -5),  // left of the image
      square(80, 4, 16, 16, -5),   // right of it
      square(4, 40, 16, 16, -5),   // below
      square(4, 4, 16, 16, +2),    // behind the eye
      square(4, 4, 16, 16, -20),   // beyond the far plane (10.5)
      square(24, 8, 16, 16, -5),   // inside
  };
  const PatchSet set = scene::bezierPatchSet(patches, "test:outside");
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 64, 32);
  frame::Renderer renderer(context());
  frame::VisibilityOracle oracle(context());
  const auto counts = oracle.query(renderer, target, test::pixelCamera(64, 32), gpu, &set, {}, {});
  EXPECT_EQ(counts.pixels, (std::vector<uint32_t>{0, 0, 0, 0, 0, 256}));
}

TEST_F(OracleTest, PatchSeenExactlyEdgeOnHasZeroPixels) {
  // Eye at the origin looking down -z; a flat patch in the plane y = 0 projects to a line.
  const auto camera =
      frame::Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.0, 64, 64, 0.1, 100);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  frame::VisibilityOracle oracle(context());
  TessellationOptions tess;
  tess.uniformLevel = 8;
  for (double tilt : {0.0, 0.2}) {
    const auto patch = scene::flatBezierPatch({-1, 0, -2}, {2, 0, 0}, {0, tilt, -2});
    const PatchSet set = scene::bezierPatchSet(std::span(&patch, 1), "test:edge-on");
    frame::GpuPatchSet gpu(context(), set);
    const auto counts = oracle.query(renderer, target, camera, gpu, &set, {}, tess);
    if (tilt == 0.0)
      EXPECT_EQ(counts.pixels[0], 0u) << "edge-on patch has pixels";
    else
      EXPECT_GT(counts.pixels[0], 0u) << "tilted patch should be seen";
  }
}

TEST_F(OracleTest, FullyVisiblePatchCountsItsRectangleAndItsTiles) {
  const auto patch = square(16, 8, 32, 32, -3);  // columns 16..47, rows 8..39
  const PatchSet set = scene::convertToGregory(
      scene::bezierPatchSet(std::span(&patch, 1), "test:rect"), [](uint32_t) { return true; });
  frame::GpuPatchSet gpu(context(), set);
  frame::RenderTarget target(context(), 64, 64);
  frame::Renderer renderer(context());
  frame::VisibilityOracle oracle(context());
  const auto counts =
      oracle.query(renderer, target, test::pixelCamera(64, 64), gpu, &set, {}, {}, 2);
  EXPECT_EQ(counts.pixels[0], 32u * 32u);
  ASSERT_EQ(counts.tilesPerSide(), 4u);
  ASSERT_EQ(counts.tileWidth(), 16u);
  // Tiles are 16 x 16: the rectangle covers tile columns 1, 2 fully and rows 0 (8 rows),
  // 1 (16 rows), 2 (8 rows).
  for (uint32_t ty = 0; ty < 4; ++ty)
    for (uint32_t tx = 0; tx < 4; ++tx) {
      const uint32_t cols = (tx == 1 || tx == 2) ? 16 : 0;
      const uint32_t rows = ty == 0 ? 8 : ty == 1 ? 16 : ty == 2 ? 8 : 0;
      EXPECT_EQ(counts.tile(0, tx, ty), cols * rows) << "tile " << tx << "," << ty;
    }
}

TEST_F(OracleTest, CountsEqualTheItemBufferReadBack) {
  scene::TorusOptions o;
  o.refinePatch = 5;
  const PatchSet scene = scene::concatenate(
      scene::convertToGregory(scene::bsplineTorus(o), [](uint32_t p) { return p % 4 == 0; }),
      scene::bezierSphere({0.3, 0.2, 0.6}, 0.5, 2));
  frame::GpuPatchSet gpu(context(), scene);
  frame::GpuTriangleMesh wall(context(), frame::boxMesh({-0.4, -2, 1.3}, {0.1, 2, 1.35}));
  const frame::GpuTriangleMesh* occluders[] = {&wall};
  const uint32_t w = 120, h = 90;  // not multiples of the tile count
  frame::RenderTarget target(context(), w, h);
  frame::Renderer renderer(context());
  frame::VisibilityOracle oracle(context());
  const auto camera =
      frame::Camera::lookAt({0.5, -1.0, 3.5}, {0, 0, 0}, {0, 0, 1}, 45.0, w, h, 0.1, 20);
  TessellationOptions tess;
  tess.mode = TessellationOptions::Mode::Adaptive;
  const auto counts = oracle.query(renderer, target, camera, gpu, &scene, occluders, tess, 3);
  const auto items = target.readItems(context());

  std::vector<uint32_t> pixels(scene.patchCount(), 0), tiles(size_t{scene.patchCount()} * 64, 0);
  uint32_t background = 0, occluder = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const uint32_t v = items[y * w + x];
      if (v == 0) {
        ++background;
      } else if (v == 0xFFFFFFFFu) {
        ++occluder;
      } else {
        ASSERT_LE(v, scene.patchCount());
        ++pixels[v - 1];
        ++tiles[size_t{v - 1} * 64 + (y / counts.tileHeight()) * 8 + x / counts.tileWidth()];
      }
    }
  EXPECT_EQ(counts.pixels, pixels);
  EXPECT_EQ(counts.tilePixels, tiles);
  EXPECT_EQ(counts.backgroundPixels, background);
  EXPECT_EQ(counts.occluderPixels, occluder);
  EXPECT_GT(occluder, 0u);
  EXPECT_GT(counts.visiblePatchCount(), 10u);
  EXPECT_LT(counts.visiblePatchCount(), scene.patchCount());  // back sides and hidden parts
}

}  // namespace
}  // namespace osd_cull
