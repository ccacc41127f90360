#include "osd_cull/frame/cull_frame.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <osd_cull/shared/draw_layout.h>
#include <osd_cull/shared/visibility_layout.h>

#include <algorithm>
#include <chrono>
#include <map>

namespace osd_cull::frame {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Submits, waits, returns the wall time of recording, submission and execution.
double timedSubmit(vulkan::Context& context, const std::function<void(VkCommandBuffer)>& record) {
  const auto start = Clock::now();
  context.submit(record);
  return msSince(start);
}

uint32_t drawStatusOf(uint32_t status) {
  using namespace shader;
  if (status & kStatusNewlyVisible) return kDrawStatusNewlyVisible;
  if (status & kStatusVisible) return kDrawStatusVisible;
  switch ((status >> kStatusStageShift) & 0xFu) {
    case kStageFrustum:
      return kDrawStatusFrustum;
    case kStageBackPatch:
      return kDrawStatusBackPatch;
    case kStageOcclusion:
      return kDrawStatusOccluded;
    default:
      return kDrawStatusNone;
  }
}

}  // namespace

// One slot of the statistics ring: the frame it holds, its two pipeline-statistics
// queries (0: first pass, 1: second pass, or in aggressive mode the statistics copy), the
// per-mesh counters copied on the GPU (VisibilityBuffer::recordStatsCopy) and, where the
// queue has them, kStageStamps timestamps: before pass 1, after pass 1, the pyramid, the
// cull and pass 2.
struct CullFrame::StatsSlot {
  static constexpr uint32_t kStageStamps = 5;
  StatsSlot(vulkan::Context& context, size_t meshes, bool gpuTimes)
      : queries(context, 2),
        counters(context, std::max<size_t>(1, meshes) * VisibilityBuffer::kStatsCopyWords * 4,
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, vulkan::MemoryUse::Readback) {
    if (gpuTimes) stamps.emplace(context, kStageStamps);
  }
  // The device has finished the frame: its last query and timestamp are written.
  bool finished() const {
    return queries.tryResult(1) && (!stamps || stamps->available(kStageStamps - 1));
  }
  void stamp(VkCommandBuffer cmd, uint32_t index) {
    if (stamps) stamps->write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, index);
  }
  std::optional<uint64_t> frame;  // none: never used
  bool aggressive = false;
  vulkan::PipelineStatisticsQuery queries;
  vulkan::Buffer counters;
  std::optional<vulkan::TimestampQuery> stamps;
};

const char* toString(CullDrawMode mode) {
  return mode == CullDrawMode::Filtered ? "filtered" : "tf0";
}

CullFrame::CullFrame(vulkan::Context& context, Renderer& renderer, RenderTarget& target,
                     std::span<const CullMesh> meshes, const CullFrameOptions& options)
    : context_(context),
      renderer_(renderer),
      target_(target),
      meshes_(meshes.begin(), meshes.end()),
      options_(options),
      programs_(std::make_unique<VisibilityPrograms>(context)) {
  if (!context.info().optional.hostQueryReset)
    throw Error("CullFrame: device '" + context.info().name +
                "' lacks hostQueryReset (a Vulkan 1.2 feature), needed by the statistics ring");
  if (options.statsSlots == 0) throw Error("CullFrame: CullFrameOptions::statsSlots must be >= 1");
  gpuNote_ = options.gpuTimes ? vulkan::TimestampQuery::unavailableReason(context)
                              : "timestamps off (CullFrameOptions::gpuTimes)";
  for (uint32_t i = 0; i < options.statsSlots; ++i)
    slots_.push_back(std::make_unique<StatsSlot>(context, meshes.size(), gpuNote_.empty()));
  const CullSettings& cull = options.cull;
  // Each mesh's stages: its own (CullMesh::stages) or the options'.
  auto stagesOf = [&](const CullMesh& m) {
    return m.stages ? *m.stages : CullStages{cull.frustum, cull.backPatch, cull.occlusion};
  };
  const bool anyOcclusion = std::any_of(meshes.begin(), meshes.end(), [&](const CullMesh& m) {
    return !stagesOf(m).occlusion.empty();
  });
  if (anyOcclusion && target.format().samples != VK_SAMPLE_COUNT_1_BIT)
    throw Error("CullFrame: Hi-Z occlusion needs a single-sample depth attachment");
  if (anyOcclusion) {
    pyramid_ = std::make_unique<HiZPyramid>(context, target.depth(), options.hiz);
    stage_ = std::make_unique<HiZCullStage>(context, *pyramid_);
  }
  bool unculled = false;  // a mesh without any stage draws from survivedResults_
  uint32_t base = 0;
  // Each mesh reads its adaptive levels from its own slot of its set's tessLevels()
  // (TessLevelsPass), reserved before any descriptor set of the set is written.
  std::map<GpuPatchSet*, uint32_t> levelSlots;
  for (const CullMesh& m : meshes_) levelSlotOf_.push_back(m.gpu ? levelSlots[m.gpu]++ : 0u);
  for (const auto& [gpu, slots] : levelSlots) gpu->reserveTessLevelSlots(context, slots);
  for (size_t i = 0; i < meshes_.size(); ++i) {
    const CullMesh& m = meshes_[i];
    if (!m.gpu || !m.host) throw Error("CullFrame: a mesh without GpuPatchSet or PatchSet");
    if (m.gpu->patchCount() != m.host->patchCount())
      throw Error("CullFrame: mesh '" + m.host->source + "' has " +
                  std::to_string(m.host->patchCount()) + " host and " +
                  std::to_string(m.gpu->patchCount()) + " device patches");
    itemBases_.push_back(base);
    base += m.gpu->patchCount();
    visibility_.push_back(
        std::make_unique<VisibilityBuffer>(context, *programs_, *m.gpu, options.firstFrame));
    // Issue 10: an instance joins the batch of an earlier one with the same patch set and
    // the same cull configuration; its model is its own.
    auto same = [&](const Batch& b) {
      const CullMesh& o = meshes_[b.members.front()];
      const auto validity = [](const CullMesh& x) {
        return x.backPatchValidity
                   ? std::optional<std::pair<bool, std::string>>(
                         {x.backPatchValidity->enabled, x.backPatchValidity->reason})
                   : std::nullopt;
      };
      return o.gpu == m.gpu && o.host == m.host && o.cullData == m.cullData &&
             o.displacementMap == m.displacementMap && o.uvCorners.data() == m.uvCorners.data() &&
             o.displacedKernel.extension == m.displacedKernel.extension &&
             o.displacedKernel.box == m.displacedKernel.box && validity(o) == validity(m) &&
             stagesOf(o) == stagesOf(m);
    };
    auto batch = options.batchInstances ? std::find_if(batches_.begin(), batches_.end(), same)
                                        : batches_.end();
    if (batch == batches_.end()) {
      batches_.emplace_back();
      batch = batches_.end() - 1;
    }
    batchOf_.push_back(size_t(batch - batches_.begin()));
    slotOf_.push_back(uint32_t(batch->members.size()));
    batch->members.push_back(i);
  }
  for (Batch& b : batches_) {
    const CullMesh& m = meshes_[b.members.front()];
    CullSettings settings = cull;
    const CullStages stages = stagesOf(m);
    settings.frustum = stages.frustum;
    settings.backPatch = stages.backPatch;
    settings.occlusion = stages.occlusion;
    const bool anyStage = stages.any();
    unculled = unculled || !anyStage;
    if (m.backPatchValidity) settings.backPatchValidity = *m.backPatchValidity;
    if (m.displacementMap) {
      settings.displacementMap = m.displacementMap;
      settings.uvCorners = m.uvCorners;
      settings.displacedKernel = m.displacedKernel;
    }
    settings.instanceCount = uint32_t(b.members.size());
    if (anyStage)
      b.pass = m.cullData
                   ? std::make_unique<CullPass>(context, *m.gpu, *m.host, settings, *m.cullData)
                   : std::make_unique<CullPass>(context, *m.gpu, *m.host, settings);
    if (b.pass) {
      std::vector<uint32_t> slots;
      for (size_t k : b.members) slots.push_back(levelSlotOf_[k]);
      b.pass->setTessLevelSlots(std::move(slots));
    }
    if (anyStage && b.members.size() > 1)
      for (size_t k = 0; k < b.members.size(); ++k)
        b.results.emplace_back(
            context, std::max<size_t>(4, size_t{m.gpu->patchCount()} * 4),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  }
  if (unculled) {
    survivedResults_ = vulkan::Buffer(context, std::max<size_t>(4, size_t{base} * 4),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vulkan::fill(context, survivedResults_, shader::kStageNone);
  }
}

const HiZPyramid& CullFrame::pyramid() const {
  if (!pyramid_) throw Error("CullFrame::pyramid: the frame runs no occlusion stage");
  return *pyramid_;
}

CullFrame::~CullFrame() = default;

void CullFrame::reset(FirstFrame firstFrame) {
  options_.firstFrame = firstFrame;
  for (auto& v : visibility_) v->reset(firstFrame);
}

void CullFrame::setOptions(const CullFrameOptions& options) {
  const HiZOptions hiz = options_.hiz;
  const FirstFrame first = options_.firstFrame;
  const CullSettings cull = options_.cull;
  const uint32_t slots = options_.statsSlots;
  options_ = options;
  options_.statsSlots = slots;
  options_.hiz = hiz;
  options_.firstFrame = first;
  options_.cull = cull;
}

CullFrame::Chunks CullFrame::chunks(size_t mesh) const {
  const GpuPatchSet& g = *meshes_[mesh].gpu;
  const TessellationOptions& t = options_.render.tessellation;
  return {indirectDrawChunk(t, kBezierPoints, g.bezierCount()),
          indirectDrawChunk(t, kGregoryPoints, g.gregoryCount())};
}

void CullFrame::recordPatchDraws(VkCommandBuffer cmd, const Camera& camera, bool secondPass) {
  for (size_t m = 0; m < meshes_.size(); ++m) {
    VisibilityBuffer& v = *visibility_[m];
    // The second pass draws only where a patch became newly visible: where the device has
    // conditional rendering, it skips the mesh's draws itself (in the tess-factor-0 variant
    // they would run the control shader over every patch), read from the count the
    // status update wrote in this command buffer, with no host round trip.
    const bool conditional = secondPass && v.beginIfNewlyVisible(cmd);
    recordMeshDraws(cmd, camera, m, secondPass);
    if (conditional) v.endCondition(cmd);
  }
}

void CullFrame::recordMeshDraws(VkCommandBuffer cmd, const Camera& camera, size_t m,
                                bool secondPass) {
  VisibilityBuffer& v = *visibility_[m];
  const GpuPatchSet& g = *meshes_[m].gpu;
  PatchDraw draw{meshes_[m].gpu, meshes_[m].host, itemBases_[m]};
  draw.model = &meshes_[m].model;
  draw.cullBackFaces = meshes_[m].cullBackFaces;
  draw.tessLevelSlot = levelSlotOf_[m];  // recorded by recordFirstPass when it applies
  if (options_.drawMode == CullDrawMode::TessFactorZero) {
    draw.set = secondPass ? v.secondPassAll() : v.firstPassAll();
    renderer_.recordSlots(cmd, camera, draw, PatchType::Bezier, 0, g.bezierCount(), {},
                          options_.render);
    renderer_.recordSlots(cmd, camera, draw, PatchType::Gregory, g.firstGregorySlot(),
                          g.gregoryCount(), {}, options_.render);
    return;
  }
  DrawListBuffers& list = secondPass ? v.secondPass() : v.firstPass();
  draw.set = list.drawSet;
  const Chunks c = chunks(m);
  const uint32_t maxBezier = v.maxDraws(PatchType::Bezier, c.bezier);
  renderer_.recordIndirect(cmd, camera, draw, PatchType::Bezier, list.commands, 0, list.counters,
                           4 * shader::kListDrawsBezier, maxBezier, options_.render);
  renderer_.recordIndirect(cmd, camera, draw, PatchType::Gregory, list.commands,
                           VkDeviceSize{maxBezier} * sizeof(VkDrawIndirectCommand), list.counters,
                           4 * shader::kListDrawsGregory, v.maxDraws(PatchType::Gregory, c.gregory),
                           options_.render);
}

CullFrame::StatsSlot& CullFrame::beginFrame(const Camera& camera) {
  if (camera.width != target_.width() || camera.height != target_.height())
    throw Error("CullFrame: camera viewport " + std::to_string(camera.width) + "x" +
                std::to_string(camera.height) + " differs from the render target " +
                std::to_string(target_.width()) + "x" + std::to_string(target_.height()));
  StatsSlot& slot = *slots_[nextFrame_ % slots_.size()];
  // The slot's last frame must be over before its queries are reset from the host.
  if (slot.frame && !slot.finished())
    throw Error("CullFrame::record: frame " + std::to_string(*slot.frame) + ", recorded " +
                std::to_string(slots_.size()) +
                " frames ago, has not finished on the device; wait for its submission first "
                "or use more CullFrameOptions::statsSlots");
  slot.queries.hostReset();
  if (slot.stamps) slot.stamps->hostReset();
  slot.frame = nextFrame_++;
  slot.aggressive = options_.aggressive;
  return slot;
}

void CullFrame::recordFirstPass(VkCommandBuffer cmd, const Camera& camera,
                                std::span<const GpuTriangleMesh* const> occluders,
                                StatsSlot& slot) {
  slot.stamp(cmd, 0);
  if (options_.drawMode == CullDrawMode::Filtered)
    for (size_t m = 0; m < meshes_.size(); ++m) {
      const Chunks c = chunks(m);
      visibility_[m]->recordFirstPassCommands(cmd, c.bezier, c.gregory);
    }
  // This view's adaptive levels, read by both passes and the cull kernel.
  for (size_t m = 0; m < meshes_.size(); ++m) {
    PatchDraw draw{meshes_[m].gpu, meshes_[m].host, itemBases_[m]};
    draw.model = &meshes_[m].model;
    renderer_.recordTessLevels(cmd, camera, draw, levelSlotOf_[m], options_.render);
  }
  for (Batch& b : batches_)
    if (b.pass) b.pass->useRecordedTessLevels();
  RenderOptions pass = options_.render;
  pass.clear = true;
  renderer_.beginPass(cmd, target_, pass);
  slot.queries.begin(cmd, 0);
  renderer_.recordOccluders(cmd, camera, occluders);
  recordPatchDraws(cmd, camera, false);
  slot.queries.end(cmd, 0);
  renderer_.endPass(cmd);
  slot.stamp(cmd, 1);
}

void CullFrame::recordPyramid(VkCommandBuffer cmd, StatsSlot& slot) {
  if (pyramid_) pyramid_->record(cmd, target_.depthLayout());
  slot.stamp(cmd, 2);
}

void CullFrame::recordBatchCull(VkCommandBuffer cmd, const Camera& camera, Batch& batch) {
  // One dispatch for every instance: frustum → back-patch → Hi-Z occlusion, a result code
  // per (instance, patch), each instance culled in its object space with view · model
  // composed in double (instanceCamera).
  std::vector<Camera> cameras;
  for (size_t m : batch.members) cameras.push_back(instanceCamera(camera, meshes_[m].model));
  // The occlusion stage's set only for a pass that has that stage (meshes' stages differ).
  const bool occlusion = stage_ && !batch.pass->settings().occlusion.empty();
  batch.pass->record(cmd, cameras, options_.render.tessellation,
                     occlusion ? stage_->set() : VK_NULL_HANDLE);
  if (batch.members.size() == 1) {
    vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kComputeRead);
    return;
  }
  // Each instance's codes into its own buffer for its status update (VisibilityBuffer
  // reads a whole buffer).
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kTransferRead);
  const VkDeviceSize bytes = VkDeviceSize{batch.pass->results().size()} * 4;
  for (size_t k = 0; k < batch.members.size(); ++k) {
    const VkBufferCopy region{k * bytes, 0, bytes};
    if (bytes > 0)
      vkCmdCopyBuffer(cmd, batch.pass->resultsBuffer().handle(), batch.results[k].handle(), 1,
                      &region);
  }
  vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite, vulkan::scope::kComputeRead);
}

void CullFrame::recordCull(VkCommandBuffer cmd, const Camera& camera, StatsSlot& slot) {
  for (Batch& batch : batches_) {
    if (batch.pass) recordBatchCull(cmd, camera, batch);
    for (size_t k = 0; k < batch.members.size(); ++k) {
      const size_t m = batch.members[k];
      const Chunks c = chunks(m);
      const vulkan::Buffer& results = !batch.pass             ? survivedResults_
                                      : batch.results.empty() ? batch.pass->resultsBuffer()
                                                              : batch.results[k];
      visibility_[m]->recordUpdate(cmd, results, c.bezier, c.gregory);
      visibility_[m]->recordStatsCopy(cmd, slot.counters,
                                      VkDeviceSize{m} * VisibilityBuffer::kStatsCopyWords * 4);
    }
  }
  slot.stamp(cmd, 3);
}

uint64_t CullFrame::cullDispatches() const {
  uint64_t n = 0;
  for (const Batch& b : batches_)
    if (b.pass) n += b.pass->dispatchCount();
  return n;
}

void CullFrame::recordSecondPass(VkCommandBuffer cmd, const Camera& camera, StatsSlot& slot) {
  // Query 1 ends after everything else of the frame: its result marks the frame finished.
  if (slot.aggressive) {
    slot.queries.begin(cmd, 1);
    slot.queries.end(cmd, 1);
  } else {
    RenderOptions pass = options_.render;
    pass.clear = false;
    renderer_.beginPass(cmd, target_, pass);
    slot.queries.begin(cmd, 1);
    recordPatchDraws(cmd, camera, true);
    slot.queries.end(cmd, 1);
    renderer_.endPass(cmd);
  }
  slot.stamp(cmd, 4);
}

uint64_t CullFrame::record(VkCommandBuffer cmd, const Camera& camera,
                           std::span<const GpuTriangleMesh* const> occluders) {
  StatsSlot& slot = beginFrame(camera);
  recordFirstPass(cmd, camera, occluders, slot);
  recordPyramid(cmd, slot);
  recordCull(cmd, camera, slot);
  recordSecondPass(cmd, camera, slot);
  for (auto& v : visibility_) v->advance();
  return *slot.frame;
}

std::optional<CullFrameStats> CullFrame::stats(uint64_t frame) const {
  const StatsSlot& slot = *slots_[frame % slots_.size()];
  if (slot.frame != frame) return std::nullopt;
  const std::optional<vulkan::PipelineStatistics> last = slot.queries.tryResult(1);
  if (!last || !slot.finished()) return std::nullopt;
  CullFrameStats s;
  s.frame = frame;
  s.gpuNote = gpuNote_;
  if (slot.stamps) {
    // All five are written: the last one is, and the device writes them in order.
    const vulkan::TimestampQuery& t = *slot.stamps;
    s.gpu.pass1 = *t.tryElapsedMs(0, 1);
    s.gpu.pyramid = *t.tryElapsedMs(1, 2);
    s.gpu.cull = *t.tryElapsedMs(2, 3);
    s.gpu.pass2 = *t.tryElapsedMs(3, 4);
    s.gpu.total = *t.tryElapsedMs(0, 4);
  }
  s.pass1 = slot.queries.result(0);  // available: it ended before query 1
  if (!slot.aggressive) s.pass2 = *last;
  const auto words = slot.counters.mappedAs<const uint32_t>();
  for (size_t m = 0; m < meshes_.size(); ++m) {
    const uint32_t* c = words.data() + m * VisibilityBuffer::kStatsCopyWords;
    const uint32_t* st = c + shader::kListCounterCount;
    s.patchesTotal += meshes_[m].gpu->patchCount();
    s.drawnPass1 += c[shader::kListSurvivorsBezier] + c[shader::kListSurvivorsGregory];
    s.culledFrustum += st[shader::kStatCulledFrustum];
    s.culledBackPatch += st[shader::kStatCulledBackPatch];
    s.culledOcclusion += st[shader::kStatCulledOcclusion];
    s.newlyVisible += st[shader::kStatNewlyVisible];
    s.survivors += st[shader::kStatSurvivors];
  }
  if (!slot.aggressive) s.drawnPass2 = s.newlyVisible;
  for (const Batch& b : batches_)
    if (b.pass && b.pass->clustersEnabled()) {
      const ClusterCounts k = b.pass->clusterCounts();
      s.clusters.clusters += k.clusters;
      s.clusters.culled += k.culled;
      s.clusters.accepted += k.accepted;
      s.clusters.undecided += k.undecided;
      s.clusters.perPatchInvocations += k.perPatchInvocations;
    }
  return s;
}

CullFrameStats CullFrame::render(const Camera& camera,
                                 std::span<const GpuTriangleMesh* const> occluders) {
  const auto start = Clock::now();
  uint64_t frame = 0;
  double pass1Ms = 0, pyramidMs = 0, cullMs = 0, pass2Ms = 0;
  if (!options_.timePasses) {
    context_.submit([&](VkCommandBuffer cmd) { frame = record(cmd, camera, occluders); });
  } else {
    // Diagnostic: the same commands, one submission and wait per pass.
    StatsSlot& slot = beginFrame(camera);
    frame = *slot.frame;
    pass1Ms = timedSubmit(
        context_, [&](VkCommandBuffer cmd) { recordFirstPass(cmd, camera, occluders, slot); });
    if (pyramid_)
      pyramidMs = timedSubmit(context_, [&](VkCommandBuffer cmd) { recordPyramid(cmd, slot); });
    cullMs = timedSubmit(context_, [&](VkCommandBuffer cmd) {
      if (!pyramid_) recordPyramid(cmd, slot);  // its timestamp only
      recordCull(cmd, camera, slot);
    });
    pass2Ms =
        timedSubmit(context_, [&](VkCommandBuffer cmd) { recordSecondPass(cmd, camera, slot); });
    for (auto& v : visibility_) v->advance();
  }
  const double frameMs = msSince(start);
  std::optional<CullFrameStats> s = stats(frame);
  if (!s) throw Error("CullFrame::render: the statistics of the finished frame are unavailable");
  s->frameMs = frameMs;
  s->pass1Ms = pass1Ms;
  s->pyramidMs = pyramidMs;
  s->cullMs = cullMs;
  s->pass2Ms = pass2Ms;
  return *s;
}

std::vector<uint32_t> CullFrame::readResults(size_t mesh) const {
  const uint32_t n = meshes_.at(mesh).gpu->patchCount();
  const CullPass* pass = cullPass(mesh);
  if (!pass) return std::vector<uint32_t>(n, shader::kStageNone);
  const auto r = pass->results(slotOf_[mesh]);
  return std::vector<uint32_t>(r.begin(), r.begin() + n);
}

FrameStats CullFrame::renderStatusView(RenderTarget& target, const Camera& camera,
                                       std::span<const GpuTriangleMesh* const> occluders) {
  if (statusLists_.empty()) {
    statusSetLayout_ = vulkan::createDescriptorSetLayout(context_, patchSetBindings());
    statusPool_ = std::make_unique<vulkan::DescriptorPool>(
        context_, static_cast<uint32_t>(meshes_.size()), patchSetBindings());
    for (const CullMesh& m : meshes_) {
      statusLists_.emplace_back(context_, std::max<size_t>(4, size_t{m.gpu->patchCount()} * 4),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
      statusSets_.push_back(statusPool_->allocate(statusSetLayout_.get()));
      m.gpu->writeDescriptorSet(context_.device(), statusSets_.back(), statusLists_.back());
    }
  }
  std::vector<PatchDraw> draws;
  for (size_t m = 0; m < meshes_.size(); ++m) {
    const std::vector<uint32_t> status = visibility_[m]->readStatus(context_);
    std::vector<uint32_t> list(std::max<size_t>(1, status.size()));
    for (uint32_t p = 0; p < status.size(); ++p)
      list[p] = p | (drawStatusOf(status[p]) << shader::kDrawListStatusShift);
    vulkan::upload<uint32_t>(context_, statusLists_[m], list);
    draws.push_back({meshes_[m].gpu, meshes_[m].host, itemBases_[m], statusSets_[m],
                     &meshes_[m].model, meshes_[m].cullBackFaces});
  }
  RenderOptions o = options_.render;
  o.clear = true;
  o.statusColors = true;
  o.debugColors = false;
  return renderer_.render(target, camera, draws, occluders, o);
}

}  // namespace osd_cull::frame
