#include "osd_cull/vk/glsl/runtime_compiler.h"

#include "osd_cull/error.h"
#include "osd_cull/version.h"
#include "osd_cull/vk/glsl/shader_sources.h"
#include "osd_cull/vk/glsl/spirv_disk_cache.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>

#if defined(OSD_CULL_HAVE_OSD_GPU)
#include <opensubdiv/osd/glslPatchShaderSource.h>
#endif

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

namespace osd_cull::vulkan::glsl {

namespace {

constexpr std::string_view kOsdPatchBasis = "osd/patch_basis.glsl";

const std::string& osdPatchBasisText() {
#if defined(OSD_CULL_HAVE_OSD_GPU)
  static const std::string text =
      "#define OSD_PATCH_BASIS_GLSL\n" +
      OpenSubdiv::Osd::GLSLPatchShaderSource::GetPatchBasisShaderSource();
  return text;
#else
  throw Error(std::string(kOsdPatchBasis) +
              ": OpenSubdiv's osdGPU library was not found at build time; it provides the "
              "GLSL patch basis");
#endif
}

const EmbeddedShader* findEmbedded(std::string_view path) {
  for (const auto& s : embeddedShaders())
    if (s.path == path) return &s;
  return nullptr;
}

std::string normalize(const std::filesystem::path& p) {
  return p.lexically_normal().generic_string();
}

/// Resolves #include against the embedded files; results live as long as the includer.
class EmbeddedIncluder : public glslang::TShader::Includer {
 public:
  IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
    const std::filesystem::path dir = std::filesystem::path(includer).parent_path();
    if (auto* r = tryOpen(normalize(dir / header))) return r;
    return tryOpen(normalize(header));
  }
  IncludeResult* includeSystem(const char* header, const char*, size_t) override {
    return tryOpen(normalize(header));
  }
  void releaseInclude(IncludeResult*) override {}

 private:
  IncludeResult* tryOpen(const std::string& path) {
    std::string_view text;
    if (path == kOsdPatchBasis) {
      text = osdPatchBasisText();
    } else if (const EmbeddedShader* s = findEmbedded(path)) {
      text = s->text;
    } else {
      return nullptr;
    }
    results_.push_back(std::make_unique<IncludeResult>(path, text.data(), text.size(), nullptr));
    return results_.back().get();
  }
  std::vector<std::unique_ptr<IncludeResult>> results_;
};

EShLanguage languageOf(VkShaderStageFlagBits stage) {
  switch (stage) {
    case VK_SHADER_STAGE_VERTEX_BIT:
      return EShLangVertex;
    case VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT:
      return EShLangTessControl;
    case VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT:
      return EShLangTessEvaluation;
    case VK_SHADER_STAGE_GEOMETRY_BIT:
      return EShLangGeometry;
    case VK_SHADER_STAGE_FRAGMENT_BIT:
      return EShLangFragment;
    case VK_SHADER_STAGE_COMPUTE_BIT:
      return EShLangCompute;
    default:
      throw Error("shader compiler: unsupported stage " + std::to_string(stage));
  }
}

/// glslang prints "ERROR: name:line: message"; keep those lines, drop the summary.
std::string cleanLog(const std::string& log) {
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.empty() || line.find("compilation errors") != std::string::npos) continue;
    for (const char* prefix : {"ERROR: ", "WARNING: "})
      if (line.starts_with(prefix)) line = line.substr(std::char_traits<char>::length(prefix));
    out += "\n  " + line;
  }
  return out;
}

std::vector<uint32_t> compile(std::string_view text, const std::string& name,
                              VkShaderStageFlagBits stage, std::span<const ShaderDefine> defines) {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });

  const EShLanguage language = languageOf(stage);
  std::string preamble = "#extension GL_GOOGLE_include_directive : require\n";
  for (const auto& d : defines) preamble += "#define " + d.name + " " + d.value + "\n";

  glslang::TShader shader(language);
  const char* strings[] = {text.data()};
  const int lengths[] = {static_cast<int>(text.size())};
  const char* names[] = {name.c_str()};
  shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  EmbeddedIncluder includer;
  if (!shader.parse(GetDefaultResources(), 450, false, messages, includer))
    throw Error("GLSL compile of " + name + " failed:" + cleanLog(shader.getInfoLog()));
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages))
    throw Error("GLSL link of " + name + " failed:" + cleanLog(program.getInfoLog()));
  std::vector<uint32_t> spirv;
  glslang::SpvOptions options;
  options.validate = false;
  glslang::GlslangToSpv(*program.getIntermediate(language), spirv, &options);
  return spirv;
}

struct Cache {
  std::mutex mutex;
  std::map<std::string, Spirv> entries;
  CompileStats stats;
};

Cache& cache() {
  static Cache c;
  return c;
}

std::string cacheKey(std::string_view kind, std::string_view what, VkShaderStageFlagBits stage,
                     std::span<const ShaderDefine> defines) {
  std::string key(kind);
  key += '\0';
  key += what;
  key += '\0' + std::to_string(stage);
  for (const auto& d : defines) key += '\0' + d.name + '=' + d.value;
  return key;
}

/// Everything besides a variant's own text, stage and defines that its SPIR-V depends on:
/// versions and a hash of every file an #include can reach.
const std::string& environmentStamp() {
  static const std::string stamp = [] {
    uint64_t files = fnv1a64("");
    for (const auto& s : embeddedShaders()) {
      files = fnv1a64(s.path, files);
      files = fnv1a64(std::string_view("\0", 1), files);
      files = fnv1a64(s.text, files);
    }
    std::string basis = "none";
#if defined(OSD_CULL_HAVE_OSD_GPU)
    basis = std::to_string(fnv1a64(osdPatchBasisText()));
#endif
    return std::string("osd_cull ") + libraryVersion() + "; glslang " +
           std::to_string(GLSLANG_VERSION_MAJOR) + "." + std::to_string(GLSLANG_VERSION_MINOR) +
           "." + std::to_string(GLSLANG_VERSION_PATCH) + "; vulkan 1.2, spir-v 1.5; shaders " +
           std::to_string(files) + "; osd basis " + basis;
  }();
  return stamp;
}

/// Memory first, then the disk cache, then glslang. `text` is the variant's own text (the
/// memory key of a file names only its path).
Spirv cached(const std::string& key, std::string_view text,
             const std::function<std::vector<uint32_t>()>& build) {
  Cache& c = cache();
  {
    std::lock_guard lock(c.mutex);
    if (auto it = c.entries.find(key); it != c.entries.end()) {
      ++c.stats.hits;
      return it->second;
    }
  }
  // Load or compile outside the lock; a concurrent compile of the same key is harmless.
  const auto start = std::chrono::steady_clock::now();
  const std::string diskKey = shaderCacheKey(key, text);
  std::optional<std::vector<uint32_t>> words = loadCachedSpirv(diskKey);
  const bool fromDisk = words.has_value();
  bool stored = false;
  if (!fromDisk) {
    words = build();
    stored = storeCachedSpirv(diskKey, *words);
  }
  auto spirv = std::make_shared<const std::vector<uint32_t>>(std::move(*words));
  std::lock_guard lock(c.mutex);
  ++(fromDisk ? c.stats.diskHits : c.stats.compiles);
  c.stats.diskWrites += stored ? 1 : 0;
  c.stats.milliseconds +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return c.entries.emplace(key, std::move(spirv)).first->second;
}

}  // namespace

std::string shaderCacheKey(std::string_view memoryKey, std::string_view text) {
  std::string key = environmentStamp();
  key += '\0';
  key += memoryKey;
  key += '\0';
  key += text;
  return key;
}

std::string_view shaderText(std::string_view path) {
  if (path == kOsdPatchBasis) return osdPatchBasisText();
  if (const EmbeddedShader* s = findEmbedded(path)) return s->text;
  throw Error("shader " + std::string(path) + " is not embedded (files come from shaders/)");
}

Spirv compileShader(const ShaderSource& source) {
  const VkShaderStageFlagBits stage = shaderStageOf(source.path);
  const std::string_view text = shaderText(source.path);
  return cached(cacheKey("file", source.path, stage, source.defines), text,
                [&] { return compile(text, source.path, stage, source.defines); });
}

Spirv compileGlsl(std::string_view text, std::string_view name, VkShaderStageFlagBits stage,
                  std::span<const ShaderDefine> defines) {
  const std::string n(name);
  return cached(cacheKey(std::string("text\0", 5) + n, text, stage, defines), {},
                [&] { return compile(text, n, stage, defines); });
}

Spirv compile(const ShaderVariant& variant) {
  return variant.generated
             ? glsl::compileGlsl(variant.text, variant.name, variant.stage, variant.defines)
             : glsl::compileShader({variant.name, variant.defines});
}

CompileStats compileStats() {
  std::lock_guard lock(cache().mutex);
  return cache().stats;
}

}  // namespace osd_cull::vulkan::glsl
