// The SPIR-V disk cache: entries keyed by everything the code depends on, full key
// compared on load, damaged files are misses, `off` disables it, and a second process
// loads every variant instead of compiling it.
#include "osd_cull/vk/glsl/runtime_compiler.h"
#include "osd_cull/vk/glsl/spirv_disk_cache.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kSpirvMagic = 0x07230203;

/// Points the cache at a fresh folder for one test.
class SpirvCacheTest : public ::testing::Test {
 protected:
  void SetUp() override { ::setenv("OSD_CULL_SHADER_CACHE", dir_.path().c_str(), 1); }
  void TearDown() override { ::unsetenv("OSD_CULL_SHADER_CACHE"); }
  size_t files() const {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_.path())) n += e.path().extension() == ".spv";
    return n;
  }
  test::TempDir dir_{"osd_cull_spirv_cache_"};
};

TEST_F(SpirvCacheTest, StoredWordsComeBackOnlyForTheirOwnKey) {
  const std::vector<uint32_t> words = {kSpirvMagic, 0x00010500u, 0u, 8u, 0u, 42u};
  ASSERT_TRUE(vulkan::glsl::storeCachedSpirv("key one", words));
  EXPECT_EQ(vulkan::glsl::loadCachedSpirv("key one"), words);
  EXPECT_EQ(vulkan::glsl::loadCachedSpirv("key two"), std::nullopt);
  // Another key's file under this key's name (a hash collision) is a miss, not its code.
  fs::copy_file(vulkan::glsl::spirvCacheFile("key one"), vulkan::glsl::spirvCacheFile("key two"));
  EXPECT_EQ(vulkan::glsl::loadCachedSpirv("key two"), std::nullopt);
  // A damaged entry is a miss.
  fs::resize_file(vulkan::glsl::spirvCacheFile("key one"),
                  fs::file_size(vulkan::glsl::spirvCacheFile("key one")) - 6);
  EXPECT_EQ(vulkan::glsl::loadCachedSpirv("key one"), std::nullopt);
  std::ofstream(vulkan::glsl::spirvCacheFile("key one"), std::ios::binary) << "garbage";
  EXPECT_EQ(vulkan::glsl::loadCachedSpirv("key one"), std::nullopt);
}

TEST_F(SpirvCacheTest, OffDisablesTheCache) {
  ::setenv("OSD_CULL_SHADER_CACHE", "off", 1);
  EXPECT_TRUE(vulkan::glsl::spirvCacheDirectory().empty());
  EXPECT_FALSE(vulkan::glsl::storeCachedSpirv("k", std::vector<uint32_t>{kSpirvMagic, 1, 2, 3, 4}));
  EXPECT_EQ(vulkan::glsl::loadCachedSpirv("k"), std::nullopt);
}

TEST_F(SpirvCacheTest, EachVariantIsWrittenOnceUnderAKeyWithItsTextAndDefines) {
  const std::string text =
      "#version 450\nlayout(local_size_x = 1) in;\n"
      "layout(std430, binding = 0) buffer B { uint v[]; };\n"
      "void main() { v[0] = VALUE; }  // " +
      dir_.path().string() + "\n";
  const vulkan::ShaderDefine one[] = {{"VALUE", "1u"}};
  const vulkan::ShaderDefine two[] = {{"VALUE", "2u"}};
  const auto before = vulkan::glsl::compileStats();
  auto a = vulkan::glsl::compileGlsl(text, "test/disk.comp", VK_SHADER_STAGE_COMPUTE_BIT, one);
  auto b = vulkan::glsl::compileGlsl(text, "test/disk.comp", VK_SHADER_STAGE_COMPUTE_BIT, two);
  vulkan::glsl::compileGlsl(text, "test/disk.comp", VK_SHADER_STAGE_COMPUTE_BIT, one);  // memory
  const auto after = vulkan::glsl::compileStats();
  EXPECT_EQ(after.compiles - before.compiles, 2u);
  EXPECT_EQ(after.diskWrites - before.diskWrites, 2u);
  EXPECT_EQ(after.hits - before.hits, 1u);
  EXPECT_EQ(files(), 2u);
  EXPECT_NE(*a, *b);
  // The key holds the environment stamp: library and glslang versions, embedded files.
  const std::string key = vulkan::glsl::shaderCacheKey("memory key", "text");
  EXPECT_NE(key.find("osd_cull "), std::string::npos);
  EXPECT_NE(key.find("glslang "), std::string::npos);
  EXPECT_NE(key.find("shaders "), std::string::npos);
  EXPECT_NE(key, vulkan::glsl::shaderCacheKey("memory key", "other text"));
}

// The library's own variants are embedded at build time: a program (osd-cull) takes every
// one from there and neither compiles nor touches the SPIR-V cache.
TEST_F(SpirvCacheTest, TheProgramTakesEveryVariantFromTheLibraryAndWritesNoCache) {
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  const std::string command =
      "OSD_CULL_SHADER_CACHE=" + dir_.path().string() + " " + test::osdCullProgram().string() +
      " render --width 48 --height 32 --cull all --out " + (dir_.path() / "frame.png").string();
  const std::regex figures(R"(shader variants: (\d+) from the library's build-time SPIR-V)");
  std::smatch m;
  const auto run = test::runCommand(command);
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  ASSERT_TRUE(std::regex_search(run.output, m, figures)) << run.output;
  EXPECT_GE(std::stoi(m[1]), 5);  // patch stages, occluder stages, the cull kernel, Hi-Z
  EXPECT_EQ(files(), 0u);
}

}  // namespace
}  // namespace osd_cull
