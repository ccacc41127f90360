#pragma once
/// \file query.h
/// \brief Timestamp and pipeline-statistics queries.
///
/// On lavapipe (see shared/PLATFORM.md) pipeline statistics for vertex, tessellation and
/// clipping stages are exact; the fragment-invocation count counts 4x4 blocks run, not
/// fragments. Timestamps (Mesa 22.3.6, 64 valid bits, 1 ns) agree with the wall clock:
/// lavapipe runs the commands of a submission in order and writes a timestamp after the
/// work recorded before it has finished (docs/results/frame-cost.md re-checks it per run).

#include "osd_cull/vk/handle.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::vulkan {

class Context;

/// \brief The counters osd_cull reads from a pipeline-statistics query.
struct PipelineStatistics {
  uint64_t inputAssemblyVertices = 0;
  uint64_t vertexShaderInvocations = 0;
  uint64_t clippingInvocations = 0;
  uint64_t clippingPrimitives = 0;
  uint64_t fragmentShaderInvocations = 0;
  uint64_t tessControlPatches = 0;
  uint64_t tessEvaluationInvocations = 0;
  uint64_t computeShaderInvocations = 0;

  PipelineStatistics& operator+=(const PipelineStatistics& o);
};

/// \brief A pool of pipeline-statistics queries, each counting everything in PipelineStatistics.
class PipelineStatisticsQuery {
 public:
  PipelineStatisticsQuery(Context& context, uint32_t count = 1);
  /// \brief Resets all queries (record outside a render pass, before begin()).
  void reset(VkCommandBuffer cmd);
  void begin(VkCommandBuffer cmd, uint32_t index = 0);
  void end(VkCommandBuffer cmd, uint32_t index = 0);
  /// \brief The counters of query `index`; waits for the result.
  PipelineStatistics result(uint32_t index = 0) const;
  /// \brief The counters of query `index` if the device has written them, without
  /// waiting; std::nullopt while they are not available.
  std::optional<PipelineStatistics> tryResult(uint32_t index = 0) const;
  /// \brief Resets all queries from the host (hostQueryReset, core in Vulkan 1.2): they
  /// read as unavailable at once, before any command buffer runs.
  void hostReset();

 private:
  VkDevice device_;
  UniqueQueryPool pool_;
  uint32_t count_;
};

/// \brief A pool of timestamp queries.
class TimestampQuery {
 public:
  /// \brief Why `context`'s queue cannot write timestamps (its family's timestampValidBits
  /// is 0; timestampComputeAndGraphics is only the promise that every graphics and compute
  /// queue can); empty when it can. Timestamps are optional in Vulkan.
  static std::string unavailableReason(const Context& context);
  /// \throws osd_cull::Error when the queue has no timestamp support.
  TimestampQuery(Context& context, uint32_t count);
  /// \brief Resets all queries (record before any write()).
  void reset(VkCommandBuffer cmd);
  /// \brief Resets all queries from the host (hostQueryReset, core in Vulkan 1.2).
  void hostReset();
  /// \brief True when the device has written timestamp `index` (no wait).
  bool available(uint32_t index) const;
  /// \brief Milliseconds between timestamps `first` and `second` without waiting;
  /// std::nullopt while either is not written yet.
  std::optional<double> tryElapsedMs(uint32_t first, uint32_t second) const;
  /// \brief Writes timestamp `index` when `stage` completes.
  void write(VkCommandBuffer cmd, VkPipelineStageFlagBits stage, uint32_t index);
  /// \brief Milliseconds between timestamps `first` and `second`; waits for the results.
  double elapsedMs(uint32_t first, uint32_t second) const;

 private:
  std::optional<uint64_t> tryTicks(uint32_t index) const;
  double toMs(uint64_t first, uint64_t second) const;

  VkDevice device_;
  UniqueQueryPool pool_;
  uint32_t count_;
  double periodNs_;
  uint64_t mask_;
};

}  // namespace osd_cull::vulkan
