#pragma once
/// \file draw_chunks.h
/// \brief Splitting patch draws so that no rasterizer batch overflows.
///
/// Mesa lavapipe 22.3 (shared/PLATFORM.md) splits a draw into batches of 4096 control
/// points and wraps tessellated vertices beyond 65,535 within a batch: whole runs of
/// patches vanish. A draw is therefore split so that any run of consecutive patches that
/// can share a batch stays within the vertex limit. The rule costs nothing on other
/// devices (a few more draw calls at high levels).

#include <cstdint>
#include <span>
#include <vector>

namespace osd_cull::frame {

/// \brief A range of draw slots drawn with one vkCmdDraw.
struct DrawChunk {
  uint32_t first = 0;  ///< first slot (index into the draw list)
  uint32_t count = 0;  ///< patches
};

/// \brief Limits of the rasterizer's internal batches.
struct BatchLimits {
  uint32_t controlPointsPerBatch = 4096;
  uint32_t verticesPerBatch = 65535;
};

/// \brief Splits slots [0, vertexBounds.size()) into consecutive draws such that every
/// window of ceil(controlPointsPerBatch / controlPoints) consecutive patches within a draw
/// has at most verticesPerBatch tessellated vertices (by the given per-patch bounds).
std::vector<DrawChunk> planDrawChunks(std::span<const uint32_t> vertexBounds,
                                      uint32_t controlPoints, const BatchLimits& limits = {});

}  // namespace osd_cull::frame
