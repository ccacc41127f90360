// The displaced draw variant (shaders/patch/displace.glsl): undisplaced sets keep pipelines
// without displacement code; displaced sets move the surface by the map.
#include "adapters/load_mesh.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/shader_compiler.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

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
