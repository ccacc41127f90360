// The run-time compiler (osd_cull_glsl): embedded files, includes, variants, cache, errors
// with file:line.
#include "osd_cull/error.h"
#include "osd_cull/vk/glsl/runtime_compiler.h"
#include "osd_cull/vk/glsl/shader_sources.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace osd_cull {
namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;

// These tests check glslang itself: no SPIR-V from the disk cache (test_spirv_cache.cpp).
const bool kDiskCacheOff = ::setenv("OSD_CULL_SHADER_CACHE", "off", 1) == 0;

TEST(VkShader, StageComesFromTheExtension) {
  EXPECT_EQ(vulkan::shaderStageOf("a/b.comp"), VK_SHADER_STAGE_COMPUTE_BIT);
  EXPECT_EQ(vulkan::shaderStageOf("x.tesc"), VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT);
  EXPECT_EQ(vulkan::shaderStageOf("x.tese"), VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT);
  EXPECT_THROW(vulkan::shaderStageOf("x.glsl"), Error);
}

TEST(VkShader, CompileErrorNamesFileAndLine) {
  const char* text = "#version 450\nvoid main() {\n  float x = undefinedThing;\n}\n";
  try {
    vulkan::glsl::compileGlsl(text, "test/broken.comp", VK_SHADER_STAGE_COMPUTE_BIT);
    FAIL() << "expected a compile error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test/broken.comp:3"), std::string::npos) << what;
    EXPECT_NE(what.find("undefinedThing"), std::string::npos) << what;
  }
}

TEST(VkShader, DefinesMakeVariantsAndEachIsCompiledOnce) {
  const char* text = R"(#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer B { uint v[]; };
void main() { v[0] = VALUE; }
)";
  const vulkan::ShaderDefine one[] = {{"VALUE", "1u"}};
  const vulkan::ShaderDefine two[] = {{"VALUE", "2u"}};
  ASSERT_TRUE(kDiskCacheOff);
  const auto before = vulkan::glsl::compileStats();
  auto a = vulkan::glsl::compileGlsl(text, "test/variant.comp", VK_SHADER_STAGE_COMPUTE_BIT, one);
  auto b = vulkan::glsl::compileGlsl(text, "test/variant.comp", VK_SHADER_STAGE_COMPUTE_BIT, two);
  auto a2 = vulkan::glsl::compileGlsl(text, "test/variant.comp", VK_SHADER_STAGE_COMPUTE_BIT, one);
  const auto after = vulkan::glsl::compileStats();
  ASSERT_FALSE(a->empty());
  EXPECT_EQ((*a)[0], kSpirvMagic);
  EXPECT_NE(*a, *b);
  EXPECT_EQ(a.get(), a2.get());  // same cached object
  EXPECT_EQ(after.compiles - before.compiles, 2u);
  EXPECT_EQ(after.hits - before.hits, 1u);
  // Without the define the text does not compile.
  EXPECT_THROW(vulkan::glsl::compileGlsl(text, "test/variant.comp", VK_SHADER_STAGE_COMPUTE_BIT),
               Error);
}

TEST(VkShader, OpenSubdivPatchBasisIsIncludable) {
  const char* text = R"(#version 450
#include "osd/patch_basis.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer B { float w[]; };
void main() {
  float wP[20], wDs[20], wDt[20], wDss[20], wDst[20], wDtt[20];
  Osd_EvalBasisGregory(0.25, 0.5, wP, wDs, wDt, wDss, wDst, wDtt);
  for (int i = 0; i < 20; ++i) w[i] = wP[i];
}
)";
  auto spirv = vulkan::glsl::compileGlsl(text, "test/basis.comp", VK_SHADER_STAGE_COMPUTE_BIT);
  EXPECT_EQ((*spirv)[0], kSpirvMagic);
  EXPECT_GT(vulkan::glsl::shaderText("osd/patch_basis.glsl").size(), 10000u);
}

TEST(VkShader, MissingIncludeIsAnError) {
  const char* text = "#version 450\n#include \"no/such/file.glsl\"\nvoid main() {}\n";
  try {
    vulkan::glsl::compileGlsl(text, "test/include.comp", VK_SHADER_STAGE_COMPUTE_BIT);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/file.glsl"), std::string::npos) << e.what();
  }
}

TEST(VkShader, EveryEmbeddedStageFileCompiles) {
  size_t stages = 0;
  for (const auto& s : vulkan::glsl::embeddedShaders()) {
    const std::string path(s.path);
    if (path.ends_with(".glsl") || path.ends_with(".h")) continue;
    SCOPED_TRACE(path);
    // Patch stages need PATCH_POINTS and, like every reader of control points,
    // OSD_CULL_POINTS_BDA (common/control_points.glsl); compile every variant (other files
    // ignore them).
    for (const char* points : {"16", "20"})
      for (const char* bda : {"0", "1"}) {
        auto spirv = vulkan::glsl::compileShader(
            {path, {{"PATCH_POINTS", points}, {"OSD_CULL_POINTS_BDA", bda}}});
        EXPECT_EQ((*spirv)[0], kSpirvMagic);
      }
    ++stages;
  }
  EXPECT_GT(stages, 0u);
}

}  // namespace
}  // namespace osd_cull
