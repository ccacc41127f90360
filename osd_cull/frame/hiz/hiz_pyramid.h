#pragma once
/// \file hiz_pyramid.h
/// \brief The hierarchical depth pyramid (Hi-Z map, Niessner & Loop §4.1), built in compute
/// from a depth image: every texel holds the farthest depth of its footprint.
///
/// Layout: bound::HiZLayout (sizes padded to powers of two, pixels past the image count as
/// far, level 0 at half resolution as in the paper or at full resolution). By default the
/// build is blocked (shaders/hiz/hiz_blocks.comp): three levels per dispatch, each
/// invocation a 4 x 4 block of texels and the 2 x 2 and 1 above it, the top level read from
/// a copy of the depth in an RGBA32F texel buffer (four pixels per fetch), the others with a
/// min/max-reduction sampler (VK_SAMPLER_REDUCTION_MODE_MAX) or four texel fetches: the
/// cheapest on lavapipe (docs/algorithms/occlusion.md, "Building the pyramid on lavapipe").
/// The single-pass build (hiz_single_pass.comp, a single-pass downsampler as AMD FidelityFX
/// SPD: one dispatch, shared memory, the last workgroup builds the top levels) and the
/// per-level build (one dispatch and barrier per level) remain. All give the same values,
/// equal to bound::buildHiZPyramid().

#include "osd_cull/bound/occlusion.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/image.h"
#include "osd_cull/vk/pipeline.h"

#include <osd_cull/shared/hiz_layout.h>

#include <memory>
#include <vector>

namespace osd_cull::vulkan {
class Context;
class DescriptorPool;
}  // namespace osd_cull::vulkan

namespace osd_cull::frame {

/// \brief How each level is reduced.
enum class HiZReduction {
  Auto,        ///< Blocked (fastest on lavapipe)
  Blocked,     ///< three levels per dispatch, 4 x 4 texels per invocation (the default)
  SinglePass,  ///< all levels in one dispatch (texel fetches, shared memory)
  Sampler,     ///< one dispatch per level, min/max sampler reduction (throws when unsupported)
  FourTap,     ///< one dispatch per level, four texelFetch() and max()
};

/// \brief "auto", "blocked", "single", "sampler", "fourtap".
const char* toString(HiZReduction reduction);

/// \brief Options of a HiZPyramid.
struct HiZOptions {
  bool fullResolution = false;  ///< level 0 at the depth image's resolution (paper: half)
  HiZReduction reduction = HiZReduction::Auto;
  /// Level at which the occlusion test looks a box up (params().lookup).
  bound::HiZLookup lookup = bound::HiZLookup::Paper;
  /// For measurements only: the per-level build as it was before the gathered top level and
  /// the skipped padding (every texel written in every build). Same values.
  bool legacyBuild = false;
  /// Blocked build: read the top level from the depth image (one gather or fetch per texel)
  /// rather than from a copy of it. Forced when the depth image lacks TRANSFER_SRC usage or
  /// is not D32_SFLOAT, or the copy exceeds maxTexelBufferElements.
  bool readDepthImage = false;
  /// Blocked build: reduce the levels past the first dispatch's with four texel fetches
  /// even where the MAX sampler exists (as on devices without it).
  bool fourTapLevels = false;
};

/// \brief True when the device can reduce pyramid levels with a MAX sampler: the
/// samplerFilterMinmax feature and MINMAX and LINEAR filtering of R32_SFLOAT.
bool supportsMinmaxReduction(const vulkan::Context& context);
/// \brief True when the depth image (D32_SFLOAT) can be reduced with a MAX sampler too.
/// (Not on lavapipe 22.3, which lacks LINEAR filtering of D32_SFLOAT: there the top level
/// is reduced with four fetches and the others with the sampler.)
bool supportsMinmaxDepthReduction(const vulkan::Context& context);

/// \brief A Hi-Z pyramid over one depth image (e.g. RenderTarget::depth()).
///
/// The pyramid image (R32_SFLOAT, one mip per level) stays in VK_IMAGE_LAYOUT_GENERAL.
/// record() leaves it readable by compute shaders (view() with texelFetch) and transfers.
class HiZPyramid {
 public:
  /// \brief A pyramid for `depth` (a single-sample depth format with SAMPLED usage, e.g.
  /// the application's depth attachment through vulkan::Image::borrow), which must outlive it.
  /// \throws osd_cull::Error when HiZReduction::Sampler is asked for and not supported.
  HiZPyramid(vulkan::Context& context, const vulkan::Image& depth, const HiZOptions& options = {});
  ~HiZPyramid();
  HiZPyramid(const HiZPyramid&) = delete;
  HiZPyramid& operator=(const HiZPyramid&) = delete;

  const bound::HiZLayout& layout() const { return layout_; }
  /// \brief True when all levels are built in one dispatch (HiZReduction::SinglePass).
  bool singlePass() const { return singlePass_; }
  /// \brief True for the blocked build (HiZReduction::Blocked, Auto).
  bool blocked() const { return blocked_; }
  /// \brief True when the blocked build reads the top level from a copy of the depth.
  bool copiesDepth() const { return bool(depthRows_); }
  /// \brief Dispatches per build: 1 with the single pass; blocked one per three levels
  /// until the rest fit the tail, one for the tail (2 at 720p and 1080p); else one per
  /// level.
  uint32_t dispatchCount() const;
  /// \brief True when levels 1.. are reduced with the MAX sampler (per-level and blocked
  /// builds).
  bool usesSampler() const { return sampler_; }
  /// \brief True when level 0 is reduced from the depth image with the MAX sampler.
  bool depthUsesSampler() const { return depthSampler_; }
  const vulkan::Image& image() const { return image_; }
  /// \brief A view of all levels, for texelFetch(sampler2D, p, level).
  VkImageView view() const { return image_.view(); }
  /// \brief A nearest-filter sampler to bind with view() (texelFetch ignores filtering).
  VkSampler fetchSampler() const { return fetchSampler_.get(); }
  /// \brief What the occlusion test needs (shaders/hiz/occlusion.glsl).
  shader::HiZParams params() const;

  /// \brief Records the build. The depth image is in `depthLayout` with its writes made
  /// available by the render pass that wrote it (RenderTarget's passes do), and is returned
  /// to that layout, readable by later fragment tests. Earlier compute and transfer reads
  /// of the pyramid are waited for.
  void record(VkCommandBuffer cmd, VkImageLayout depthLayout);
  /// \brief Records the build, submits it and waits.
  void build(vulkan::Context& context, VkImageLayout depthLayout);
  /// \brief Reads every level back: levels[l][y * levelWidth(l) + x].
  std::vector<std::vector<float>> readLevels(vulkan::Context& context) const;

 private:
  const vulkan::Image& depth_;
  bound::HiZLayout layout_;
  const vulkan::ComputeProgram& programOf(uint32_t level) const;
  void createSinglePass(vulkan::Context& context);
  void recordSinglePass(VkCommandBuffer cmd);
  void createBlocked(vulkan::Context& context, bool readDepthImage);
  void recordBlocked(VkCommandBuffer cmd, VkImageLayout depthLayout);
  void recordPerLevel(VkCommandBuffer cmd);
  /// Texels of `level` a build must write: all the first time, later only those whose
  /// footprint overlaps the depth image.
  VkExtent2D updatedExtent(uint32_t level) const;

  bool singlePass_ = false;
  bool blocked_ = false;
  bool legacy_ = false;
  bool sampler_ = false;
  bool depthSampler_ = false;
  bound::HiZLookup lookup_ = bound::HiZLookup::Paper;
  bool built_ = false;
  vulkan::Image image_;
  vulkan::UniqueSampler depthMaxSampler_;  // clamp to an opaque white border (far): MAX
                                           // filter, or nearest for gathers
  vulkan::UniqueSampler levelMaxSampler_;  // MAX, clamp to edge
  vulkan::UniqueSampler fetchSampler_;     // nearest, for texelFetch
  std::unique_ptr<vulkan::ComputeProgram> fetchProgram_;
  std::unique_ptr<vulkan::ComputeProgram> samplerProgram_;
  std::unique_ptr<vulkan::ComputeProgram> gatherProgram_;  // sampler build, depth level
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  std::vector<VkDescriptorSet> sets_;  // one per level
  std::unique_ptr<vulkan::ComputeProgram> singlePassProgram_;
  vulkan::Buffer counter_;  // workgroups finished (single pass)
  VkDescriptorSet singlePassSet_ = VK_NULL_HANDLE;
  // Blocked build: its dispatches (one set each, in sets_), the programs of the top level,
  // of the other blocked levels and of the tail, and the depth copied as RGBA32F texels
  // (rows of depthRowTexels_), when it is.
  struct BlockDispatch {
    uint32_t firstLevel = 0, levels = 0;
    bool tail = false;  // shaders/hiz/hiz_tail.comp
  };
  std::vector<BlockDispatch> blockDispatches_;
  std::unique_ptr<vulkan::ComputeProgram> topProgram_;
  std::unique_ptr<vulkan::ComputeProgram> blockProgram_;
  std::unique_ptr<vulkan::ComputeProgram> tailProgram_;
  const vulkan::ComputeProgram& blockProgramOf(const BlockDispatch& b) const;
  vulkan::Buffer depthRows_;
  vulkan::DeviceHandle<VkBufferView, vkDestroyBufferView> depthRowsView_;
  uint32_t depthRowTexels_ = 0;
};

}  // namespace osd_cull::frame
