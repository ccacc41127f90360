#include "osd_cull/vk/query.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

#include <array>

namespace osd_cull::vulkan {

namespace {

// Bit order defines the order of results (ascending bit value).
constexpr VkQueryPipelineStatisticFlags kStatisticFlags =
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT |                     // 0x1
    VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |                   // 0x4
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |                        // 0x20
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |                         // 0x40
    VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT |                 // 0x80
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT |         // 0x100
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT |  // 0x200
    VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;                   // 0x400
constexpr uint32_t kStatisticCount = 8;

UniqueQueryPool createPool(Context& context, VkQueryType type, uint32_t count,
                           VkQueryPipelineStatisticFlags statistics) {
  if (count == 0) throw Error("vk query pool: count must be positive");
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = type;
  info.queryCount = count;
  info.pipelineStatistics = statistics;
  VkQueryPool pool = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateQueryPool(context.device(), &info, nullptr, &pool));
  return UniqueQueryPool(context.device(), pool);
}

void checkIndex(uint32_t index, uint32_t count, const char* what) {
  if (index >= count)
    throw Error(std::string(what) + ": query index " + std::to_string(index) +
                " out of range (pool holds " + std::to_string(count) + ")");
}

}  // namespace

PipelineStatistics& PipelineStatistics::operator+=(const PipelineStatistics& o) {
  inputAssemblyVertices += o.inputAssemblyVertices;
  vertexShaderInvocations += o.vertexShaderInvocations;
  clippingInvocations += o.clippingInvocations;
  clippingPrimitives += o.clippingPrimitives;
  fragmentShaderInvocations += o.fragmentShaderInvocations;
  tessControlPatches += o.tessControlPatches;
  tessEvaluationInvocations += o.tessEvaluationInvocations;
  computeShaderInvocations += o.computeShaderInvocations;
  return *this;
}

PipelineStatisticsQuery::PipelineStatisticsQuery(Context& context, uint32_t count)
    : device_(context.device()),
      pool_(createPool(context, VK_QUERY_TYPE_PIPELINE_STATISTICS, count, kStatisticFlags)),
      count_(count) {}

void PipelineStatisticsQuery::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_.get(), 0, count_);
}

void PipelineStatisticsQuery::begin(VkCommandBuffer cmd, uint32_t index) {
  checkIndex(index, count_, "PipelineStatisticsQuery::begin");
  vkCmdBeginQuery(cmd, pool_.get(), index, 0);
}

void PipelineStatisticsQuery::end(VkCommandBuffer cmd, uint32_t index) {
  checkIndex(index, count_, "PipelineStatisticsQuery::end");
  vkCmdEndQuery(cmd, pool_.get(), index);
}

namespace {

PipelineStatistics toStatistics(const uint64_t* v) {
  PipelineStatistics s;
  s.inputAssemblyVertices = v[0];
  s.vertexShaderInvocations = v[1];
  s.clippingInvocations = v[2];
  s.clippingPrimitives = v[3];
  s.fragmentShaderInvocations = v[4];
  s.tessControlPatches = v[5];
  s.tessEvaluationInvocations = v[6];
  s.computeShaderInvocations = v[7];
  return s;
}

}  // namespace

PipelineStatistics PipelineStatisticsQuery::result(uint32_t index) const {
  checkIndex(index, count_, "PipelineStatisticsQuery::result");
  std::array<uint64_t, kStatisticCount> v{};
  OSD_CULL_VK(vkGetQueryPoolResults(device_, pool_.get(), index, 1, sizeof(v), v.data(), sizeof(v),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return toStatistics(v.data());
}

std::optional<PipelineStatistics> PipelineStatisticsQuery::tryResult(uint32_t index) const {
  checkIndex(index, count_, "PipelineStatisticsQuery::tryResult");
  // The counters, then the availability word.
  std::array<uint64_t, kStatisticCount + 1> v{};
  const VkResult r =
      vkGetQueryPoolResults(device_, pool_.get(), index, 1, sizeof(v), v.data(), sizeof(v),
                            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
  if (r == VK_NOT_READY || v[kStatisticCount] == 0) return std::nullopt;
  check(r, "vkGetQueryPoolResults (pipeline statistics)");
  return toStatistics(v.data());
}

void PipelineStatisticsQuery::hostReset() { vkResetQueryPool(device_, pool_.get(), 0, count_); }

std::string TimestampQuery::unavailableReason(const Context& context) {
  if (context.info().timestampValidBits == 0)
    return "the queue family of device '" + context.info().name +
           "' has timestampValidBits 0 (timestamps are optional in Vulkan)";
  return {};
}

TimestampQuery::TimestampQuery(Context& context, uint32_t count)
    : device_(context.device()),
      pool_(createPool(context, VK_QUERY_TYPE_TIMESTAMP, count, 0)),
      count_(count),
      periodNs_(context.info().limits.timestampPeriod) {
  const uint32_t bits = context.info().timestampValidBits;
  if (bits == 0) throw Error("TimestampQuery: " + unavailableReason(context));
  mask_ = bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
}

void TimestampQuery::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_.get(), 0, count_);
}

void TimestampQuery::write(VkCommandBuffer cmd, VkPipelineStageFlagBits stage, uint32_t index) {
  checkIndex(index, count_, "TimestampQuery::write");
  vkCmdWriteTimestamp(cmd, stage, pool_.get(), index);
}

void TimestampQuery::hostReset() { vkResetQueryPool(device_, pool_.get(), 0, count_); }

std::optional<uint64_t> TimestampQuery::tryTicks(uint32_t index) const {
  checkIndex(index, count_, "TimestampQuery");
  std::array<uint64_t, 2> v{};  // the timestamp, then the availability word
  const VkResult r =
      vkGetQueryPoolResults(device_, pool_.get(), index, 1, sizeof(v), v.data(), sizeof(v),
                            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
  if (r == VK_NOT_READY || v[1] == 0) return std::nullopt;
  check(r, "vkGetQueryPoolResults (timestamp)");
  return v[0];
}

bool TimestampQuery::available(uint32_t index) const { return tryTicks(index).has_value(); }

std::optional<double> TimestampQuery::tryElapsedMs(uint32_t first, uint32_t second) const {
  const std::optional<uint64_t> a = tryTicks(first), b = tryTicks(second);
  if (!a || !b) return std::nullopt;
  return toMs(*a, *b);
}

double TimestampQuery::toMs(uint64_t first, uint64_t second) const {
  const uint64_t ticks = ((second & mask_) - (first & mask_)) & mask_;
  return static_cast<double>(ticks) * periodNs_ * 1e-6;
}

double TimestampQuery::elapsedMs(uint32_t first, uint32_t second) const {
  checkIndex(first, count_, "TimestampQuery::elapsedMs");
  checkIndex(second, count_, "TimestampQuery::elapsedMs");
  uint64_t a = 0, b = 0;
  OSD_CULL_VK(vkGetQueryPoolResults(device_, pool_.get(), first, 1, sizeof(a), &a, sizeof(a),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  OSD_CULL_VK(vkGetQueryPoolResults(device_, pool_.get(), second, 1, sizeof(b), &b, sizeof(b),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return toMs(a, b);
}

}  // namespace osd_cull::vulkan
