#include "osd_cull/frame/hiz/visibility_buffer.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/shader_variants.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <osd_cull/shared/draw_layout.h>

#include <algorithm>

namespace osd_cull::frame {

namespace {

using namespace shader;

std::vector<vulkan::DescriptorBinding> storageBindings(uint32_t count) {
  std::vector<vulkan::DescriptorBinding> b;
  for (uint32_t i = 0; i < count; ++i)
    b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
  return b;
}

const std::vector<vulkan::DescriptorBinding>& updateBindings() {
  static const auto b = storageBindings(kVisBindingStats + 1);
  return b;
}

const std::vector<vulkan::DescriptorBinding>& drawsBindings() {
  static const auto b = storageBindings(kDrawsBindingCommands + 1);
  return b;
}

uint32_t ceilDiv(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

// Compute writes of the lists and commands, seen by indirect draws, the draw shaders (list
// entries) and the host (counters, statistics).
constexpr vulkan::Scope kListReaders{
    VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT |
        VK_PIPELINE_STAGE_TRANSFER_BIT,
    VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_HOST_READ_BIT |
        VK_ACCESS_TRANSFER_READ_BIT};

// The second pass's conditional rendering reads the newly-visible count.
constexpr vulkan::Scope kConditionReader{VK_PIPELINE_STAGE_CONDITIONAL_RENDERING_BIT_EXT,
                                         VK_ACCESS_CONDITIONAL_RENDERING_READ_BIT_EXT};

const vulkan::ShaderSource kUpdateShader{"hiz/visibility_update.comp", {}};
const vulkan::ShaderSource kDrawsShader{"hiz/visibility_draws.comp", {}};

}  // namespace

const char* toString(FirstFrame policy) {
  switch (policy) {
    case FirstFrame::AllVisible:
      return "all";
    case FirstFrame::HalfVisible:
      return "half";
    case FirstFrame::NoneVisible:
      return "none";
  }
  return "?";
}

VisibilityPrograms::VisibilityPrograms(vulkan::Context& context)
    : update_(std::make_unique<vulkan::ComputeProgram>(context, kUpdateShader, updateBindings(),
                                                       sizeof(VisibilityConstants))),
      draws_(std::make_unique<vulkan::ComputeProgram>(context, kDrawsShader, drawsBindings(),
                                                      sizeof(VisibilityConstants))) {}

VisibilityPrograms::~VisibilityPrograms() = default;

uint32_t DrawListBuffers::bezier() const {
  return counters.mappedAs<const uint32_t>()[kListSurvivorsBezier];
}

uint32_t DrawListBuffers::gregory() const {
  return counters.mappedAs<const uint32_t>()[kListSurvivorsGregory];
}

VisibilityBuffer::VisibilityBuffer(vulkan::Context& context, const VisibilityPrograms& programs,
                                   GpuPatchSet& gpu, FirstFrame firstFrame)
    : context_(context), programs_(programs), gpu_(gpu) {
  const uint32_t n = std::max(1u, gpu.patchCount());
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const VkBufferUsageFlags indirect = storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  status_ = vulkan::Buffer(context, size_t{n} * 4, storage);
  conditional_ = context.info().optional.conditionalRendering;
  stats_ = vulkan::Buffer(
      context, kStatCount * 4,
      conditional_ ? storage | VK_BUFFER_USAGE_CONDITIONAL_RENDERING_BIT_EXT : storage,
      vulkan::MemoryUse::Readback);
  // Enough commands for one-patch draws of every patch: any chunk size fits.
  const size_t maxCommands = size_t{gpu.bezierCount()} + gpu.gregoryCount() + 2;
  // Sets: per list one draws set, per parity one update set per results buffer (a few).
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, 16, updateBindings());
  // Six patch draw sets (three compact lists, three full lists), owned here.
  drawSetLayout_ = vulkan::createDescriptorSetLayout(context, patchSetBindings());
  drawPool_ = std::make_unique<vulkan::DescriptorPool>(context, 6, patchSetBindings());
  auto drawSet = [&](const vulkan::Buffer& list) {
    const VkDescriptorSet set = drawPool_->allocate(drawSetLayout_.get());
    gpu.writeDescriptorSet(context.device(), set, list);
    return set;
  };
  auto makeList = [&](DrawListBuffers& l) {
    l.list = vulkan::Buffer(context, size_t{n} * 4, storage);
    l.counters =
        vulkan::Buffer(context, kListCounterCount * 4, indirect, vulkan::MemoryUse::Readback);
    l.commands = vulkan::Buffer(context, maxCommands * 16, indirect);
    l.drawSet = drawSet(l.list);
    l.draws = pool_->allocate(programs.draws().setLayout());
    vulkan::DescriptorWriter()
        .buffer(kDrawsBindingCounters, l.counters)
        .buffer(kDrawsBindingCommands, l.commands)
        .update(context.device(), l.draws);
  };
  for (auto& l : lists_) makeList(l);
  makeList(secondPass_);
  for (uint32_t i = 0; i < 2; ++i) {
    all_[i] = vulkan::Buffer(context, size_t{n} * 4, storage);
    allSets_[i] = drawSet(all_[i]);
  }
  secondAll_ = vulkan::Buffer(context, size_t{n} * 4, storage);
  secondAllSet_ = drawSet(secondAll_);
  reset(firstFrame);
}

VisibilityBuffer::~VisibilityBuffer() = default;

void VisibilityBuffer::reset(FirstFrame firstFrame) {
  const uint32_t n = gpu_.patchCount(), nb = gpu_.bezierCount();
  std::vector<uint32_t> status(std::max(1u, n), 0), list(std::max(1u, n), 0),
      all(std::max(1u, n), 0), none(std::max(1u, n), 0);
  std::array<uint32_t, kListCounterCount> counters{};
  for (uint32_t p = 0; p < n; ++p) {
    const bool visible = firstFrame == FirstFrame::AllVisible ||
                         (firstFrame == FirstFrame::HalfVisible && p % 2 == 0);
    const uint32_t entry = p | (kDrawStatusVisible << kDrawListStatusShift);
    status[p] = visible ? kStatusVisible : 0u;
    all[p] = visible ? entry : p | kDrawListCulled;
    none[p] = p | kDrawListCulled;
    if (!visible) continue;
    const bool bezier = p < nb;
    uint32_t& count = counters[bezier ? kListSurvivorsBezier : kListSurvivorsGregory];
    list[(bezier ? 0 : nb) + count++] = entry;
  }
  parity_ = 0;
  vulkan::upload<uint32_t>(context_, status_, status);
  vulkan::upload<uint32_t>(context_, lists_[0].list, list);
  vulkan::upload<uint32_t>(context_, all_[0], all);
  vulkan::upload<uint32_t>(context_, secondAll_, none);
  vulkan::upload<uint32_t>(context_, lists_[0].counters, counters);
  for (DrawListBuffers* l : {&lists_[1], &secondPass_}) vulkan::fill(context_, l->counters, 0);
  vulkan::fill(context_, stats_, 0);
}

uint32_t VisibilityBuffer::maxDraws(PatchType type, uint32_t chunk) const {
  return ceilDiv(type == PatchType::Bezier ? gpu_.bezierCount() : gpu_.gregoryCount(), chunk);
}

void VisibilityBuffer::recordFirstPassCommands(VkCommandBuffer cmd, uint32_t chunkBezier,
                                               uint32_t chunkGregory) {
  const VisibilityConstants c{gpu_.patchCount(), gpu_.bezierCount(), chunkBezier, chunkGregory};
  const uint32_t commands =
      maxDraws(PatchType::Bezier, chunkBezier) + maxDraws(PatchType::Gregory, chunkGregory);
  // The counters were written by the last update (and read by its indirect draws).
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kComputeReadWrite);
  programs_.draws().dispatch(cmd, firstPass().draws, std::as_bytes(std::span(&c, 1)),
                             std::max(1u, vulkan::groupCount(commands, kVisGroupSize)));
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, kListReaders);
}

VkDescriptorSet VisibilityBuffer::updateSet(const vulkan::Buffer& results) {
  const uint32_t next = parity_ ^ 1u;
  auto& set = updateSets_[{results.handle(), parity_}];
  if (set) return set;
  set = pool_->allocate(programs_.update().setLayout());
  vulkan::DescriptorWriter()
      .buffer(kVisBindingResults, results)
      .buffer(kVisBindingStatus, status_)
      .buffer(kVisBindingNextList, lists_[next].list)
      .buffer(kVisBindingNextCounters, lists_[next].counters)
      .buffer(kVisBindingNewList, secondPass_.list)
      .buffer(kVisBindingNewCounters, secondPass_.counters)
      .buffer(kVisBindingNextAll, all_[next])
      .buffer(kVisBindingNewAll, secondAll_)
      .buffer(kVisBindingStats, stats_)
      .update(context_.device(), set);
  return set;
}

void VisibilityBuffer::recordUpdate(VkCommandBuffer cmd, const vulkan::Buffer& results,
                                    uint32_t chunkBezier, uint32_t chunkGregory) {
  const VkDescriptorSet set = updateSet(results);
  DrawListBuffers& next = lists_[parity_ ^ 1u];
  // Earlier readers of the lists being rewritten: last frame's draws, the host.
  vulkan::memoryBarrier(cmd, kListReaders, vulkan::scope::kTransferWrite);
  if (conditional_) vulkan::memoryBarrier(cmd, kConditionReader, vulkan::scope::kTransferWrite);
  vkCmdFillBuffer(cmd, next.counters.handle(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, secondPass_.counters.handle(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, stats_.handle(), 0, VK_WHOLE_SIZE, 0);
  vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite, vulkan::scope::kComputeReadWrite);
  vulkan::memoryBarrier(cmd, kListReaders, vulkan::scope::kComputeWrite);
  const uint32_t n = gpu_.patchCount();
  const VisibilityConstants c{n, gpu_.bezierCount(), chunkBezier, chunkGregory};
  programs_.update().dispatch(cmd, set, std::as_bytes(std::span(&c, 1)),
                              std::max(1u, vulkan::groupCount(n, kVisGroupSize)));
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kComputeReadWrite);
  const uint32_t commands =
      maxDraws(PatchType::Bezier, chunkBezier) + maxDraws(PatchType::Gregory, chunkGregory);
  programs_.draws().dispatch(cmd, secondPass_.draws, std::as_bytes(std::span(&c, 1)),
                             std::max(1u, vulkan::groupCount(commands, kVisGroupSize)));
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, kListReaders);
  if (conditional_) vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, kConditionReader);
}

bool VisibilityBuffer::beginIfNewlyVisible(VkCommandBuffer cmd) const {
  if (!conditional_) return false;
  VkConditionalRenderingBeginInfoEXT info{VK_STRUCTURE_TYPE_CONDITIONAL_RENDERING_BEGIN_INFO_EXT};
  info.buffer = stats_.handle();
  info.offset = VkDeviceSize{kStatNewlyVisible} * 4;
  context_.cmdBeginConditionalRendering()(cmd, &info);
  return true;
}

void VisibilityBuffer::endCondition(VkCommandBuffer cmd) const {
  context_.cmdEndConditionalRendering()(cmd);
}

void VisibilityBuffer::recordStatsCopy(VkCommandBuffer cmd, const vulkan::Buffer& dst,
                                       VkDeviceSize offset) {
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kTransferRead);
  const VkBufferCopy counters{0, offset, kListCounterCount * 4};
  vkCmdCopyBuffer(cmd, firstPass().counters.handle(), dst.handle(), 1, &counters);
  const VkBufferCopy stats{0, offset + kListCounterCount * 4, kStatCount * 4};
  vkCmdCopyBuffer(cmd, stats_.handle(), dst.handle(), 1, &stats);
  vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite, vulkan::scope::kHostRead);
}

std::span<const uint32_t> VisibilityBuffer::stats() const {
  return stats_.mappedAs<const uint32_t>().first(kStatCount);
}

std::vector<uint32_t> VisibilityBuffer::readStatus(vulkan::Context& context) const {
  auto s = vulkan::readback<uint32_t>(context, status_);
  s.resize(gpu_.patchCount());
  return s;
}

std::vector<vulkan::ShaderVariant> visibilityShaderVariants() {
  return {vulkan::ShaderVariant::file(kUpdateShader), vulkan::ShaderVariant::file(kDrawsShader)};
}

}  // namespace osd_cull::frame
