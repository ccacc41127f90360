#include "osd_cull/frame/draw/draw_chunks.h"

#include "osd_cull/error.h"

#include <deque>

namespace osd_cull::frame {

std::vector<DrawChunk> planDrawChunks(std::span<const uint32_t> vertexBounds,
                                      uint32_t controlPoints, const BatchLimits& limits) {
  if (controlPoints == 0 || limits.controlPointsPerBatch == 0)
    throw Error("planDrawChunks: control points per patch and per batch must be positive");
  const size_t window = (limits.controlPointsPerBatch + controlPoints - 1) / controlPoints;
  std::vector<DrawChunk> chunks;
  std::deque<uint64_t> recent;  // bounds of the last (window - 1) patches of the current draw
  uint64_t recentSum = 0;
  for (uint32_t slot = 0; slot < vertexBounds.size(); ++slot) {
    const uint64_t b = vertexBounds[slot];
    if (chunks.empty() || recentSum + b > limits.verticesPerBatch) {
      chunks.push_back({slot, 0});
      recent.clear();
      recentSum = 0;
    }
    ++chunks.back().count;
    recent.push_back(b);
    recentSum += b;
    if (recent.size() >= window) {
      recentSum -= recent.front();
      recent.pop_front();
    }
  }
  return chunks;
}

}  // namespace osd_cull::frame
