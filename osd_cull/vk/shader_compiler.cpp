#include "osd_cull/vk/shader_compiler.h"

#include "osd_cull/error.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

namespace osd_cull::vulkan {

namespace {

// The second hash of a key starts from another offset basis, so that the pair is a 128-bit
// index (a collision in both is not a concern for a few hundred variants).
constexpr uint64_t kSecondSeed = 0x6c62272e07bb0142ull;

struct Cache {
  std::mutex mutex;
  std::map<std::pair<uint64_t, uint64_t>, Spirv> entries;
  ShaderCacheStats stats;
};

Cache& cache() {
  static Cache c;
  return c;
}

std::string defineList(std::span<const ShaderDefine> defines) {
  std::string s = "{";
  for (size_t i = 0; i < defines.size(); ++i)
    s += (i ? ", " : "") + defines[i].name + (defines[i].value.empty() ? "" : "=") +
         defines[i].value;
  return s + "}";
}

}  // namespace

namespace {

// MurmurHash3's finalizer: FNV-1a leaves keys that differ in their last bytes with hashes
// that differ in few bits; this spreads them over all 64.
uint64_t mix(uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  return h ^ (h >> 33);
}

}  // namespace

std::pair<uint64_t, uint64_t> spirvKeyHash(std::string_view key) {
  return {mix(fnv1a64(key)), mix(fnv1a64(key, kSecondSeed))};
}

ShaderVariant ShaderVariant::file(const ShaderSource& source) {
  ShaderVariant v;
  v.name = source.path;
  v.stage = shaderStageOf(source.path);
  v.defines = source.defines;
  return v;
}

ShaderVariant ShaderVariant::glsl(std::string_view text, std::string_view name,
                                  VkShaderStageFlagBits stage,
                                  std::span<const ShaderDefine> defines) {
  ShaderVariant v;
  v.name = name;
  v.stage = stage;
  v.defines.assign(defines.begin(), defines.end());
  v.generated = true;
  v.text = text;
  return v;
}

std::string ShaderVariant::key() const {
  std::string key = generated ? "text" : "file";
  key += '\0' + name + '\0' + std::to_string(stage);
  for (const auto& d : defines) key += '\0' + d.name + '=' + d.value;
  key += '\0';
  key += text;
  return key;
}

std::string ShaderVariant::describe() const {
  if (!generated) return name + " " + defineList(defines);
  // Generated text: its defines and includes say which configuration it is (e.g. the cull
  // kernel's CULL_* switches and method files); long lines (generated code) are left out.
  std::string s = name + " (generated, " + std::to_string(text.size()) + " bytes";
  if (!defines.empty()) s += ", " + defineList(defines);
  std::istringstream in(text);
  std::string line, lines;
  while (std::getline(in, line))
    for (const std::string_view directive : {"#define ", "#include "})
      if (line.starts_with(directive) && line.size() < 60)
        lines += (lines.empty() ? "" : ", ") + line.substr(directive.starts_with("#i") ? 1 : 8);
  return s + (lines.empty() ? "" : ": " + lines) + ")";
}

VkShaderStageFlagBits shaderStageOf(std::string_view path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".vert") return VK_SHADER_STAGE_VERTEX_BIT;
  if (ext == ".tesc") return VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
  if (ext == ".tese") return VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
  if (ext == ".geom") return VK_SHADER_STAGE_GEOMETRY_BIT;
  if (ext == ".frag") return VK_SHADER_STAGE_FRAGMENT_BIT;
  if (ext == ".comp") return VK_SHADER_STAGE_COMPUTE_BIT;
  throw Error("shader " + std::string(path) +
              ": unknown stage (extension must be .vert .tesc .tese .geom .frag or .comp)");
}

Spirv findEmbeddedSpirv(const ShaderVariant& variant) {
  const auto start = std::chrono::steady_clock::now();
  const auto hash = spirvKeyHash(variant.key());
  Cache& c = cache();
  std::lock_guard lock(c.mutex);
  if (auto it = c.entries.find(hash); it != c.entries.end()) {
    ++c.stats.hits;
    return it->second;
  }
  const std::span<const uint32_t> words = embeddedSpirvWords();
  for (const EmbeddedSpirv& e : embeddedSpirv())
    if (e.hash0 == hash.first && e.hash1 == hash.second) {
      auto spirv = std::make_shared<const std::vector<uint32_t>>(
          words.begin() + e.offset, words.begin() + e.offset + e.words);
      ++c.stats.embedded;
      c.stats.milliseconds +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      return c.entries.emplace(hash, std::move(spirv)).first->second;
    }
  return nullptr;
}

namespace {

Spirv embeddedOrThrow(const ShaderVariant& variant) {
  if (Spirv spirv = findEmbeddedSpirv(variant)) return spirv;
  throw Error("shader variant " + variant.describe() +
              " has no build-time SPIR-V in this library (" +
              std::to_string(embeddedSpirv().size()) +
              " variants are embedded): the module that requests it must list it "
              "(osd_cull/frame/shader_variants.h) so that the build compiles it");
}

}  // namespace

Spirv compileShader(const ShaderSource& source) {
  return embeddedOrThrow(ShaderVariant::file(source));
}

Spirv compileGlsl(std::string_view text, std::string_view name, VkShaderStageFlagBits stage,
                  std::span<const ShaderDefine> defines) {
  return embeddedOrThrow(ShaderVariant::glsl(text, name, stage, defines));
}

ShaderCacheStats shaderCacheStats() {
  std::lock_guard lock(cache().mutex);
  return cache().stats;
}

}  // namespace osd_cull::vulkan
