#pragma once
/// \file runtime_compiler.h
/// \brief GLSL → SPIR-V with glslang at run time: the optional component osd_cull_glsl.
///
/// The library itself takes its shaders from the SPIR-V compiled at build time
/// (osd_cull/vk/shader_compiler.h) and does not link glslang. This component compiles at run
/// time; it is linked by the build-time generator that produces that SPIR-V
/// (tools/embed_spirv.cpp) and by the tests, which compile shaders of their own. It is not
/// installed.
///
/// `#include "x"` and `#include <x>` resolve against the files of shaders/ embedded as text
/// (relative to the including file first, then to shaders/). One virtual file exists besides
/// them: "osd/patch_basis.glsl" is OpenSubdiv's own GLSL patch basis
/// (Osd::GLSLPatchShaderSource::GetPatchBasisShaderSource(), with OSD_PATCH_BASIS_GLSL
/// defined), so patches are evaluated with OpenSubdiv's functions.
///
/// Every variant (file, stage, defines) is compiled once per process and cached in memory,
/// and across processes in the SPIR-V disk cache (spirv_disk_cache.h).
/// Shaders target Vulkan 1.2 / SPIR-V 1.5. Defines come before the first line of the
/// file; GL_GOOGLE_include_directive is enabled for every shader.

#include "osd_cull/vk/shader_compiler.h"

namespace osd_cull::vulkan::glsl {

/// \brief The text of an embedded file (or of "osd/patch_basis.glsl").
/// \throws osd_cull::Error when no such file is embedded.
std::string_view shaderText(std::string_view path);

/// \brief Compiles a file variant of shaders/ (cached).
/// \throws osd_cull::Error with glslang's messages as "file:line: message".
Spirv compileShader(const ShaderSource& source);

/// \brief Compiles GLSL given as text (cached by text, stage and defines). `name` is used
/// in messages and as the base for relative #include.
Spirv compileGlsl(std::string_view text, std::string_view name, VkShaderStageFlagBits stage,
                  std::span<const ShaderDefine> defines = {});

/// \brief compileShader or compileGlsl, as the variant is a file or generated text.
Spirv compile(const ShaderVariant& variant);

/// \brief What this component did in this process: variants compiled by glslang, answered
/// from memory, loaded from the disk cache, and written to it.
struct CompileStats {
  size_t compiles = 0;
  size_t hits = 0;
  size_t diskHits = 0;
  size_t diskWrites = 0;
  double milliseconds = 0.0;  ///< wall time spent compiling and loading (not memory hits)
};
CompileStats compileStats();

/// \brief The disk-cache key of a variant: the environment (library and glslang versions,
/// a hash of every embedded file and of OpenSubdiv's patch basis), then `memoryKey` (kind,
/// name, stage, defines) and the variant's own `text`.
std::string shaderCacheKey(std::string_view memoryKey, std::string_view text);

}  // namespace osd_cull::vulkan::glsl
