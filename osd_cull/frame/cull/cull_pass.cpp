#include "osd_cull/frame/cull/cull_pass.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/drawn_triangle_set.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/draw/draw_chunks.h"
#include "osd_cull/frame/draw/tess_levels_pass.h"
#include "osd_cull/frame/shader_variants.h"
#include "osd_cull/parallel.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/limits.h"
#include "osd_cull/vk/pipeline.h"
#include "osd_cull/vk/shader_compiler.h"
#include "osd_cull/vk/transfer.h"

#include <osd_cull/shared/cluster_layout.h>
#include <osd_cull/shared/draw_layout.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <set>

namespace osd_cull::frame {

namespace {

namespace sh = osd_cull::shader;

const vulkan::DescriptorBinding kBindings[] = {
    {sh::kCullBindingPoints, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingCones, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingResults, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingDrawList, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingCounters, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingCommands, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingTable, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingParams, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingDisplacedView, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingTessLevels, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingBoxes, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingClusterWork, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingClusters, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingDeferred, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {sh::kCullBindingClusterMembers, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
     VK_SHADER_STAGE_COMPUTE_BIT}};

// What the outputs are read by after the pass: indirect draws, the patch draw shaders (draw
// list) and the host (results, counters).
constexpr vulkan::Scope kAfterCull{
    VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
        VK_PIPELINE_STAGE_HOST_BIT,
    VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_HOST_READ_BIT};

uint32_t maxDraws(uint32_t count, uint32_t chunk) { return (count + chunk - 1) / chunk; }

// Workgroups of the cull dispatch: each instance covers its patches with whole groups
// (shaders/cull/cull_main.glsl), instance after instance.
uint64_t cullGroups(uint32_t patches, uint32_t lanes, uint32_t instances) {
  return uint64_t{vulkan::groupCount(patches, sh::kCullGroupSize / lanes)} * instances;
}

// vkCmdUpdateBuffer takes at most 65536 bytes a call.
void updateBuffer(VkCommandBuffer cmd, const vulkan::Buffer& buffer, const void* data,
                  size_t bytes) {
  constexpr size_t kMaxUpdate = 65536;
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t offset = 0; offset < bytes; offset += kMaxUpdate)
    vkCmdUpdateBuffer(cmd, buffer.handle(), offset, std::min(kMaxUpdate, bytes - offset),
                      p + offset);
}

// A cone rounded to float toward "visible": sin of the half-angle rounded up; the apex and
// axis round to nearest, which the kernel's test margin covers (shaders/cull/cone.glsl).
float roundUp(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::max());
  return f;
}
float roundDown(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::max());
  return f;
}

// One patch's kConeVec4s vec4 (shared/cull_layout.h): the cone, then what the drawn-triangle
// bound needs (bound::bezierDerivativeBounds for Bézier patches).
void packCone(const bound::ConeOfNormals& c, const bound::DerivativeBounds& d, float* out) {
  out[0] = static_cast<float>(c.apex.x);
  out[1] = static_cast<float>(c.apex.y);
  out[2] = static_cast<float>(c.apex.z);
  out[3] = roundUp(c.sinAngle);
  out[4] = static_cast<float>(c.axis.x);
  out[5] = static_cast<float>(c.axis.y);
  out[6] = static_cast<float>(c.axis.z);
  out[7] = c.valid ? -1.0f : static_cast<float>(static_cast<uint32_t>(c.reason));
  out[8] = roundUp(d.g);
  out[9] = roundUp(d.h);
  out[10] = roundUp(d.maxAbs);
  out[11] = roundDown(c.minNormal);
  out[12] = roundUp(c.maxRadius);
  out[13] = roundUp(c.angle);
  out[14] = 0.0f;
  out[15] = 0.0f;
}

}  // namespace

std::vector<float> packPatchBoxes(const PatchSet& patches) {
  const size_t n = patches.patchCount();
  std::vector<float> boxes(n * sh::kBoxFloats);
  for (uint32_t p = 0; p < n; ++p) {
    const std::span<const glm::dvec3> points = patches.controlPoints(p);
    glm::dvec3 lo = points[0], hi = points[0];
    bool finite = true;
    for (const glm::dvec3& q : points) {
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
      finite = finite && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
    }
    // A non-finite point: a NaN box, which the kernel keeps as the reference keeps the
    // patch (kFrustumNonFinite), where min/max would drop a NaN.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int c = 0; c < 3; ++c) {
      boxes[c * n + p] = finite ? roundDown(lo[c]) : float(nan);
      boxes[(3 + c) * n + p] = finite ? roundUp(hi[c]) : float(nan);
    }
  }
  return boxes;
}

// The parts of a drawn-triangle kernel (shaders/cull/cull_main.glsl): the cull kernel that
// hands the patches the listed-triangle test could decide to the listed-triangle passes,
// those passes (one per patch type: Bezier, Gregory), and the lean cull kernel for views
// where no patch can be listed (CullPass::leanKernelApplies).
enum class CullPass::KernelPart { Deferring, Listed, ListedGregory, Lean };

// Where a drawn-triangle kernel takes the tessellation levels (CULL_LEVELS in
// shaders/cull/drawn_triangles.glsl): fixed at composition, since llvmpipe pays for every
// branch of a kernel whether or not a lane takes it. Uniform levels, the levels pass's exact
// adaptive levels, or adaptive levels computed from the curves with a slack (no levels
// pass: nothing can be listed there, so only the lean kernel has that source).
enum class CullPass::LevelSource : uint32_t { Uniform = 1, Exact = 2, Curves = 3 };

namespace {

using KernelPart = CullPass::KernelPart;
using LevelSource = CullPass::LevelSource;

// The kernel parts and level sources a drawn-triangle kernel is composed in: the listing
// needs exact levels, and the lean kernel serves the uniform levels where nothing can be
// listed and the computed ones (CullPass::kernelFor).
constexpr std::pair<KernelPart, LevelSource> kDrawnKernels[] = {
    {KernelPart::Deferring, LevelSource::Uniform},
    {KernelPart::Deferring, LevelSource::Exact},
    {KernelPart::Listed, LevelSource::Uniform},
    {KernelPart::Listed, LevelSource::Exact},
    {KernelPart::ListedGregory, LevelSource::Uniform},
    {KernelPart::ListedGregory, LevelSource::Exact},
    {KernelPart::Lean, LevelSource::Uniform},
    {KernelPart::Lean, LevelSource::Curves}};

// The kernel source of one configuration: generated declarations, then the stage files,
// then the main (shaders/cull/cull_main.glsl explains the macros).
std::string composeKernel(const std::vector<const CullMethod*>& stages, uint32_t lanes,
                          bool drawnTriangles, bool drawnEnumerate,
                          const CullMethod::Displaced* displaced, bool pointsByAddress,
                          bool patchBoxes, KernelPart part = KernelPart::Deferring,
                          LevelSource levels = LevelSource::Uniform, bool clusters = false) {
  auto has = [&](CullStage s) {
    return std::any_of(stages.begin(), stages.end(),
                       [&](const CullMethod* m) { return m->stage == s; });
  };
  std::string text = "#version 450\n";
  text += "#define CULL_LANES " + std::to_string(lanes) + "\n";
  text += std::string("#define OSD_CULL_POINTS_BDA ") + (pointsByAddress ? "1" : "0") + "\n";
  text += std::string("#define CULL_FRUSTUM ") + (has(CullStage::Frustum) ? "1" : "0") + "\n";
  text += std::string("#define CULL_BACK_PATCH ") + (has(CullStage::BackPatch) ? "1" : "0") + "\n";
  text += std::string("#define CULL_OCCLUSION ") + (has(CullStage::Occlusion) ? "1" : "0") + "\n";
  text += std::string("#define CULL_DRAWN ") +
          (drawnTriangles && has(CullStage::BackPatch) ? "1" : "0") + "\n";
  // The listing only refines the drawn-triangle back-patch test; elsewhere it is off, so the
  // kernel text (and its build-time SPIR-V) does not depend on it. With the bound it always
  // runs at low levels (bound::kDrawnListLowLevel), at every level with drawnEnumerate, in
  // its own pass over the patches the cull kernel deferred to it (on lavapipe the listing's
  // code costs every invocation of a kernel containing it, even where it never runs:
  // docs/results/cull-kernel-floor.md). The lean kernel, for views where no patch can be
  // listed (CullPass::record chooses it, leanKernelApplies()), defers nothing.
  const bool drawn = drawnTriangles && has(CullStage::BackPatch);
  const bool listed = drawn && (part == KernelPart::Listed || part == KernelPart::ListedGregory);
  const bool deferring = drawn && part == KernelPart::Deferring;
  text += std::string("#define CULL_DRAWN_ENUMERATE ") + (listed ? "1" : "0") + "\n";
  text += std::string("#define CULL_DRAWN_LISTED ") + (listed ? "1" : "0") + "\n";
  text += std::string("#define CULL_DRAWN_DEFER ") + (deferring ? "1" : "0") + "\n";
  if (listed)
    text += std::string("#define CULL_DRAWN_LISTED_GREGORY ") +
            (part == KernelPart::ListedGregory ? "1" : "0") + "\n";
  if (drawn) text += "#define CULL_LEVELS " + std::to_string(static_cast<uint32_t>(levels)) + "\n";
  if (listed || deferring)
    text += "#define CULL_DRAWN_LIST_LEVEL " +
            std::to_string(drawnEnumerate ? 64u : bound::kDrawnListLowLevel) + "\n";
  text += std::string("#define CULL_DISPLACED ") + (displaced ? "1" : "0") + "\n";
  text += std::string("#define CULL_PATCH_BOXES ") + (patchBoxes ? "1" : "0") + "\n";
  text += std::string("#define CULL_CLUSTERS ") + (clusters && !listed ? "1" : "0") + "\n";
  if (displaced)
    text += "#define DISPLACED_BOX " + std::to_string(static_cast<uint32_t>(displaced->box)) + "\n";
  for (const CullMethod* m : stages)
    if (m->generatedGlsl) text += m->generatedGlsl();
  text += "#include \"cull/frustum.glsl\"\n";
  for (const CullMethod* m : stages)
    if (m->stage != CullStage::Frustum) text += "#include \"" + m->glslFile + "\"\n";
  text += "#include \"cull/cull_main.glsl\"\n";
  return text;
}

constexpr const char* kCullKernelName = "cull/cull_kernel.comp";
const vulkan::ShaderSource kWriteDraws{"cull/write_draws.comp", {}};
const vulkan::ShaderSource kClusterCull{"cull/cluster_cull.comp", {}};

// The back-patch methods the cluster test serves: their per-patch test is the cone test of
// the cones the clusters are built from (bound/patch_clusters.h).
bool clusterMethod(const CullMethod* backPatch) {
  return backPatch == nullptr || backPatch->name == "tcone" || backPatch->name == "ncone";
}

}  // namespace

std::vector<vulkan::ShaderVariant> cullPassShaderVariants() {
  // Every kernel a CullPass can compose (as its constructor selects the stages): each stage
  // off or one of its registered methods, with or without the drawn-triangle bound (and its
  // listed-triangle refinement) and points by address; a displaced mesh has no back-patch stage and
  // the box of its displaced kernel (either box with the other methods), and a displaced kernel
  // needs a displaced mesh.
  auto methods = [](CullStage stage) {
    std::vector<const CullMethod*> list = {nullptr};
    for (const CullMethod& m : cullMethods())
      if (m.stage == stage) list.push_back(&m);
    return list;
  };
  std::vector<vulkan::ShaderVariant> variants = {vulkan::ShaderVariant::file(kWriteDraws),
                                                 vulkan::ShaderVariant::file(kClusterCull)};
  std::set<std::string> texts;
  for (const CullMethod* frustum : methods(CullStage::Frustum))
    for (const CullMethod* backPatch : methods(CullStage::BackPatch))
      for (const CullMethod* occlusion : methods(CullStage::Occlusion))
        for (const bool drawn : {false, true})
          for (const bool enumerate : {false, true})
            for (const bool bda : {false, true})
              for (const bool boxes : {false, true})
                for (const int box : {-1, 0, 1}) {  // -1: not displaced, else a DisplacedBox
                  if (enumerate && !(drawn && backPatch)) continue;
                  if (boxes && (occlusion || box >= 0)) continue;  // CullPass::patchBoxes()
                  if (box >= 0 && backPatch) continue;
                  if (occlusion && occlusion->displaced &&
                      (box < 0 || static_cast<int>(occlusion->displaced->box) != box))
                    continue;
                  std::vector<const CullMethod*> stages;
                  uint32_t lanes = 1;
                  for (const CullMethod* m : {frustum, backPatch, occlusion})
                    if (m) {
                      stages.push_back(m);
                      lanes = std::max(lanes, m->lanesPerPatch);
                    }
                  CullMethod::Displaced displaced;
                  displaced.box = static_cast<bound::DisplacedBox>(std::max(box, 0));
                  // With the listed-triangle test and, for the views where it cannot run,
                  // without (CullPass::leanKernelApplies).
                  // Clustered (CullSettings::clusters): static points, undisplaced, no
                  // occlusion, a cone method or none.
                  for (const auto& [part, levels] : kDrawnKernels)
                    for (const bool clusters : {false, true}) {
                      if (!(drawn && backPatch) &&
                          (part != KernelPart::Deferring || levels != LevelSource::Uniform))
                        continue;
                      if (clusters &&
                          (!boxes || occlusion || box >= 0 || !clusterMethod(backPatch)))
                        continue;
                      std::string text = composeKernel(stages, lanes, drawn, enumerate,
                                                       box >= 0 ? &displaced : nullptr, bda, boxes,
                                                       part, levels, clusters);
                      if (texts.insert(text).second)
                        variants.push_back(vulkan::ShaderVariant::glsl(
                            text, kCullKernelName, VK_SHADER_STAGE_COMPUTE_BIT));
                    }
                }
  return variants;
}

uint32_t indirectDrawChunk(const TessellationOptions& tessellation, uint32_t controlPoints,
                           uint32_t count) {
  if (count == 0) return 1;
  const uint32_t level = tessellation.mode == TessellationOptions::Mode::Uniform
                             ? std::min(tessellation.uniformLevel * 2, tessellation.maxLevel)
                             : tessellation.maxLevel;
  const std::vector<uint32_t> bounds(count, (level + 1) * (level + 1));
  const std::vector<DrawChunk> chunks = planDrawChunks(bounds, controlPoints);
  return std::max<uint32_t>(1, chunks.front().count);
}

CullPass::CullPass(vulkan::Context& context, GpuPatchSet& gpu, const PatchSet& host,
                   const CullSettings& settings, const vulkan::Buffer& cullData)
    : CullPass(context, gpu, host, settings, &cullData) {}

CullPass::CullPass(vulkan::Context& context, GpuPatchSet& gpu, const PatchSet& host,
                   const CullSettings& settings)
    : CullPass(context, gpu, host, settings, nullptr) {}

CullPass::CullPass(vulkan::Context& context, GpuPatchSet& gpu, const PatchSet& host,
                   const CullSettings& settings, const vulkan::Buffer* cullData)
    : context_(context), gpu_(gpu), host_(host), settings_(settings) {
  if (cullData != nullptr) {
    const VkDeviceSize needed =
        VkDeviceSize{std::max<uint32_t>(1, host.patchCount())} * sh::kConeVec4s * 16;
    if (cullData->size() < needed)
      throw Error("CullPass: the cull data buffer has " + std::to_string(cullData->size()) +
                  " bytes, " + std::to_string(needed) + " needed for " +
                  std::to_string(host.patchCount()) + " patches");
    cullData_ = cullData;
  }
  if (host.patchCount() != gpu.patchCount() || host.bezierCount != gpu.bezierCount())
    throw Error("CullPass: host PatchSet '" + host.source + "' has " +
                std::to_string(host.bezierCount) + " + " + std::to_string(host.gregoryCount) +
                " patches, the GpuPatchSet " + std::to_string(gpu.bezierCount()) + " + " +
                std::to_string(gpu.gregoryCount()));
  auto add = [&](const std::string& name, CullStage stage) {
    const CullMethod& m = cullMethod(name);
    if (m.stage != stage)
      throw Error("CullPass: method '" + name + "' is a " + toString(m.stage) + " method, not a " +
                  toString(stage) + " method");
    if (m.needsFloat64 && !context.info().optional.shaderFloat64)
      throw Error("CullPass: method '" + name +
                  "' computes in double and needs shaderFloat64, "
                  "which device '" +
                  context.info().name + "' lacks");
    stages_.push_back(&m);
    lanes_ = std::max(lanes_, m.lanesPerPatch);
  };
  if (settings.frustum) add("frustum", CullStage::Frustum);
  const bool displacedMesh = settings.displacementMap != nullptr;
  if (!settings.backPatch.empty()) {
    if (displacedMesh) {
      cullMethod(settings.backPatch);  // still reject unknown names
      backPatchNote_ = "back-patch culling off for " + host.source + ": " + kDisplacedBackPatchNote;
    } else if (settings.backPatchValidity.enabled) {
      add(settings.backPatch, CullStage::BackPatch);
    } else {
      cullMethod(settings.backPatch);  // still reject unknown names
      backPatchNote_ =
          "back-patch culling off for " + host.source + ": " + settings.backPatchValidity.reason;
    }
  }
  if (!settings.occlusion.empty()) add(settings.occlusion, CullStage::Occlusion);
  displacedKernel_ = settings.displacedKernel;
  for (const CullMethod* m : stages_)
    if (m->displaced) {
      if (!displacedMesh)
        throw Error("CullPass: method '" + m->name + "' bounds displaced surfaces; " + host.source +
                    " has no displacement map");
      displacedKernel_ = *m->displaced;
    }
  // With external cull data (the bounds pass's displaced output of an animated mesh) the
  // per-patch data is the GPU's; the host copy would be stale after one frame.
  if (displacedMesh && cullData_ == &conesBuffer_)
    displaced_ = bound::buildDisplacedPatches(host, settings.uvCorners, *settings.displacementMap,
                                              displacedKernel_.extension);

  if (settings.instanceCount == 0) throw Error("CullPass: " + host.source + ": 0 instances");
  const uint32_t n = host.patchCount();
  checkLimits(n);
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const VkBufferUsageFlags indirect = storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  if (cullData_ == &conesBuffer_) uploadHostCones(context);
  buildClusters(context);
  const std::vector<float> boxes = patchBoxes() ? packPatchBoxes(host) : std::vector<float>(1);
  boxes_ = vulkan::Buffer(context, boxes.size() * sizeof(float), storage);
  vulkan::upload<float>(context, boxes_, boxes);
  const size_t instances = settings.instanceCount;
  displacedView_ = vulkan::Buffer(context, instances * sizeof(sh::DisplacedView), storage);
  instances_ = vulkan::Buffer(context, 16 + instances * sizeof(sh::CullInstance), storage);
  std::vector<uint32_t> table(2, 0u);
  for (const CullMethod* m : stages_)
    if (m->table) table = m->table();
  table_ = vulkan::Buffer(context, table.size() * sizeof(uint32_t), storage);
  vulkan::upload<uint32_t>(context, table_, table);
  const size_t codes = std::max<size_t>(1, instances * n);
  results_ = vulkan::Buffer(context, codes * 4, storage, vulkan::MemoryUse::Readback);
  drawList_ = vulkan::Buffer(context, codes * 4, storage);
  deferred_ = vulkan::Buffer(context, (2 * sh::kDeferredHeader + 2 * instances * n) * 4, indirect);
  counters_ = vulkan::Buffer(context, instances * sh::kCounterCount * 4, indirect,
                             vulkan::MemoryUse::Readback);
  commands_ = vulkan::Buffer(context, instances * (size_t{n} + 2) * sizeof(VkDrawIndirectCommand),
                             indirect);
  std::fill_n(results_.mappedAs<uint32_t>().begin(), codes, sh::kResultInitial);
  std::fill_n(counters_.mappedAs<uint32_t>().begin(), instances * sh::kCounterCount, 0u);
  // Instance i reads its precomputed adaptive levels from slot i unless told otherwise
  // (setTessLevelSlots); reserved before the kernel's set is written.
  gpu.reserveTessLevelSlots(context, settings.instanceCount);
  for (uint32_t i = 0; i < settings.instanceCount; ++i) levelSlots_.push_back(i);
  buildPipelines(context);
}

CullPass::~CullPass() {
  // The draw set names this pass's draw list: the patch set must not keep (or rewrite) it.
  if (drawSet_ != VK_NULL_HANDLE) gpu_.releaseDrawListSet(drawSet_);
}

void CullPass::checkLimits(uint32_t n) const {
  // Everything the pass binds, dispatches or draws, named, before any buffer exists
  // (the points are GpuPatchSet's to check).
  const uint64_t instances = settings_.instanceCount;
  const std::string of = " of " + std::to_string(n) + " patches" +
                         (instances > 1 ? " x " + std::to_string(instances) + " instances" : "");
  vulkan::checkStorageBufferRange(context_, uint64_t{n} * 4 * sh::kConeVec4s * sizeof(float),
                                  "CullPass: the cones" + of);
  vulkan::checkStorageBufferRange(context_, instances * n * 4, "CullPass: the result codes" + of);
  vulkan::checkStorageBufferRange(context_, instances * n * 4, "CullPass: the draw list" + of);
  vulkan::checkStorageBufferRange(context_, (2 * sh::kDeferredHeader + 2 * instances * n) * 4,
                                  "CullPass: the listed-triangle candidates" + of);
  vulkan::checkStorageBufferRange(context_,
                                  instances * (uint64_t{n} + 2) * sizeof(VkDrawIndirectCommand),
                                  "CullPass: the draw commands" + of);
  vulkan::checkStorageBufferRange(context_, 16 + instances * sizeof(sh::CullInstance),
                                  "CullPass: the instance matrices" + of);
  vulkan::checkedGroups2D(context_, cullGroups(n, lanes_, settings_.instanceCount),
                          "CullPass: the cull dispatch" + of);
  vulkan::checkedGroupsXY(context_, vulkan::groupCount(n + 2, sh::kDrawsGroupSize), instances,
                          "CullPass: the draw-command dispatch" + of);
  vulkan::checkDrawIndirectCount(context_, n, "CullPass: the indirect draws" + of);
}

void CullPass::uploadHostCones(vulkan::Context& context) {
  constexpr size_t kFloatsPerCone = 4 * sh::kConeVec4s;
  constexpr size_t kConeBytes = kFloatsPerCone * sizeof(float);
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (displaced()) {
    const std::vector<float> packed = packDisplacedPatches(displaced_);
    conesBuffer_ = vulkan::Buffer(context, packed.size() * sizeof(float), storage);
    vulkan::upload<float>(context, conesBuffer_, packed);
    return;
  }
  if (backPatchEnabled())
    cones_ = bound::buildPatchCones(host_, stages_[settings_.frustum ? 1 : 0]->reference);
  if (cones_.empty()) {  // the binding exists in every kernel's set: a placeholder
    conesBuffer_ = vulkan::Buffer(context, kConeBytes, storage);
    vulkan::upload<float>(context, conesBuffer_, std::vector<float>(kFloatsPerCone, 0.0f));
    return;
  }
  // Packed straight into the buffer (unified memory) or the staging memory, over the host's
  // threads: at a million patches a full-size host copy first would cost more than the
  // packing (first touches of fresh memory cost about 3 ms per MB on the machine measured,
  // docs/results/cull-kernel-floor.md).
  static_assert(vulkan::kUploadChunkBytes % kConeBytes == 0, "whole cones per staging piece");
  conesBuffer_ = vulkan::Buffer(context, cones_.size() * kConeBytes, storage);
  vulkan::initializeGenerated(
      context, conesBuffer_, cones_.size() * kConeBytes,
      [&](std::span<std::byte> chunk, VkDeviceSize offset) {
        const uint32_t first = uint32_t(offset / kConeBytes);
        float* out = reinterpret_cast<float*>(chunk.data());
        const uint32_t inChunk = uint32_t(chunk.size() / kConeBytes);
        parallelChunks(inChunk, bound::kParallelConePatches, 0, [&](uint32_t begin, uint32_t end) {
          for (uint32_t i = begin; i < end; ++i) {
            const uint32_t p = first + i;
            const bound::DerivativeBounds d =
                host_.type(p) == PatchType::Bezier
                    ? bound::bezierDerivativeBounds(host_.controlPoints(p))
                    : bound::DerivativeBounds{};
            packCone(cones_[p], d, out + kFloatsPerCone * i);
          }
        });
      });
}

void CullPass::buildClusters(vulkan::Context& context) {
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (!settings_.clusters) {  // the bindings exist in every kernel's set: placeholders
    clusterWork_ = vulkan::Buffer(context, sh::kClusterWorkHeader * 4, storage);
    clusterData_ = vulkan::Buffer(context, 16, storage);
    clusterMembers_ = vulkan::Buffer(context, 16, storage);
    return;
  }
  const std::string why = "CullPass: clusters (CullSettings::clusters) on " + host_.source;
  if (settings_.instanceCount != 1)
    throw Error(why + " cull one instance, not " + std::to_string(settings_.instanceCount));
  if (displaced()) throw Error(why + " need an undisplaced mesh");
  if (!settings_.occlusion.empty())
    throw Error(why + " do not combine with the occlusion stage '" + settings_.occlusion + "'");
  if (!settings_.staticPoints || cullData_ != &conesBuffer_)
    throw Error(why +
                " need static points (CullSettings::staticPoints, host-built cones): "
                "the cluster bounds are built once");
  for (const CullMethod* m : stages_)
    if (m->stage == CullStage::BackPatch && !clusterMethod(m))
      throw Error(why + " serve the tcone and ncone back-patch methods, not '" + m->name + "'");
  clusters_ = bound::buildPatchClusters(host_, cones_, settings_.clusterModel);
  const size_t k = clusters_.clusters.size();
  std::vector<float> data(std::max<size_t>(1, k) * sh::kClusterVec4s * 4, 0.0f);
  std::vector<uint32_t> members(4 * k + clusters_.members.size() + 1, 0u);
  for (size_t i = 0; i < k; ++i) {
    const bound::PatchCluster& c = clusters_.clusters[i];
    float* v = &data[i * sh::kClusterVec4s * 4];
    for (int j = 0; j < 3; ++j) {
      v[j] = roundDown(c.boxMin[j]);
      v[4 + j] = roundUp(c.boxMax[j]);
      v[8 + j] = static_cast<float>(c.apex[j]);
      v[12 + j] = static_cast<float>(c.axis[j]);
    }
    v[3] = roundUp(c.sinAngle);
    v[7] = roundUp(c.cullSinAngle);
    v[11] = c.coneValid ? 1.0f : 0.0f;
    members[4 * i] = c.first;
    members[4 * i + 1] = c.bezierCount;
    members[4 * i + 2] = c.gregoryCount;
  }
  std::copy(clusters_.members.begin(), clusters_.members.end(), members.begin() + 4 * k);
  clusterData_ = vulkan::Buffer(context, data.size() * sizeof(float), storage);
  vulkan::upload<float>(context, clusterData_, data);
  clusterMembers_ = vulkan::Buffer(context, members.size() * 4, storage);
  vulkan::upload<uint32_t>(context, clusterMembers_, members);
  clusterWork_ =
      vulkan::Buffer(context, (sh::kClusterWorkHeader + size_t{host_.patchCount()}) * 4,
                     storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, vulkan::MemoryUse::Readback);
  std::fill_n(clusterWork_.mappedAs<uint32_t>().begin(), sh::kClusterWorkHeader, 0u);
}

bound::ClusterTests CullPass::clusterTests() const {
  bound::ClusterTests t;
  t.frustum = settings_.frustum;
  t.backPatch = backPatchEnabled();
  // Back-facing clusters are culled whole only where the per-patch test is the surface cone
  // test: the drawn-triangle test widens each cone per view (bound::widenCone).
  t.backCull = backPatchEnabled() && !drawnTriangles();
  t.accept = settings_.occlusion.empty();
  return t;
}

ClusterCounts CullPass::clusterCounts() const {
  if (!settings_.clusters) return {};
  const auto w = clusterWork_.mappedAs<const uint32_t>();
  return {uint32_t(clusters_.clusters.size()), w[sh::kClusterWorkCulled],
          w[sh::kClusterWorkAccepted], w[sh::kClusterWorkUndecided], w[sh::kClusterWorkListed]};
}

// The layouts and pipelines of one kernel configuration. Creating a pipeline runs the
// driver's compiler (lavapipe: LLVM, up to 0.4 s for the tangent-plane kernel), so passes with
// the same kernel on the same device share one: a scene with many instances of a mesh has a
// pass per instance and view. A drawn-triangle configuration has a kernel per part and level
// source (kDrawnKernels); each is created the first time a record needs it, so a pass that
// only ever draws uniform levels compiles no adaptive kernel.
struct CullPipelines {
  vulkan::UniqueDescriptorSetLayout setLayout;
  vulkan::UniqueDescriptorSetLayout stageSetLayout;
  vulkan::UniquePipelineLayout layout;
  vulkan::UniquePipeline draws;
  vulkan::UniquePipeline clusters;  ///< cluster_cull.comp, for clustered kernels only

  /// The pipeline of a composed kernel `text`, created on first use.
  VkPipeline kernel(vulkan::Context& context, const std::string& text) const {
    const std::lock_guard<std::mutex> lock(mutex);
    vulkan::UniquePipeline& p = kernels[text];
    if (!p)
      p = vulkan::createComputePipeline(
          context, layout.get(),
          vulkan::compileGlsl(text, kCullKernelName, VK_SHADER_STAGE_COMPUTE_BIT));
    return p.get();
  }

 private:
  mutable std::mutex mutex;
  mutable std::map<std::string, vulkan::UniquePipeline> kernels;
};

namespace {

std::shared_ptr<const CullPipelines> sharedPipelines(vulkan::Context& context,
                                                     const std::string& kernel,
                                                     const std::vector<const CullMethod*>& stages,
                                                     bool clusters) {
  static std::mutex mutex;
  static std::map<std::pair<VkDevice, std::string>, std::weak_ptr<const CullPipelines>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  std::weak_ptr<const CullPipelines>& slot = cache[{context.device(), kernel}];
  if (auto existing = slot.lock()) return existing;
  auto p = std::make_shared<CullPipelines>();
  p->setLayout = vulkan::createDescriptorSetLayout(context, kBindings);
  std::vector<VkDescriptorSetLayout> layouts = {p->setLayout.get()};
  for (const CullMethod* m : stages)
    if (!m->stageBindings.empty()) {
      p->stageSetLayout = vulkan::createDescriptorSetLayout(context, m->stageBindings);
      layouts.push_back(p->stageSetLayout.get());
    }
  p->layout = vulkan::createPipelineLayout(context, layouts, sizeof(sh::CullConstants),
                                           VK_SHADER_STAGE_COMPUTE_BIT);
  p->draws =
      vulkan::createComputePipeline(context, p->layout.get(), vulkan::compileShader(kWriteDraws));
  if (clusters)
    p->clusters = vulkan::createComputePipeline(context, p->layout.get(),
                                                vulkan::compileShader(kClusterCull));
  slot = p;
  return p;
}

}  // namespace

std::string CullPass::kernelText(KernelPart part, LevelSource levels) const {
  return composeKernel(stages_, lanes_, settings_.drawnTriangles, settings_.drawnEnumerate,
                       displaced() ? &displacedKernel_ : nullptr, gpu_.pointsByAddress(),
                       patchBoxes(), part, levels, settings_.clusters);
}

CullPass::Kernels CullPass::kernelsFor(const TessellationOptions& tessellation) const {
  Kernels k;
  if (!drawnTriangles()) {  // one kernel: nothing is deferred, no level is read
    k.cull = pipelines_->kernel(context_, kernelText(KernelPart::Deferring, LevelSource::Uniform));
    return k;
  }
  const TessellationOptions t = effectiveOptions(tessellation, gpu_.hasTransitionEdges());
  const LevelSource levels = t.mode == TessellationOptions::Mode::Uniform ? LevelSource::Uniform
                             : usesExactLevels(tessellation)              ? LevelSource::Exact
                                                                          : LevelSource::Curves;
  // The lean kernel where nothing can be listed: uniform levels above the list level (not
  // with drawnEnumerate, which lists at every level) and computed adaptive levels.
  const bool lean = levels == LevelSource::Curves ||
                    (levels == LevelSource::Uniform && !settings_.drawnEnumerate &&
                     leanKernelApplies(tessellation));
  if (lean) {
    k.cull = pipelines_->kernel(context_, kernelText(KernelPart::Lean, levels));
    return k;
  }
  k.cull = pipelines_->kernel(context_, kernelText(KernelPart::Deferring, levels));
  if (gpu_.bezierCount() > 0)
    k.listed = pipelines_->kernel(context_, kernelText(KernelPart::Listed, levels));
  if (gpu_.gregoryCount() > 0)
    k.listedGregory = pipelines_->kernel(context_, kernelText(KernelPart::ListedGregory, levels));
  return k;
}

void CullPass::buildPipelines(vulkan::Context& context) {
  pipelines_ = sharedPipelines(context, kernelText(KernelPart::Deferring, LevelSource::Uniform),
                               stages_, settings_.clusters);
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, 1, kBindings);
  set_ = pool_->allocate(pipelines_->setLayout.get());
  vulkan::DescriptorWriter()
      .buffer(sh::kCullBindingPoints, gpu_.pointBinding())
      .buffer(sh::kCullBindingCones, *cullData_)
      .buffer(sh::kCullBindingResults, results_)
      .buffer(sh::kCullBindingDrawList, drawList_)
      .buffer(sh::kCullBindingCounters, counters_)
      .buffer(sh::kCullBindingCommands, commands_)
      .buffer(sh::kCullBindingTable, table_)
      .buffer(sh::kCullBindingParams, gpu_.params())
      .buffer(sh::kCullBindingDisplacedView, displacedView_)
      .buffer(sh::kCullBindingInstances, instances_)
      .buffer(sh::kCullBindingTessLevels, gpu_.tessLevels())
      .buffer(sh::kCullBindingBoxes, boxes_)
      .buffer(sh::kCullBindingClusterWork, clusterWork_)
      .buffer(sh::kCullBindingClusters, clusterData_)
      .buffer(sh::kCullBindingClusterMembers, clusterMembers_)
      .buffer(sh::kCullBindingDeferred, deferred_)
      .update(context.device(), set_);
  boundTessLevels_ = gpu_.tessLevels().handle();
}

void CullPass::recordClusters(VkCommandBuffer cmd) {
  const bound::ClusterTests t = clusterTests();
  const uint32_t flags =
      (t.frustum ? sh::kClusterFlagFrustum : 0u) | (t.backPatch ? sh::kClusterFlagBackPatch : 0u) |
      (t.backCull ? sh::kClusterFlagBackCull : 0u) | (t.accept ? sh::kClusterFlagAccept : 0u);
  const uint32_t k = uint32_t(clusters_.clusters.size());
  uint32_t header[sh::kClusterWorkHeader] = {0u, 1u, 1u, 0u, 0u, 0u, 0u, 0u, k, 0u, flags, 0u};
  header[sh::kClusterWorkPatchesPerGroup] = sh::kCullGroupSize / lanes_;
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kTransferWrite);
  vkCmdUpdateBuffer(cmd, clusterWork_.handle(), 0, sizeof(header), header);
  vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite, vulkan::scope::kComputeReadWrite);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->clusters.get());
  vkCmdDispatch(cmd, vulkan::groupCount(k, sh::kClusterGroupSize), 1, 1);
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeReadWrite,
                        {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                         VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                             VK_ACCESS_INDIRECT_COMMAND_READ_BIT});
}

bool CullPass::leanKernelApplies(const TessellationOptions& tessellation) const {
  // The listing (shaders/cull/drawn_triangle_set.glsl) lists a patch only when its levels
  // are exact and every outer level is at most bound::kDrawnListLowLevel. Under uniform
  // levels an edge has max(1, min(L, max)) segments, a transition edge two halves of
  // h = min(L, floor(max / 2)) each (one segment in all when h = 0), as the kernel's
  // drawnEdgeLevels and drawnTrianglesFaceAway compute them.
  const TessellationOptions t = effectiveOptions(tessellation, gpu_.hasTransitionEdges());
  if (t.mode != TessellationOptions::Mode::Uniform) return false;
  uint32_t lowest = std::max(1u, std::min(t.uniformLevel, t.maxLevel));
  const uint32_t half = std::min(t.uniformLevel, t.maxLevel / 2);
  if (gpu_.hasTransitionEdges()) lowest = std::min(lowest, half == 0 ? 1u : 2 * half);
  return lowest > bound::kDrawnListLowLevel;
}

bool CullPass::patchBoxes() const {
  return settings_.staticPoints && !displaced() && settings_.occlusion.empty();
}

bool CullPass::backPatchEnabled() const {
  return std::any_of(stages_.begin(), stages_.end(),
                     [](const CullMethod* m) { return m->stage == CullStage::BackPatch; });
}

bound::CullTests CullPass::referenceTests() const {
  bound::CullTests t;
  t.frustum = settings_.frustum;
  for (const CullMethod* m : stages_)
    if (m->stage == CullStage::BackPatch) t.backPatch = m->reference;
  return t;
}

bound::CullTests CullPass::referenceTests(const Camera& camera,
                                          const TessellationOptions& tessellation,
                                          std::vector<bound::TriangleShape>& shapes) const {
  bound::CullTests t = referenceTests();
  shapes.clear();
  if (drawnTriangles()) {
    if (usesExactLevels(tessellation) && exactLevels_)
      // The levels the kernel and the draws read (slot 0: the reference checks instance 0).
      shapes = drawnTriangleShapes(readTessLevels(context_, gpu_, levelSlots_[0]));
    else
      shapes = drawnTriangleShapes(host_, camera.viewProjection(),
                                   glm::dvec2(camera.width, camera.height), tessellation);
    t.drawnShapes = shapes;
    t.drawnEnumerate = settings_.drawnEnumerate;
    t.drawnListLevel = bound::kDrawnListLowLevel;
    t.snapPerDistance = bound::snapPerDistance(camera.viewProjection(), camera.width, camera.height,
                                               context_.info().limits.subPixelPrecisionBits);
  }
  return t;
}

sh::CullInstance CullPass::instanceValues(const Camera& camera) const {
  const glm::dmat4 viewProj = camera.viewProjection();
  const bound::CullView view = bound::makeCullView(viewProj);
  sh::CullInstance c{};
  c.viewProjection = glm::mat4(viewProj);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  c.eye = glm::vec4(nan, nan, nan, 0.0f);
  if (view.eye) {
    // The scale between world-space and clip-space tangent-plane coefficients
    // (shaders/cull/tangent_plane_common.glsl); eyePosition() exists only when e.w != 0.
    const double invEw = 1.0 / std::abs(bound::homogeneousEye(viewProj).w);
    c.eye = glm::vec4(glm::vec3(*view.eye), static_cast<float>(invEw));
  }
  c.snapPerDistance =
      static_cast<float>(bound::snapPerDistance(viewProj, camera.width, camera.height,
                                                context_.info().limits.subPixelPrecisionBits) *
                         1.001);
  return c;
}

sh::CullConstants CullPass::constants(const Camera& camera,
                                      const TessellationOptions& tessellation) const {
  const sh::CullInstance instance = instanceValues(camera);
  sh::CullConstants c{};
  c.viewProjection = instance.viewProjection;
  c.eye = instance.eye;
  c.snapPerDistance = instance.snapPerDistance;
  // The tessellation the draw shaders will use (Renderer applies effectiveOptions() too).
  const TessellationOptions t = effectiveOptions(tessellation, gpu_.hasTransitionEdges());
  c.viewport = glm::vec4(float(camera.width), float(camera.height), float(t.uniformLevel),
                         float(t.maxLevel));
  c.tessPixelsPerSegment =
      t.mode == TessellationOptions::Mode::Uniform ? 0.0f : float(t.pixelsPerSegment);
  c.patchCount = gpu_.patchCount();
  c.bezierCount = gpu_.bezierCount();
  c.pointStride = gpu_.pointStride();
  c.pointOffset = gpu_.pointOffset();
  c.drawChunkBezier = indirectDrawChunk(tessellation, kBezierPoints, gpu_.bezierCount());
  c.drawChunkGregory = indirectDrawChunk(tessellation, kGregoryPoints, gpu_.gregoryCount());
  return c;
}

void CullPass::record(VkCommandBuffer cmd, const Camera& camera,
                      const TessellationOptions& tessellation, VkDescriptorSet stageSet) {
  record(cmd, std::span<const Camera>(&camera, 1), tessellation, stageSet);
}

void CullPass::record(VkCommandBuffer cmd, std::span<const Camera> cameras,
                      const TessellationOptions& tessellation, VkDescriptorSet stageSet) {
  if (pipelines_->stageSetLayout && stageSet == VK_NULL_HANDLE)
    throw Error("CullPass::record: the occlusion stage '" + settings_.occlusion +
                "' needs its descriptor set");
  if (cameras.size() != settings_.instanceCount)
    throw Error("CullPass::record: " + std::to_string(cameras.size()) + " cameras for " +
                std::to_string(settings_.instanceCount) + " instances of " + host_.source);
  const sh::CullConstants c = constants(cameras.front(), tessellation);
  exactLevels_ = usesExactLevels(tessellation);  // of this record, before the instances read it
  // The instances' view · model values (shared/cull_layout.h CullInstance) and, displaced,
  // their camera-space matrices, written in the command buffer so frames in flight keep
  // their own.
  std::vector<uint8_t> instanceData(16 + cameras.size() * sizeof(sh::CullInstance), 0);
  const uint32_t header[4] = {uint32_t(cameras.size()), 0u, 0u, 0u};
  std::memcpy(instanceData.data(), header, sizeof(header));
  for (size_t i = 0; i < cameras.size(); ++i) {
    sh::CullInstance v = instanceValues(cameras[i]);
    v.exactLevels = exactLevels_ ? 1u : 0u;
    v.levelSlot = levelSlots_[i];
    std::memcpy(instanceData.data() + 16 + i * sizeof(v), &v, sizeof(v));
  }
  chunkBezier_ = c.drawChunkBezier;
  chunkGregory_ = c.drawChunkGregory;
  // Exact adaptive levels: the levels pass for every instance (unless the caller recorded it
  // for this frame, recordTessLevels()), read by the kernel and by the survivors' draws.
  if (exactLevels_ && !levelsRecorded_) recordTessLevels(cmd, cameras, tessellation);
  levelsRecorded_ = false;
  if (gpu_.tessLevels().handle() != boundTessLevels_) {  // reserveTessLevelSlots() moved it
    vulkan::DescriptorWriter()
        .buffer(sh::kCullBindingTessLevels, gpu_.tessLevels())
        .update(context_.device(), set_);
    boundTessLevels_ = gpu_.tessLevels().handle();
  }
  // Earlier readers of the outputs (draws, host) and writers of the points come first.
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kTransferWrite);
  vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
  const Kernels kernels = kernelsFor(tessellation);
  const bool listed = kernels.listed != VK_NULL_HANDLE || kernels.listedGregory != VK_NULL_HANDLE;
  // The first word of the Gregory candidates' list (shared/cull_layout.h deferred[]).
  const VkDeviceSize gregoryList =
      (sh::kDeferredHeader + 2 * VkDeviceSize{settings_.instanceCount} * gpu_.bezierCount()) * 4;
  if (listed) {  // no candidates yet; dispatches of 0 x 1 x 1 groups
    const uint32_t none[sh::kDeferredHeader] = {0u, 1u, 1u, 0u};
    vkCmdUpdateBuffer(cmd, deferred_.handle(), 0, sizeof(none), none);
    vkCmdUpdateBuffer(cmd, deferred_.handle(), gregoryList, sizeof(none), none);
  }
  updateBuffer(cmd, instances_, instanceData.data(), instanceData.size());
  if (displaced()) {
    std::vector<sh::DisplacedView> views;
    for (const Camera& camera : cameras) views.push_back(displacedView(camera));
    updateBuffer(cmd, displacedView_, views.data(), views.size() * sizeof(sh::DisplacedView));
  }
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kComputeReadWrite);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->layout.get(), 0, 1,
                          &set_, 0, nullptr);
  if (stageSet != VK_NULL_HANDLE)
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->layout.get(), 1, 1,
                            &stageSet, 0, nullptr);
  vkCmdPushConstants(cmd, pipelines_->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  const uint32_t n = gpu_.patchCount();
  if (n > 0) {
    if (settings_.clusters) recordClusters(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernels.cull);
    if (settings_.clusters) {  // the undecided clusters' patches (cluster_cull.comp)
      vkCmdDispatchIndirect(cmd, clusterWork_.handle(), 0);
    } else {
      const vulkan::DispatchSize groups = vulkan::checkedGroups2D(
          context_, cullGroups(n, lanes_, settings_.instanceCount), "CullPass: the cull dispatch");
      vkCmdDispatch(cmd, groups.x, groups.y, 1);
    }
    if (listed) {  // the candidates the kernel deferred (shaders/cull/cull_main.glsl)
      vulkan::memoryBarrier(
          cmd, vulkan::scope::kComputeReadWrite,
          {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
               VK_ACCESS_INDIRECT_COMMAND_READ_BIT});
      if (kernels.listed != VK_NULL_HANDLE) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernels.listed);
        vkCmdDispatchIndirect(cmd, deferred_.handle(), 0);
      }
      if (kernels.listedGregory != VK_NULL_HANDLE) {
        // Both passes append to the same draw lists and counters.
        if (kernels.listed != VK_NULL_HANDLE)
          vulkan::memoryBarrier(cmd, vulkan::scope::kComputeReadWrite,
                                vulkan::scope::kComputeReadWrite);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernels.listedGregory);
        vkCmdDispatchIndirect(cmd, deferred_.handle(), gregoryList);
      }
    }
    ++dispatches_;
  }
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeReadWrite, vulkan::scope::kComputeReadWrite);
  const uint32_t commandCount =
      maxDraws(gpu_.bezierCount(), chunkBezier_) + maxDraws(gpu_.gregoryCount(), chunkGregory_);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->draws.get());
  const vulkan::DispatchSize rows =
      vulkan::checkedGroupsXY(context_, vulkan::groupCount(commandCount, sh::kDrawsGroupSize),
                              settings_.instanceCount, "CullPass: the draw-command dispatch");
  vkCmdDispatch(cmd, rows.x, rows.y, 1);
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, kAfterCull);
}

bool CullPass::usesExactLevels(const TessellationOptions& tessellation) const {
  return drawnTriangles() && usesTessLevelsPass(gpu_, tessellation);
}

void CullPass::recordTessLevels(VkCommandBuffer cmd, std::span<const Camera> cameras,
                                const TessellationOptions& tessellation) {
  if (!usesExactLevels(tessellation)) return;
  if (cameras.size() != settings_.instanceCount)
    throw Error("CullPass::recordTessLevels: " + std::to_string(cameras.size()) + " cameras for " +
                std::to_string(settings_.instanceCount) + " instances of " + host_.source);
  if (!tessLevels_) tessLevels_ = std::make_unique<TessLevelsPass>(context_);
  for (uint32_t i = 0; i < cameras.size(); ++i)
    tessLevels_->record(cmd, cameras[i], nullptr, gpu_, levelSlots_[i], tessellation);
  levelsRecorded_ = true;
}

void CullPass::setTessLevelSlots(std::vector<uint32_t> slots) {
  if (slots.size() != settings_.instanceCount)
    throw Error("CullPass::setTessLevelSlots: " + std::to_string(slots.size()) + " slots for " +
                std::to_string(settings_.instanceCount) + " instances of " + host_.source);
  for (uint32_t s : slots)
    if (s >= gpu_.tessLevelSlots())
      throw Error("CullPass::setTessLevelSlots: slot " + std::to_string(s) + " of a set with " +
                  std::to_string(gpu_.tessLevelSlots()) + " (GpuPatchSet::reserveTessLevelSlots)");
  levelSlots_ = std::move(slots);
}

double CullPass::run(const Camera& camera, const TessellationOptions& tessellation,
                     VkDescriptorSet stageSet) {
  const auto start = std::chrono::steady_clock::now();
  context_.submit([&](VkCommandBuffer cmd) { record(cmd, camera, tessellation, stageSet); });
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::span<const uint32_t> CullPass::results(uint32_t instance) const {
  if (instance >= settings_.instanceCount)
    throw Error("CullPass::results: instance " + std::to_string(instance) + " of " +
                std::to_string(settings_.instanceCount));
  return results_.mappedAs<const uint32_t>().subspan(size_t{instance} * gpu_.patchCount(),
                                                     gpu_.patchCount());
}

CullCounts CullPass::counts(uint32_t instance) const {
  if (instance >= settings_.instanceCount)
    throw Error("CullPass::counts: instance " + std::to_string(instance) + " of " +
                std::to_string(settings_.instanceCount));
  const auto c = counters_.mappedAs<const uint32_t>().subspan(size_t{instance} * sh::kCounterCount);
  return {c[sh::kCounterSurvivorsBezier], c[sh::kCounterSurvivorsGregory],
          c[sh::kCounterDrawsBezier], c[sh::kCounterDrawsGregory]};
}

std::vector<uint32_t> CullPass::survivors(vulkan::Context& context) const {
  const CullCounts n = counts();
  const std::vector<uint32_t> list = vulkan::readback<uint32_t>(context, drawList_);
  std::vector<uint32_t> out(list.begin(), list.begin() + n.survivorsBezier);
  out.insert(out.end(), list.begin() + gpu_.bezierCount(),
             list.begin() + gpu_.bezierCount() + n.survivorsGregory);
  return out;
}

uint32_t CullPass::recordDraws(VkCommandBuffer cmd, Renderer& renderer, const Camera& camera,
                               const RenderOptions& options, uint32_t itemBase) {
  if (settings_.instanceCount != 1)
    throw Error("CullPass::recordDraws: the pass culls " + std::to_string(settings_.instanceCount) +
                " instances of " + host_.source + "; draw them through CullFrame");
  const uint32_t chunkB =
      indirectDrawChunk(options.tessellation, kBezierPoints, gpu_.bezierCount());
  const uint32_t chunkG =
      indirectDrawChunk(options.tessellation, kGregoryPoints, gpu_.gregoryCount());
  if (chunkB != chunkBezier_ || chunkG != chunkGregory_)
    throw Error("CullPass::recordDraws: the draw commands were written for " +
                std::to_string(chunkBezier_) + "/" + std::to_string(chunkGregory_) +
                " patches per draw, these tessellation options need " + std::to_string(chunkB) +
                "/" + std::to_string(chunkG) + "; pass the same options to record()");
  if (drawSet_ == VK_NULL_HANDLE) drawSet_ = gpu_.descriptorSetWithDrawList(context_, drawList_);
  PatchDraw draw{&gpu_, &host_, itemBase, drawSet_};
  if (exactLevels_) draw.tessLevelSlot = levelSlots_[0];
  const uint32_t maxB = gpu_.bezierCount() ? maxDraws(gpu_.bezierCount(), chunkB) : 0;
  const uint32_t maxG = gpu_.gregoryCount() ? maxDraws(gpu_.gregoryCount(), chunkG) : 0;
  renderer.recordIndirect(cmd, camera, draw, PatchType::Bezier, commands_, 0, counters_,
                          4 * sh::kCounterDrawsBezier, maxB, options);
  renderer.recordIndirect(cmd, camera, draw, PatchType::Gregory, commands_,
                          VkDeviceSize{maxB} * sizeof(VkDrawIndirectCommand), counters_,
                          4 * sh::kCounterDrawsGregory, maxG, options);
  return maxB + maxG;
}

FrameStats renderCulled(Renderer& renderer, RenderTarget& target, const Camera& camera,
                        CullPass& pass, std::span<const GpuTriangleMesh* const> occluders,
                        const RenderOptions& options, VkDescriptorSet stageSet) {
  FrameStats stats = renderer.renderWith(
      target, camera, occluders, options,
      [&](VkCommandBuffer cmd) { pass.record(cmd, camera, options.tessellation, stageSet); },
      [&](VkCommandBuffer cmd) { return pass.recordDraws(cmd, renderer, camera, options); });
  stats.patchesDrawn = pass.counts().survivors();
  return stats;
}

}  // namespace osd_cull::frame
