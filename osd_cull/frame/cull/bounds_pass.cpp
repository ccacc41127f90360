#include "osd_cull/frame/cull/bounds_pass.h"

#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/limits.h"
#include "osd_cull/vk/pipeline.h"
#include "osd_cull/vk/shader_compiler.h"
#include "osd_cull/vk/transfer.h"

#include <shared/bounds_layout.h>
#include <shared/cull_layout.h>

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <string>

namespace osd_cull::frame {
namespace {

namespace sh = osd_cull::shader;

const vulkan::DescriptorBinding kBindings[] = {
    {sh::kBoundsBindingPoints, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kBoundsBindingCones, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kBoundsBindingRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};

// The Gregory index tables of shaders/bounds/gregory_bounds.glsl, from the tables the
// reference uses (bound::buildGregoryConeFromTangentCones enumerates the same vectors).
std::string gregoryTables() {
  using bound::kGregoryBoundary;
  using bound::kGregoryInterior;
  auto candidates = [](int i, int j) {
    std::vector<int> out;
    const int k = 4 * j + i;
    if (kGregoryBoundary[static_cast<size_t>(k)] >= 0) {
      out.push_back(kGregoryBoundary[static_cast<size_t>(k)]);
    } else {
      for (const bound::GregoryInterior& g : kGregoryInterior)
        if (g.i == i && g.j == j) out = {g.a, g.b};
    }
    return out;
  };
  std::vector<std::pair<int, int>> du, dv;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      for (int hi : candidates(i + 1, j))
        for (int lo : candidates(i, j)) du.emplace_back(hi, lo);
      for (int hi : candidates(j, i + 1))
        for (int lo : candidates(j, i)) dv.emplace_back(hi, lo);
    }
  // Signs of a_u b - a b_u (linear, so the corners decide), as the reference.
  std::vector<std::array<int, 3>> ru, rv;
  for (const bound::GregoryInterior& g : kGregoryInterior)
    for (int along = 0; along < 2; ++along) {
      bool positive = false, negative = false;
      for (int corner = 0; corner < 4; ++corner) {
        const double s = corner & 1, t = corner >> 1;
        const double a = g.a0 + g.as * s + g.at * t, b = g.b0 + g.bs * s + g.bt * t;
        const double value = along == 0 ? g.as * b - a * g.bs : g.at * b - a * g.bt;
        positive |= value > 0.0;
        negative |= value < 0.0;
      }
      auto& out = along == 0 ? ru : rv;
      if (positive) out.push_back({g.a, g.b, 1});
      if (negative) out.push_back({g.a, g.b, -1});
    }
  auto pairs = [](const std::string& name, const std::vector<std::pair<int, int>>& v) {
    std::string s = "const uint " + name + "Count = " + std::to_string(v.size()) + "u;\n";
    s += "const ivec2 " + name + "[" + std::to_string(v.size()) + "] = ivec2[](";
    for (size_t k = 0; k < v.size(); ++k)
      s += (k ? ", " : "") + std::string("ivec2(") + std::to_string(v[k].first) + ", " +
           std::to_string(v[k].second) + ")";
    return s + ");\n";
  };
  auto triples = [](const std::string& name, const std::vector<std::array<int, 3>>& v) {
    std::string s = "const uint " + name + "Count = " + std::to_string(v.size()) + "u;\n";
    s += "const ivec3 " + name + "[" + std::to_string(v.size()) + "] = ivec3[](";
    for (size_t k = 0; k < v.size(); ++k)
      s += (k ? ", " : "") + std::string("ivec3(") + std::to_string(v[k][0]) + ", " +
           std::to_string(v[k][1]) + ", " + std::to_string(v[k][2]) + ")";
    return s + ");\n";
  };
  if (du.size() + ru.size() > sh::kMaxVectors || dv.size() + rv.size() > sh::kMaxVectors)
    throw Error("BoundsPass: the Gregory tables exceed the shader's 64 vectors");
  return pairs("kGregoryDu", du) + pairs("kGregoryDv", dv) + triples("kGregoryRu", ru) +
         triples("kGregoryRv", rv);
}

double widen(float v) { return static_cast<double>(v); }

uint32_t backPatchConeCode(bound::BackPatchMethod method) {
  switch (method) {
    case bound::BackPatchMethod::TCone:
      return sh::kBoundsTCone;
    case bound::BackPatchMethod::NCone:
      return sh::kBoundsNCone;
    case bound::BackPatchMethod::TangentPlane:
      return sh::kBoundsTangentPlane;
    default:
      throw Error(std::string("BoundsPass: cull data exists for tcone, ncone and the tangent "
                              "plane, not for '") +
                  bound::toString(method) + "'");
  }
}

// Nießner & Loop §4.2: ACoN is the cone of the tangent cones (TCONE), CoN the cone of the
// normal patch (NCONE); Full needs none.
uint32_t displacedConeCode(bound::DisplacedExtension extension) {
  if (extension == bound::DisplacedExtension::ACoN) return sh::kBoundsTCone;
  return extension == bound::DisplacedExtension::CoN ? sh::kBoundsNCone : sh::kBoundsNoCone;
}

std::vector<float> checkedRanges(std::span<const bound::DisplacementRange> ranges,
                                 uint32_t patchCount) {
  if (ranges.size() != patchCount)
    throw Error("BoundsPass: " + std::to_string(ranges.size()) + " displacement ranges for " +
                std::to_string(patchCount) + " patches");
  for (size_t p = 0; p < ranges.size(); ++p) {
    const bound::DisplacementRange& r = ranges[p];
    if (!(std::isfinite(r.dmin) && std::isfinite(r.dmax) && r.dmin <= 0.0 && r.dmax >= 0.0))
      throw Error("BoundsPass: the displacement range of patch " + std::to_string(p) + " is [" +
                  std::to_string(r.dmin) + ", " + std::to_string(r.dmax) +
                  "], not finite with Dmin <= 0 <= Dmax");
  }
  return packDisplacementRanges(ranges);
}

}  // namespace

// The pipeline: one kernel for every method and output (push constants choose), so every
// pass on a device shares it (creating it runs lavapipe's LLVM for about 2 s).
struct BoundsPipeline {
  vulkan::UniqueDescriptorSetLayout setLayout;
  vulkan::UniquePipelineLayout layout;
  vulkan::UniquePipeline pipeline;
};

namespace {

std::shared_ptr<const BoundsPipeline> sharedPipeline(vulkan::Context& context) {
  static std::mutex mutex;
  static std::map<VkDevice, std::weak_ptr<const BoundsPipeline>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  std::weak_ptr<const BoundsPipeline>& slot = cache[context.device()];
  if (auto existing = slot.lock()) return existing;
  auto p = std::make_shared<BoundsPipeline>();
  p->setLayout = vulkan::createDescriptorSetLayout(context, kBindings);
  const std::vector<VkDescriptorSetLayout> layouts = {p->setLayout.get()};
  p->layout = vulkan::createPipelineLayout(context, layouts, sizeof(sh::BoundsConstants),
                                           VK_SHADER_STAGE_COMPUTE_BIT);
  const std::string text = "#version 450\n#extension GL_EXT_control_flow_attributes : require\n" +
                           std::string("#define OSD_CULL_POINTS_BDA ") +
                           pointsByAddressDefine(context) + "\n" + gregoryTables() +
                           "#include \"bounds/patch_bounds_main.glsl\"\n";
  p->pipeline = vulkan::createComputePipeline(
      context, p->layout.get(),
      vulkan::compileGlsl(text, "bounds/patch_bounds.comp", VK_SHADER_STAGE_COMPUTE_BIT));
  slot = p;
  return p;
}

}  // namespace

bool BoundsPass::hasCullData(bound::BackPatchMethod method) {
  return method == bound::BackPatchMethod::TCone || method == bound::BackPatchMethod::NCone ||
         method == bound::BackPatchMethod::TangentPlane;
}

BoundsPass::BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu,
                       bound::BackPatchMethod method)
    : BoundsPass(context, gpu, backPatchConeCode(method), sh::kBoundsOutputBackPatch, {}) {
  method_ = method;
}

BoundsPass::BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu,
                       bound::DisplacedExtension extension,
                       std::span<const bound::DisplacementRange> ranges)
    : BoundsPass(context, gpu, displacedConeCode(extension), sh::kBoundsOutputDisplaced,
                 checkedRanges(ranges, gpu.patchCount())) {
  displaced_ = true;
  extension_ = extension;
}

BoundsPass::BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu, uint32_t coneCode,
                       uint32_t outputKind, std::span<const float> ranges)
    : context_(context), gpu_(gpu), coneCode_(coneCode), outputKind_(outputKind) {
  const size_t n = std::max<uint32_t>(1, gpu.patchCount());
  const std::string of = " of " + std::to_string(gpu.patchCount()) + " patches";
  vulkan::checkStorageBufferRange(context, n * sh::kConeVec4s * 4 * sizeof(float),
                                  "BoundsPass: the cull data" + of);
  vulkan::checkStorageBufferRange(context, n * 2 * sizeof(float),
                                  "BoundsPass: the displacement ranges" + of);
  vulkan::checkedGroups2D(context, vulkan::groupCount(gpu.patchCount(), sh::kBoundsGroupSize),
                          "BoundsPass: the dispatch" + of);
  cones_ = vulkan::Buffer(context, n * sh::kConeVec4s * 4 * sizeof(float),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const std::vector<float> unused(2, 0.0f);
  const std::span<const float> r = ranges.empty() ? std::span<const float>(unused) : ranges;
  ranges_ = vulkan::Buffer(context, r.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context, ranges_, r);
  pipeline_ = sharedPipeline(context);
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, 1, kBindings);
  set_ = pool_->allocate(pipeline_->setLayout.get());
}

bool BoundsPass::dependsOnPoints() const { return !(displaced_ && coneCode_ == sh::kBoundsNoCone); }

BoundsPass::~BoundsPass() = default;

void BoundsPass::record(VkCommandBuffer cmd, double pointError, float shrink) {
  if (!(std::isfinite(pointError) && pointError >= 0.0))
    throw Error("BoundsPass::record: pointError must be finite and >= 0, got " +
                std::to_string(pointError));
  // First use, or readPointsFrom() since (a point record follows it by itself).
  if (boundPoints_ != gpu_.pointBinding().handle()) {
    vulkan::DescriptorWriter()
        .buffer(sh::kBoundsBindingPoints, gpu_.pointBinding())
        .buffer(sh::kBoundsBindingCones, cones_)
        .buffer(sh::kBoundsBindingRanges, ranges_)
        .update(context_.device(), set_);
    boundPoints_ = gpu_.pointBinding().handle();
  }
  sh::BoundsConstants c{};
  c.patchCount = gpu_.patchCount();
  c.bezierCount = gpu_.bezierCount();
  c.pointStride = gpu_.pointStride();
  c.pointOffset = gpu_.pointOffset();
  c.method = coneCode_;
  c.outputKind = outputKind_;
  // Rounded up: the shader's margins assume at least this error.
  c.pointError = static_cast<float>(pointError) * (1.0f + 1e-6f);
  c.shrink = shrink;
  // Writers of the points (an upload, the point update) and readers of the old cull data
  // (a cull) come first.
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kComputeReadWrite);
  if (c.patchCount > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout.get(), 0, 1,
                            &set_, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline_->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
    const vulkan::DispatchSize groups = vulkan::checkedGroups2D(
        context_, vulkan::groupCount(c.patchCount, sh::kBoundsGroupSize), "BoundsPass");
    vkCmdDispatch(cmd, groups.x, groups.y, 1);
    ++dispatches_;
  }
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kComputeRead);
}

double BoundsPass::run(double pointError, float shrink) {
  const auto start = std::chrono::steady_clock::now();
  context_.submit([&](VkCommandBuffer cmd) { record(cmd, pointError, shrink); });
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::vector<PatchBounds> BoundsPass::readBounds(vulkan::Context& context) const {
  if (displaced_)
    throw Error("BoundsPass::readBounds: this pass writes displaced cull data (readDisplaced)");
  return unpackCullData(vulkan::readback<float>(context, cones_), gpu_.patchCount());
}

std::vector<bound::DisplacedPatch> BoundsPass::readDisplaced(vulkan::Context& context) const {
  if (!displaced_)
    throw Error("BoundsPass::readDisplaced: this pass writes back-patch cull data (readBounds)");
  return unpackDisplacedPatches(vulkan::readback<float>(context, cones_), gpu_.patchCount());
}

std::vector<PatchBounds> unpackCullData(std::span<const float> data, uint32_t patchCount) {
  constexpr size_t kFloats = 4 * sh::kConeVec4s;
  if (data.size() < size_t{patchCount} * kFloats)
    throw Error("unpackCullData: " + std::to_string(data.size()) + " floats for " +
                std::to_string(patchCount) + " patches");
  std::vector<PatchBounds> out(patchCount);
  for (uint32_t p = 0; p < patchCount; ++p) {
    const float* f = &data[kFloats * p];
    bound::ConeOfNormals& c = out[p].cone;
    c.apex = {widen(f[0]), widen(f[1]), widen(f[2])};
    c.sinAngle = widen(f[3]);
    c.axis = {widen(f[4]), widen(f[5]), widen(f[6])};
    c.valid = f[7] < 0.0f;
    c.reason = c.valid ? bound::BackPatchVerdict::BackFacing
                       : static_cast<bound::BackPatchVerdict>(static_cast<uint32_t>(f[7]));
    out[p].derivatives = {widen(f[8]), widen(f[9]), widen(f[10])};
    c.minNormal = widen(f[11]);
    c.maxRadius = widen(f[12]);
    c.angle = widen(f[13]);
  }
  return out;
}

}  // namespace osd_cull::frame
