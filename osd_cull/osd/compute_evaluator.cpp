#include "osd_cull/osd/compute_evaluator.h"

#include "osd/eval_stencils_layout.h"
#include "osd_cull/osd/shader_variants.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/pipeline.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace osd_cull::osd {
namespace {

constexpr uint32_t kGroupSize = 64;  // local_size_x of eval_stencils.comp
constexpr uint32_t kPlainBindings = 6;
constexpr uint32_t kDerivativeBindings = 10;

// What every VkComputeEvaluator on one DeviceContext shares: the ticket of the latest
// evaluation, which the static Synchronize waits for.
struct EvaluatorState {
  uint64_t lastTicket = 0;
};

EvaluatorState& evaluatorState(DeviceContext& deviceContext) {
  return *deviceContext.shared<EvaluatorState>("VkComputeEvaluator/state",
                                               [] { return std::make_shared<EvaluatorState>(); });
}

vulkan::ShaderSource stencilShader(bool derivatives) {
  vulkan::ShaderSource source{"osd/eval_stencils.comp", {}};
  if (derivatives) source.defines.push_back({"OSD_DERIVATIVES", "1"});
  return source;
}

std::shared_ptr<const vulkan::ComputeProgram> stencilKernel(DeviceContext& deviceContext,
                                                            int length, bool derivatives) {
  const std::string key = "osd/eval_stencils.comp length=" + std::to_string(length) +
                          (derivatives ? " derivatives" : "");
  return deviceContext.shared<vulkan::ComputeProgram>(key, [&] {
    std::vector<vulkan::DescriptorBinding> bindings;
    for (uint32_t b = 0; b < (derivatives ? kDerivativeBindings : kPlainBindings); ++b)
      bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
    const vulkan::ShaderSource source = stencilShader(derivatives);
    vulkan::SpecializationConstants constants;
    constants.set(0, int32_t{length});
    return std::make_shared<vulkan::ComputeProgram>(deviceContext.context(), source, bindings,
                                                    uint32_t{sizeof(gpu::EvalStencilsPush)},
                                                    constants);
  });
}

void checkDescriptor(const char* what, const BufferDescriptor& desc) {
  if (desc.offset < 0 || desc.stride <= 0 || !desc.IsValid())
    throw Error(std::string("VkComputeEvaluator: the ") + what + " descriptor (offset " +
                std::to_string(desc.offset) + ", length " + std::to_string(desc.length) +
                ", stride " + std::to_string(desc.stride) +
                ") is not valid: need offset >= 0 and 0 < length <= stride - offset % stride");
}

// Vertices [0, count) of `binding` must lie inside its buffer.
void checkRange(const char* what, const VkComputeEvaluator::Binding& binding, int count) {
  if (count <= 0) return;
  const int64_t last = int64_t{binding.desc.offset} +
                       int64_t{count - 1} * int64_t{binding.desc.stride} +
                       int64_t{binding.desc.length};
  if (last > static_cast<int64_t>(binding.floats))
    throw Error(std::string("VkComputeEvaluator: ") + what + " vertices [0, " +
                std::to_string(count) + ") at offset " + std::to_string(binding.desc.offset) +
                ", stride " + std::to_string(binding.desc.stride) + " need " +
                std::to_string(last) + " floats; the buffer has " + std::to_string(binding.floats));
}

}  // namespace

VkComputeEvaluator* VkComputeEvaluator::Create(BufferDescriptor const& srcDesc,
                                               BufferDescriptor const& dstDesc,
                                               BufferDescriptor const& duDesc,
                                               BufferDescriptor const& dvDesc,
                                               DeviceContext* deviceContext) {
  // EvaluatorCacheT deletes what Create returns: ownership leaves as a raw pointer by contract.
  return std::make_unique<VkComputeEvaluator>(requireContext(deviceContext), srcDesc, dstDesc,
                                              duDesc, dvDesc)
      .release();
}

VkComputeEvaluator* VkComputeEvaluator::Create(
    BufferDescriptor const& srcDesc, BufferDescriptor const& dstDesc,
    BufferDescriptor const& duDesc, BufferDescriptor const& dvDesc, BufferDescriptor const& duuDesc,
    BufferDescriptor const& duvDesc, BufferDescriptor const& dvvDesc,
    DeviceContext* deviceContext) {
  if (duuDesc.length > 0 || duvDesc.length > 0 || dvvDesc.length > 0)
    throw Error("VkComputeEvaluator::Create: second derivatives (duu, duv, dvv) are not supported");
  return Create(srcDesc, dstDesc, duDesc, dvDesc, deviceContext);
}

VkComputeEvaluator::VkComputeEvaluator(DeviceContext& deviceContext,
                                       BufferDescriptor const& srcDesc,
                                       BufferDescriptor const& dstDesc,
                                       BufferDescriptor const& duDesc,
                                       BufferDescriptor const& dvDesc)
    : deviceContext_(deviceContext),
      length_(srcDesc.length),
      derivatives_(duDesc.length > 0 || dvDesc.length > 0) {
  checkDescriptor("source", srcDesc);
  checkDescriptor("destination", dstDesc);
  for (const BufferDescriptor* d : {&dstDesc, &duDesc, &dvDesc})
    if (d->length > 0 && d->length != length_)
      throw Error("VkComputeEvaluator: source vertices have " + std::to_string(length_) +
                  " elements but an output descriptor has length " + std::to_string(d->length) +
                  " (stencils copy whole vertices)");
  kernel_ = stencilKernel(deviceContext, length_, derivatives_);
}

VkComputeEvaluator::~VkComputeEvaluator() = default;

DeviceContext& VkComputeEvaluator::requireContext(DeviceContext* deviceContext) {
  if (!deviceContext)
    throw Error("VkComputeEvaluator: needs a DeviceContext (Osd::Mesh's deviceContext argument)");
  return *deviceContext;
}

void VkComputeEvaluator::record(Batch& batch, const VkStencilTable& table, const Binding& src,
                                const Binding& dst, const Binding& du, const Binding& dv, int start,
                                int end) const {
  if (&table.deviceContext() != &deviceContext_)
    throw Error("VkComputeEvaluator: the stencil table belongs to another DeviceContext");
  if (!src.buffer || !dst.buffer)
    throw Error("VkComputeEvaluator: needs a source and a destination buffer");
  checkDescriptor("source", src.desc);
  checkDescriptor("destination", dst.desc);
  if (src.desc.length != length_ || dst.desc.length != length_)
    throw Error("VkComputeEvaluator: compiled for " + std::to_string(length_) +
                " elements per vertex, called with source length " +
                std::to_string(src.desc.length) + " and destination length " +
                std::to_string(dst.desc.length));
  const bool wantDerivatives = du.buffer || dv.buffer;
  if (wantDerivatives && !derivatives_)
    throw Error(
        "VkComputeEvaluator: du/dv outputs requested from an instance created without "
        "du/dv descriptors");
  if (wantDerivatives && !table.HasDerivatives())
    throw Error(
        "VkComputeEvaluator: du/dv outputs need a stencil table with du/dv weights "
        "(built from a Far::LimitStencilTable)");
  for (const auto& [name, d] : {std::pair{"du", &du}, std::pair{"dv", &dv}}) {
    if (!d->buffer) continue;
    checkDescriptor(name, d->desc);
    if (d->desc.length != length_)
      throw Error(std::string("VkComputeEvaluator: ") + name + " length " +
                  std::to_string(d->desc.length) + " differs from the vertex length " +
                  std::to_string(length_));
  }
  if (start < 0 || end > table.GetNumStencils() || start > end)
    throw Error("VkComputeEvaluator: stencils [" + std::to_string(start) + ", " +
                std::to_string(end) + ") outside the table's " +
                std::to_string(table.GetNumStencils()));
  if (start == end) return;
  checkRange("source", src, table.GetNumSourceVertices());
  checkRange("destination", dst, end);
  if (du.buffer) checkRange("du", du, end);
  if (dv.buffer) checkRange("dv", dv, end);

  // Descriptors. Unused derivative bindings point at buffers the shader never touches
  // at run time (their outputs are switched off by a zero length).
  std::array<VkDescriptorBufferInfo, kDerivativeBindings> infos{};
  infos[0] = {src.buffer, 0, VK_WHOLE_SIZE};
  infos[1] = {dst.buffer, 0, VK_WHOLE_SIZE};
  infos[2] = table.GetSizesBuffer().descriptor();
  infos[3] = table.GetOffsetsBuffer().descriptor();
  infos[4] = table.GetIndicesBuffer().descriptor();
  infos[5] = table.GetWeightsBuffer().descriptor();
  const uint32_t bindingCount = derivatives_ ? kDerivativeBindings : kPlainBindings;
  if (derivatives_) {
    infos[6] = {du.buffer ? du.buffer : dst.buffer, 0, VK_WHOLE_SIZE};
    infos[7] = {dv.buffer ? dv.buffer : dst.buffer, 0, VK_WHOLE_SIZE};
    const vulkan::Buffer& duWeights =
        table.HasDerivatives() ? table.GetDuWeightsBuffer() : table.GetWeightsBuffer();
    const vulkan::Buffer& dvWeights =
        table.HasDerivatives() ? table.GetDvWeightsBuffer() : table.GetWeightsBuffer();
    infos[8] = duWeights.descriptor();
    infos[9] = dvWeights.descriptor();
  }
  const VkDescriptorSet set = batch.allocateDescriptorSet(kernel_->setLayout());
  std::array<VkWriteDescriptorSet, kDerivativeBindings> writes{};
  for (uint32_t b = 0; b < bindingCount; ++b) {
    writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[b].dstSet = set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &infos[b];
  }
  vkUpdateDescriptorSets(deviceContext_.device(), bindingCount, writes.data(), 0, nullptr);

  gpu::EvalStencilsPush push{};
  push.srcOffset = src.desc.offset;
  push.srcStride = src.desc.stride;
  push.dstOffset = dst.desc.offset;
  push.dstStride = dst.desc.stride;
  push.duOffset = du.buffer ? du.desc.offset : 0;
  push.duStride = du.buffer ? du.desc.stride : 0;
  push.duLength = du.buffer ? du.desc.length : 0;
  push.dvOffset = dv.buffer ? dv.desc.offset : 0;
  push.dvStride = dv.buffer ? dv.desc.stride : 0;
  push.dvLength = dv.buffer ? dv.desc.length : 0;

  VkCommandBuffer cmd = batch.commandBuffer();
  // Earlier writers of the source (uploads, other evaluations) and earlier readers of the
  // destination (draws, read-backs) come first; later work sees the results.
  vulkan::memoryBarrier(cmd, vulkan::scope::kAll, vulkan::scope::kComputeReadWrite);
  const uint32_t maxGroups = std::min<uint32_t>(
      deviceContext_.context().info().limits.maxComputeWorkGroupCount[0], 65535u);
  const int chunk = static_cast<int>(maxGroups * kGroupSize);
  for (int first = start; first < end; first += chunk) {
    push.start = first;
    push.end = std::min(end, first + chunk);
    kernel_->dispatch(cmd, set, std::as_bytes(std::span(&push, 1)),
                      vulkan::groupCount(static_cast<uint32_t>(push.end - push.start), kGroupSize));
  }
  vulkan::memoryBarrier(cmd, vulkan::scope::kComputeWrite, vulkan::scope::kAll);

  batch.keepAlive(kernel_);
  table.markUsed(batch.ticket());
  lastTicket_ = std::max(lastTicket_, batch.ticket());
  EvaluatorState& state = evaluatorState(deviceContext_);
  state.lastTicket = std::max(state.lastTicket, batch.ticket());
}

uint64_t VkComputeEvaluator::submit(const VkStencilTable& table, const Binding& src,
                                    const Binding& dst, const Binding& du,
                                    const Binding& dv) const {
  return deviceContext_.submit(
      [&](Batch& batch) { record(batch, table, src, dst, du, dv, 0, table.GetNumStencils()); });
}

void VkComputeEvaluator::Synchronize(DeviceContext* deviceContext) {
  DeviceContext& context = requireContext(deviceContext);
  context.wait(evaluatorState(context).lastTicket);
}

void VkComputeEvaluator::synchronize() const { deviceContext_.wait(lastTicket_); }

std::vector<vulkan::ShaderVariant> evaluatorShaderVariants() {
  return {vulkan::ShaderVariant::file(stencilShader(false)),
          vulkan::ShaderVariant::file(stencilShader(true))};
}

}  // namespace osd_cull::osd
