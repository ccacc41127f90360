#pragma once
/// \file shader_compiler.h
/// \brief The library's shader variants as SPIR-V compiled at build time.
///
/// Every variant the library requests (a file of shaders/ with defines, or GLSL it generates,
/// such as the cull kernel) is listed by the module that requests it
/// (osd_cull/frame/shader_variants.h), compiled by the build (tools/embed_spirv.cpp, with
/// glslang) and embedded in the library. compileShader and compileGlsl look a variant up
/// there: the library neither links glslang nor compiles at run time. A variant that was not
/// embedded is an osd_cull::Error naming it. Compiling arbitrary GLSL at run time is the
/// optional component osd_cull_glsl (osd_cull/vk/glsl/runtime_compiler.h), which the tests and
/// the build-time generator link; the installed package does not ship it.

#include "osd_cull/hash.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull::vulkan {

/// \brief A preprocessor define: `#define name value` (value may be empty).
struct ShaderDefine {
  std::string name;
  std::string value;
};

/// \brief A file of shaders/ and the defines of one variant.
struct ShaderSource {
  std::string path;  ///< relative to shaders/, e.g. "patch/patch.tese"
  std::vector<ShaderDefine> defines;
};

/// \brief One shader variant: a file of shaders/ with defines, or generated GLSL text.
struct ShaderVariant {
  std::string name;  ///< the file (relative to shaders/), or the name of generated text
  VkShaderStageFlagBits stage = VK_SHADER_STAGE_COMPUTE_BIT;
  std::vector<ShaderDefine> defines;
  bool generated = false;
  std::string text;  ///< generated GLSL (empty for a file)

  static ShaderVariant file(const ShaderSource& source);
  static ShaderVariant glsl(std::string_view text, std::string_view name,
                            VkShaderStageFlagBits stage,
                            std::span<const ShaderDefine> defines = {});
  /// \brief Everything its SPIR-V depends on besides the shader files of the build.
  std::string key() const;
  /// \brief For messages: "patch/patch.tese {PATCH_POINTS=16, ...}", or for generated text
  /// its name, size and `#define` lines.
  std::string describe() const;
};

/// \brief Compiled SPIR-V words, shared by every user of the same variant.
using Spirv = std::shared_ptr<const std::vector<uint32_t>>;

/// \brief The stage of a file from its extension: .vert .tesc .tese .geom .frag .comp.
/// \throws osd_cull::Error for other extensions.
VkShaderStageFlagBits shaderStageOf(std::string_view path);

/// \brief The build-time SPIR-V of a file variant.
/// \throws osd_cull::Error naming the variant when it was not embedded.
Spirv compileShader(const ShaderSource& source);

/// \brief The build-time SPIR-V of generated GLSL (`name` names it in messages).
/// \throws osd_cull::Error naming the variant when it was not embedded.
Spirv compileGlsl(std::string_view text, std::string_view name, VkShaderStageFlagBits stage,
                  std::span<const ShaderDefine> defines = {});

/// \brief The build-time SPIR-V of a variant, or nullptr when it was not embedded.
Spirv findEmbeddedSpirv(const ShaderVariant& variant);

/// \brief One embedded variant: the 128-bit hash of its key, where its words are, and its
/// description (ShaderVariant::describe()).
struct EmbeddedSpirv {
  uint64_t hash0;
  uint64_t hash1;
  uint32_t offset;  ///< in words, into embeddedSpirvWords()
  uint32_t words;
  std::string_view description;
};

/// \brief Every embedded variant (generated at build time: embedded_spirv.cpp).
std::span<const EmbeddedSpirv> embeddedSpirv();
/// \brief The SPIR-V words of every embedded variant, back to back.
std::span<const uint32_t> embeddedSpirvWords();
/// \brief fnv1a64 (osd_cull/hash.h) of embeddedSpirvWords()' bytes, as written by the generator.
uint64_t embeddedSpirvWordsHash();

/// \brief The two hashes of a key that index embeddedSpirv().
std::pair<uint64_t, uint64_t> spirvKeyHash(std::string_view key);

/// \brief What the lookups did in this process: variants taken from the embedded SPIR-V,
/// answered from memory, and the wall time spent.
struct ShaderCacheStats {
  size_t embedded = 0;
  size_t hits = 0;
  double milliseconds = 0.0;
};
ShaderCacheStats shaderCacheStats();

}  // namespace osd_cull::vulkan
