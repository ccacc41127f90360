// The SPIR-V compiled at build time and embedded in the library (osd_cull/vk/shader_compiler.h):
// every variant the library lists is there, intact and equal to what glslang makes of it now;
// a variant that is not listed is an error naming it.
#include "osd_cull/error.h"
#include "osd_cull/frame/shader_variants.h"
#include "osd_cull/vk/glsl/runtime_compiler.h"
#include "osd_cull/vk/shader_compiler.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <string>

namespace osd_cull {
namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;

// Compare with glslang itself, not with SPIR-V from a disk cache.
const bool kDiskCacheOff = ::setenv("OSD_CULL_SHADER_CACHE", "off", 1) == 0;

TEST(EmbeddedSpirv, EveryListedVariantIsEmbeddedOnceAndTheWordsAreIntact) {
  const auto listed = frame::libraryShaderVariants();
  const auto index = vulkan::embeddedSpirv();
  EXPECT_EQ(index.size(), listed.size());
  std::set<std::string> descriptions;
  size_t words = 0;
  for (const vulkan::EmbeddedSpirv& e : index) {
    descriptions.insert(std::string(e.description));
    EXPECT_EQ(e.offset, words) << e.description;
    ASSERT_GT(e.words, 5u) << e.description;
    EXPECT_EQ(vulkan::embeddedSpirvWords()[e.offset], kSpirvMagic) << e.description;
    words += e.words;
  }
  EXPECT_EQ(vulkan::embeddedSpirvWords().size(), words);
  const auto all = vulkan::embeddedSpirvWords();
  EXPECT_EQ(osd_cull::fnv1a64({reinterpret_cast<const char*>(all.data()), all.size_bytes()}),
            vulkan::embeddedSpirvWordsHash());
  for (const vulkan::ShaderVariant& v : listed) {
    EXPECT_TRUE(descriptions.count(v.describe())) << v.describe();
    EXPECT_NE(vulkan::findEmbeddedSpirv(v), nullptr) << v.describe();
  }
  // Every cull method of the registry is in some kernel, and every stage file of the draws.
  for (const char* needle :
       {"CULL_LANES 16", "CULL_DISPLACED 1", "DISPLACED_BOX 1",
        "patch/patch.tese {PATCH_POINTS=20, OSD_CULL_POINTS_BDA=1, "
        "PATCH_DISPLACED=1}",
        "hiz/hiz_single_pass.comp", "osd/eval_stencils.comp {OSD_DERIVATIVES=1}",
        "bounds/patch_bounds.comp", "oracle/count_items.comp"}) {
    bool found = false;
    for (const std::string& d : descriptions) found = found || d.find(needle) != std::string::npos;
    EXPECT_TRUE(found) << needle;
  }
}

TEST(EmbeddedSpirv, EqualsWhatGlslangCompilesFromTheTreeNow) {
  ASSERT_TRUE(kDiskCacheOff);
  size_t generated = 0;
  for (const vulkan::ShaderVariant& v : frame::libraryShaderVariants()) {
    // Every file variant, and the generated kernels but the tangent-plane ones (the largest;
    // glslang takes seconds for them), which EveryListedVariantIsEmbedded... covers.
    if (v.generated && v.text.find("TANGENT_PLANE") != std::string::npos) continue;
    generated += v.generated;
    const vulkan::Spirv embedded = vulkan::findEmbeddedSpirv(v);
    ASSERT_NE(embedded, nullptr) << v.describe();
    EXPECT_EQ(*embedded, *vulkan::glsl::compile(v)) << v.describe();
  }
  EXPECT_GT(generated, 10u);
}

TEST(EmbeddedSpirv, AVariantNotEmbeddedIsAnErrorNamingIt) {
  try {
    vulkan::compileShader({"patch/patch.vert", {{"PATCH_POINTS", "17"}}});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("patch/patch.vert {PATCH_POINTS=17}"), std::string::npos) << what;
    EXPECT_NE(what.find("no build-time SPIR-V"), std::string::npos) << what;
    EXPECT_NE(what.find("shader_variants.h"), std::string::npos) << what;
  }
  try {
    vulkan::compileGlsl("#version 450\n#define CULL_LANES 3\nvoid main() {}\n",
                        "cull/cull_kernel.comp", VK_SHADER_STAGE_COMPUTE_BIT);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cull/cull_kernel.comp (generated, 49 bytes: CULL_LANES 3)"),
              std::string::npos)
        << what;
  }
}

TEST(EmbeddedSpirv, EachVariantIsCopiedOnceAndThenAnsweredFromMemory) {
  const vulkan::ShaderSource draws{"cull/write_draws.comp", {}};
  const auto before = vulkan::shaderCacheStats();
  const vulkan::Spirv a = vulkan::compileShader(draws);
  const vulkan::Spirv b = vulkan::compileShader(draws);
  const auto after = vulkan::shaderCacheStats();
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(after.embedded - before.embedded, 1u);
  EXPECT_EQ(after.hits - before.hits, 1u);
  EXPECT_EQ((*a)[0], kSpirvMagic);
}

}  // namespace
}  // namespace osd_cull
