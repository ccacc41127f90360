// The displaced draw variant (shaders/patch/displace.glsl): undisplaced sets keep pipelines
// without displacement code; displaced sets move the surface by the map.
#include "adapters/load_mesh.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/shader_compiler.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"
#include "support/vk_test_images.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace osd_cull {
namespace {

class DisplacedDrawTest : public test::VkTest {};

// SPIR-V instructions with opcode `op` (OpImageSampleExplicitLod = 88, OpTypeSampledImage = 27).
size_t countOp(const vulkan::Spirv& spirv, uint32_t op) {
  size_t n = 0;
  const std::vector<uint32_t>& w = *spirv;
  for (size_t i = 5; i < w.size();) {
    const uint32_t count = w[i] >> 16;
    if ((w[i] & 0xFFFFu) == op) ++n;
    i += count == 0 ? 1 : count;
  }
  return n;
}

TEST(DisplacedDrawShaders, OnlyTheDisplacedVariantSamplesAMap) {
  for (const char* points : {"16", "20"}) {
    const vulkan::ShaderDefine bda{"OSD_CULL_POINTS_BDA", "0"};  // control_points.glsl
    const auto plain = vulkan::compileShader({"patch/patch.tese", {{"PATCH_POINTS", points}, bda}});
    const auto displaced = vulkan::compileShader(
        {"patch/patch.tese", {{"PATCH_POINTS", points}, bda, {"PATCH_DISPLACED", "1"}}});
    EXPECT_EQ(countOp(plain, 27), 0u) << points;
    EXPECT_EQ(countOp(plain, 88), 0u) << points;
    EXPECT_GT(countOp(displaced, 27), 0u) << points;
    EXPECT_GE(countOp(displaced, 88), 1u) << points;  // in displacementAt()
  }
}

struct DisplacedCube {
  PatchExtraction ex;
  frame::Camera camera;
};

DisplacedCube loadCube() {
  DisplacedCube c{
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_cube.obj")),
      frame::Camera::lookAt({2.5, 1.8, 3.1}, {0, 0, 0}, {0, 1, 0}, 40.0, 64, 64, 0.5, 20.0)};
  return c;
}

std::vector<float> drawDepth(vulkan::Context& context, const DisplacedCube& cube,
                             const bound::DisplacementMap* map) {
  frame::GpuPatchSet gpu(context, cube.ex.patches);
  std::unique_ptr<frame::GpuDisplacement> displacement;
  if (map) {
    displacement = std::make_unique<frame::GpuDisplacement>(context, *map, cube.ex.uvCorners,
                                                            cube.ex.patches.patchCount());
    gpu.setDisplacement(displacement.get());
  }
  frame::RenderTarget target(context, 64, 64);
  frame::Renderer renderer(context);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 8;
  renderer.render(target, cube.camera, gpu, &cube.ex.patches, options);
  return target.readDepth(context);
}

TEST_F(DisplacedDrawTest, ScaleZeroDrawsTheUndisplacedDepthAndAScaleMovesIt) {
  OSD_CULL_REQUIRE_DATA();
  const DisplacedCube cube = loadCube();
  const auto texels = scene::proceduralDisplacementTexels(64, 3);
  const bound::DisplacementMap flat("procedural", 64, 64, texels, 0.0, 0.5);
  const bound::DisplacementMap bumpy("procedural", 64, 64, texels, 0.3, 0.5);
  const std::vector<float> plain = drawDepth(context(), cube, nullptr);
  EXPECT_EQ(drawDepth(context(), cube, &flat), plain);
  const std::vector<float> moved = drawDepth(context(), cube, &bumpy);
  size_t differ = 0;
  for (size_t i = 0; i < plain.size(); ++i) differ += moved[i] != plain[i] ? 1 : 0;
  EXPECT_GT(differ, plain.size() / 10);
}

// The level-0 texel extremes over the texel centres inside a region (wrapped): what a bound
// without the filter footprint and snapping margins would read.
bound::TexelRange centresInside(const bound::DisplacementMap& map, const bound::UvRegion& r) {
  const auto w = int64_t{map.width()}, h = int64_t{map.height()};
  bound::TexelRange out{1e30, -1e30};
  for (int64_t y = int64_t(std::ceil(r.lo.y * h - 0.5)); y + 0.5 <= r.hi.y * h; ++y)
    for (int64_t x = int64_t(std::ceil(r.lo.x * w - 0.5)); x + 0.5 <= r.hi.x * w; ++x) {
      const double v = map.level(0)[size_t(((y % h + h) % h) * w + (x % w + w) % w)];
      out.lo = std::min(out.lo, v);
      out.hi = std::max(out.hi, v);
    }
  return out;
}

TEST_F(DisplacedDrawTest, DeviceSamplesStayInTheRangeOfTheirRegion) {
  // Sathe's pre-processing and Niessner & Loop §4.2 (Dmin, Dmax): the min/max pyramid's
  // range over a patch's texture region must hold every sample the device's sampler takes
  // there (its filter footprint at the sampled mip level, its fixed-point texel snapping).
  // 8 x 8 flat patches facing an orthographic pixel camera, each with a small random texture
  // region (wrapping included) over a random 16 x 16 map; the drawn depth is the sampled D.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0), start(-1.5, 2.5), extent(0.002, 0.06);
  std::vector<float> texels(16 * 16);
  for (float& t : texels) t = static_cast<float>(unit(rng));
  const frame::Camera camera = test::pixelCamera(64, 64);
  const auto depthOf = [&](double z) {
    const glm::dvec4 c = camera.viewProjection() * glm::dvec4(0.0, 0.0, z, 1.0);
    return c.z / c.w;
  };
  const double d5 = depthOf(-5.0), d4 = depthOf(-4.0);
  std::vector<std::array<glm::dvec3, 16>> flat;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i)  // du x dv = +z: the normal faces the camera
      flat.push_back(scene::flatBezierPatch({8.0 * i, -8.0 * (j + 1), -5.0}, {8, 0, 0}, {0, 8, 0}));
  const PatchSet patches = scene::bezierPatchSet(flat, "flat grid");
  std::vector<glm::dvec2> corners;
  std::vector<bound::UvRegion> regions;
  for (uint32_t p = 0; p < patches.patchCount(); ++p) {
    const glm::dvec2 lo(start(rng), start(rng)), hi = lo + glm::dvec2(extent(rng), extent(rng));
    corners.insert(corners.end(), {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}});
    regions.push_back({lo, hi});
  }
  for (uint32_t lod : {0u, 2u}) {
    SCOPED_TRACE("maxLod " + std::to_string(lod));
    const bound::DisplacementMap map("random", 16, 16, texels, 1.0, 0.5, lod);
    frame::GpuPatchSet gpu(context(), patches);
    frame::GpuDisplacement displacement(context(), map, corners, patches.patchCount());
    gpu.setDisplacement(&displacement);
    frame::RenderTarget target(context(), 64, 64);
    frame::Renderer renderer(context());
    frame::RenderOptions options;
    options.tessellation.uniformLevel = 16;
    renderer.render(target, camera, gpu, &patches, options);
    const auto depth = target.readDepth(context());
    const auto items = target.readItems(context());
    uint32_t covered = 0, outside = 0, outsideCentres = 0;
    for (size_t i = 0; i < items.size(); ++i) {
      if (items[i] == 0) continue;
      const uint32_t p = items[i] - 1;
      ++covered;
      const double d = (depth[i] - d5) / (d4 - d5);  // the sampled displacement
      const bound::TexelRange r = map.rangeOver(regions[p]);
      const double margin = 1e-5;  // depth buffer and interpolation rounding
      outside += d < map.displacement(r.lo) - margin || d > map.displacement(r.hi) + margin;
      const bound::TexelRange c = centresInside(map, regions[p]);
      outsideCentres += d < map.displacement(c.lo) - margin || d > map.displacement(c.hi) + margin;
    }
    EXPECT_EQ(covered, 64u * 64u);
    EXPECT_EQ(outside, 0u) << "samples outside rangeOver() of their patch's region";
    // The footprint margins matter: the texels centred inside the region alone miss samples.
    EXPECT_GT(outsideCentres, covered / 20);
  }
}

TEST_F(DisplacedDrawTest, MeshWithoutTextureCoordinatesIsRefusedByName) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_pole8.obj"));
  const bound::DisplacementMap map("flat", 4, 4, std::vector<float>(16, 0.5f), 1.0, 0.5);
  try {
    frame::GpuDisplacement d(context(), map, ex.uvCorners, ex.patches.patchCount());
    FAIL() << "displacement accepted without texture coordinates";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("texture coordinates"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace osd_cull
