#pragma once
/// \file shader_compiler.h
/// \brief GLSL → SPIR-V with glslang at run time, from the embedded shaders/ files.
///
/// `#include "x"` and `#include <x>` resolve against the embedded files (relative to the
/// including file first, then to shaders/). One virtual file exists besides them:
/// "osd/patch_basis.glsl" is OpenSubdiv's own GLSL patch basis
/// (Osd::GLSLPatchShaderSource::GetPatchBasisShaderSource(), with OSD_PATCH_BASIS_GLSL
/// defined), so patches are evaluated with OpenSubdiv's functions.
///
/// Every variant (file, stage, defines) is compiled once per process and cached in memory,
/// and across processes in the SPIR-V disk cache (spirv_disk_cache.h): a program whose
/// variants are all on disk never starts glslang.
/// Shaders target Vulkan 1.2 / SPIR-V 1.5. Defines come before the first line of the
/// file; GL_GOOGLE_include_directive is enabled for every shader.

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

/// \brief An embedded shader file and the defines of one variant.
struct ShaderSource {
  std::string path;  ///< relative to shaders/, e.g. "patch/patch.tese"
  std::vector<ShaderDefine> defines;
};

/// \brief Compiled SPIR-V words, shared by every user of the same variant.
using Spirv = std::shared_ptr<const std::vector<uint32_t>>;

/// \brief The stage of a file from its extension: .vert .tesc .tese .geom .frag .comp.
/// \throws osd_cull::Error for other extensions.
VkShaderStageFlagBits shaderStageOf(std::string_view path);

/// \brief The text of an embedded file (or of "osd/patch_basis.glsl").
/// \throws osd_cull::Error when no such file is embedded.
std::string_view shaderText(std::string_view path);

/// \brief Compiles an embedded shader variant (cached).
/// \throws osd_cull::Error with glslang's messages as "file:line: message".
Spirv compileShader(const ShaderSource& source);

/// \brief Compiles GLSL given as text (cached by text, stage and defines). `name` is used
/// in messages and as the base for relative #include.
Spirv compileGlsl(std::string_view text, std::string_view name, VkShaderStageFlagBits stage,
                  std::span<const ShaderDefine> defines = {});

/// \brief What the caches did in this process: variants compiled by glslang, answered from
/// memory, loaded from the disk cache, and written to it.
struct ShaderCacheStats {
  size_t compiles = 0;
  size_t hits = 0;
  size_t diskHits = 0;
  size_t diskWrites = 0;
  double milliseconds = 0.0;  ///< wall time spent compiling and loading (not memory hits)
};
ShaderCacheStats shaderCacheStats();

/// \brief The disk-cache key of a variant: the environment (library and glslang versions,
/// a hash of every embedded file and of OpenSubdiv's patch basis), then `memoryKey` (kind,
/// name, stage, defines) and the variant's own `text`.
std::string shaderCacheKey(std::string_view memoryKey, std::string_view text);

}  // namespace osd_cull::vulkan
