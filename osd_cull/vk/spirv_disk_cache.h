#pragma once
/// \file spirv_disk_cache.h
/// \brief A persistent cache of compiled SPIR-V on disk, so that a program's first frame
/// does not pay for glslang (about 110 ms to start plus 2-4 ms per shader variant).
///
/// Entries are keyed by everything the SPIR-V depends on (shaderCacheKey): the library and
/// glslang versions, every embedded shader file, OpenSubdiv's patch basis, the stage, the
/// defines and the text compiled. A variant added or changed anywhere gets a new key; no
/// build-time list of variants can go stale. The full key is stored in each file and
/// compared on load, so a hash collision or a damaged file is a miss, never wrong code.
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

namespace osd_cull::vulkan {

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

/// \brief 64-bit FNV-1a hash of `bytes` (file names and stamps; not for security).
uint64_t fnv1a64(std::string_view bytes, uint64_t seed = 0xcbf29ce484222325ull);

}  // namespace osd_cull::vulkan
