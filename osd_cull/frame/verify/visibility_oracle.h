#pragma once
/// \file visibility_oracle.h
/// \brief Pixel-exact per-patch visibility: the item buffer of Engelhardt & Dachsbacher,
/// "Granular Visibility Queries on the GPU" (section 3.2, hierarchical item buffer).
///
/// Every patch is drawn with its ID into an R32_UINT target with depth testing (triangle
/// occluders write their own value); a compute pass counts pixels per ID and per
/// (ID, screen tile) for a 2^t x 2^t tiling. A patch with zero pixels is invisible at that
/// tessellation: the ground truth every cull method is checked against.

#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/pipeline.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull::frame {

/// \brief Visible pixels of each patch in one view.
struct VisibilityCounts {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t tileLog2 = 0;
  std::vector<uint32_t> pixels;      ///< per patch
  std::vector<uint32_t> tilePixels;  ///< per patch and tile: [patch * tiles() + ty * side + tx]
  uint32_t backgroundPixels = 0;
  uint32_t occluderPixels = 0;
  uint32_t unknownPixels = 0;  ///< item values beyond the patch count (another set's IDs)

  uint32_t patchCount() const { return static_cast<uint32_t>(pixels.size()); }
  /// \brief Tiles per side (2^tileLog2).
  uint32_t tilesPerSide() const { return 1u << tileLog2; }
  uint32_t tiles() const { return tilesPerSide() * tilesPerSide(); }
  /// \brief Tile size in pixels (the last row and column of tiles may be cut by the image).
  uint32_t tileWidth() const { return (width + tilesPerSide() - 1) / tilesPerSide(); }
  uint32_t tileHeight() const { return (height + tilesPerSide() - 1) / tilesPerSide(); }
  /// \brief Visible pixels of `patch` in tile (tx, ty).
  uint32_t tile(uint32_t patch, uint32_t tx, uint32_t ty) const {
    return tilePixels[size_t{patch} * tiles() + ty * tilesPerSide() + tx];
  }
  bool visible(uint32_t patch) const { return pixels[patch] > 0; }
  uint32_t visiblePatchCount() const;
};

/// \brief Runs the item-buffer count (and the draws that fill it).
class VisibilityOracle {
 public:
  /// \brief tileLog2 up to 8 (256 x 256 tiles).
  static constexpr uint32_t kMaxTileLog2 = 8;

  explicit VisibilityOracle(vulkan::Context& context);

  /// \brief Counts the item buffer currently in `target` (drawn by a Renderer) for item
  /// values 1..patchCount.
  VisibilityCounts count(const RenderTarget& target, uint32_t patchCount, uint32_t tileLog2 = 0);

  /// \brief Draws occluders and `patches` (item values = patch + 1) into `target` with
  /// depth testing, then counts. `host` (optional) splits draws by per-patch levels.
  /// `cullBackFaces` draws as a renderer that culls back-facing triangles does.
  VisibilityCounts query(Renderer& renderer, RenderTarget& target, const Camera& camera,
                         const GpuPatchSet& patches, const PatchSet* host,
                         std::span<const GpuTriangleMesh* const> occluders,
                         const TessellationOptions& tessellation, uint32_t tileLog2 = 0,
                         bool cullBackFaces = false);

 private:
  vulkan::Context& context_;
  std::unique_ptr<vulkan::ComputeProgram> program_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
};

}  // namespace osd_cull::frame
