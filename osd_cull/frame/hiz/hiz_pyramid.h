#pragma once
/// \file hiz_pyramid.h
/// \brief The hierarchical depth pyramid (Hi-Z map, Niessner & Loop §4.1), built in compute
/// from a depth image: every texel holds the farthest depth of its footprint.
///
/// Layout: bound::HiZLayout (sizes padded to powers of two, pixels past the image count as
/// far, level 0 at half resolution as in the paper or at full resolution). The build runs
/// one dispatch per level, either with a min/max-reduction sampler (one filtered fetch per
/// texel, VK_SAMPLER_REDUCTION_MODE_MAX) or with four texel fetches; both give the same
/// values, equal to bound::buildHiZPyramid().

#include "osd_cull/bound/occlusion.h"
#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/image.h"
#include "osd_cull/vk/pipeline.h"

#include <shared/hiz_layout.h>

#include <memory>
#include <vector>

namespace osd_cull::vulkan {
class Context;
class DescriptorPool;
}  // namespace osd_cull::vulkan

namespace osd_cull::frame {

/// \brief How each level is reduced.
enum class HiZReduction {
  Auto,     ///< Sampler when the device supports it for both formats, else FourTap
  Sampler,  ///< min/max sampler reduction (throws when unsupported)
  FourTap,  ///< four texelFetch() and max()
};

/// \brief Options of a HiZPyramid.
struct HiZOptions {
  bool fullResolution = false;  ///< level 0 at the depth image's resolution (paper: half)
  HiZReduction reduction = HiZReduction::Auto;
  /// Level at which the occlusion test looks a box up (params().lookup).
  bound::HiZLookup lookup = bound::HiZLookup::Paper;
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
  /// \brief True when levels 1.. are reduced with the MAX sampler.
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

  bool sampler_ = false;
  bool depthSampler_ = false;
  bound::HiZLookup lookup_ = bound::HiZLookup::Paper;
  bool built_ = false;
  vulkan::Image image_;
  vulkan::UniqueSampler depthMaxSampler_;  // MAX, clamp to border (opaque white = far)
  vulkan::UniqueSampler levelMaxSampler_;  // MAX, clamp to edge
  vulkan::UniqueSampler fetchSampler_;     // nearest, for texelFetch
  std::unique_ptr<vulkan::ComputeProgram> fetchProgram_;
  std::unique_ptr<vulkan::ComputeProgram> samplerProgram_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  std::vector<VkDescriptorSet> sets_;  // one per level
};

}  // namespace osd_cull::frame
