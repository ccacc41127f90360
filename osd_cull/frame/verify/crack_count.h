#pragma once
/// \file crack_count.h
/// \brief Counts the pixels where a closed tessellated surface opens (cracks): used by
/// `render` and `verify` to report the cracks of displaced meshes at UV seams
/// (docs/algorithms/displacement.md, "Tessellation") and by the crack tests.

#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/renderer.h"

#include <cstdint>
#include <span>

namespace osd_cull::frame {

/// \brief Default depth spread of the two sides of a crack (depth buffer units).
inline constexpr float kCrackDepthSpread = 0.01f;
/// \brief The maxWidth `render` and `verify` count seam cracks with (gaps up to 5 pixels:
/// the two sides of a UV seam read different texels and can part by more than a pixel).
inline constexpr uint32_t kSeamCrackWidth = 3;

/// \brief Cracks in a closed surface drawn with back faces culled (`items`, `depth`):
/// background pixels between two covered pixels (the nearest to the left and right, or
/// above and below, each within `maxWidth` pixels: gaps up to 2 maxWidth - 1 pixels
/// wide) whose depths differ by less than `maxDepthSpread`, and that are covered in the
/// same view drawn without culling (`unculledItems`). Through a crack one sees the inside of
/// a closed surface; a gap between two parts of the mesh shows background either way.
uint32_t countCracks(std::span<const uint32_t> items, std::span<const float> depth,
                     std::span<const uint32_t> unculledItems, uint32_t width, uint32_t height,
                     float maxDepthSpread = kCrackDepthSpread, uint32_t maxWidth = 1);

/// \brief Draws `draw` twice into `target` (which needs an item buffer) (back faces culled, then
/// not) with `options` otherwise, and returns countCracks() of the two images (gaps found within
/// `maxWidth` pixels of each side). The target's contents are replaced.
uint32_t countCracks(vulkan::Context& context, Renderer& renderer, RenderTarget& target,
                     const Camera& camera, const PatchDraw& draw, const RenderOptions& options,
                     uint32_t maxWidth = 1);

}  // namespace osd_cull::frame
