#pragma once
/// \file spirv_disk_cache.h
/// \brief The run-time compiler's (runtime_compiler.h) persistent cache of compiled SPIR-V on
/// disk: GLSL compiled at run time (the tests' own shaders) and the build-time generator
/// (tools/embed_spirv.cpp, with a cache in the build tree) skip glslang for what they
/// compiled before. The library's own variants are embedded (shader_compiler.h).
///
/// Entries are keyed by everything the SPIR-V depends on (shaderCacheKey): the library and
/// glslang versions, every embedded shader file, OpenSubdiv's patch basis, the stage, the
/// defines and the text compiled. A variant added or changed anywhere gets a new key. The full key
/// is stored in each file and compared on load, so a hash collision or a damaged file is a miss,
/// never wrong code.
///
/// Location: `$OSD_CULL_SHADER_CACHE` (a directory; `off` disables the cache), else
/// `$XDG_CACHE_HOME/osd_cull/spirv`, else `$HOME/.cache/osd_cull/spirv`. Files are written
/// to a temporary name and renamed, so concurrent processes never read half a file.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::vulkan::glsl {

/// \brief The cache directory, or an empty path when the cache is disabled.
std::filesystem::path spirvCacheDirectory();

/// \brief The file an entry with this key is stored in (inside spirvCacheDirectory()).
std::filesystem::path spirvCacheFile(const std::string& key);

/// \brief The SPIR-V stored under `key`, or nullopt when the cache is disabled, has no such
/// entry, or the entry is damaged or belongs to another key.
std::optional<std::vector<uint32_t>> loadCachedSpirv(const std::string& key);

/// \brief Stores `words` under `key`. Returns false when the cache is disabled or the file
/// cannot be written (the caller counts it; a cache that cannot be written only costs time).
bool storeCachedSpirv(const std::string& key, std::span<const uint32_t> words);

}  // namespace osd_cull::vulkan::glsl
