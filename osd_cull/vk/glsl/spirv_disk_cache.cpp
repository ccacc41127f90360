#include "osd_cull/vk/glsl/spirv_disk_cache.h"

#include "osd_cull/vk/shader_compiler.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

namespace osd_cull::vulkan::glsl {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kMagic = "osd_cull SPIR-V cache 1\n";
constexpr uint32_t kSpirvMagic = 0x07230203u;

std::string hex(uint64_t x) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(x));
  return buf;
}

}  // namespace

fs::path spirvCacheDirectory() {
  if (const char* dir = std::getenv("OSD_CULL_SHADER_CACHE")) {
    const std::string_view d(dir);
    if (d.empty() || d == "off" || d == "0") return {};
    return fs::path(d);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "osd_cull" / "spirv";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "osd_cull" / "spirv";
  return {};
}

fs::path spirvCacheFile(const std::string& key) {
  const fs::path dir = spirvCacheDirectory();
  if (dir.empty()) return {};
  // Two seeds: a 128-bit name, so distinct keys practically never share a file.
  return dir / (hex(fnv1a64(key)) + hex(fnv1a64(key, 0x84222325cbf29ce4ull)) + ".spv");
}

std::optional<std::vector<uint32_t>> loadCachedSpirv(const std::string& key) {
  const fs::path file = spirvCacheFile(key);
  if (file.empty()) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Layout: magic, key length (8 bytes), key, SPIR-V words.
  const size_t head = kMagic.size() + sizeof(uint64_t);
  if (bytes.size() < head || std::string_view(bytes).substr(0, kMagic.size()) != kMagic)
    return std::nullopt;
  uint64_t keySize = 0;
  std::memcpy(&keySize, bytes.data() + kMagic.size(), sizeof keySize);
  if (keySize > bytes.size() - head || std::string_view(bytes).substr(head, keySize) != key)
    return std::nullopt;
  const size_t spirvBytes = bytes.size() - head - keySize;
  if (spirvBytes < 20 || spirvBytes % 4 != 0) return std::nullopt;
  std::vector<uint32_t> words(spirvBytes / 4);
  std::memcpy(words.data(), bytes.data() + head + keySize, spirvBytes);
  if (words[0] != kSpirvMagic) return std::nullopt;
  return words;
}

bool storeCachedSpirv(const std::string& key, std::span<const uint32_t> words) {
  const fs::path file = spirvCacheFile(key);
  if (file.empty()) return false;
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  static std::atomic<unsigned> counter{0};
  const fs::path temp =
      file.string() + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    const uint64_t keySize = key.size();
    out.write(kMagic.data(), static_cast<std::streamsize>(kMagic.size()));
    out.write(reinterpret_cast<const char*>(&keySize), sizeof keySize);
    out.write(key.data(), static_cast<std::streamsize>(key.size()));
    out.write(reinterpret_cast<const char*>(words.data()),
              static_cast<std::streamsize>(words.size_bytes()));
    if (!out.flush()) {
      out.close();
      fs::remove(temp, ec);
      return false;
    }
  }
  fs::rename(temp, file, ec);
  if (!ec) return true;
  fs::remove(temp, ec);
  return false;
}

}  // namespace osd_cull::vulkan::glsl
