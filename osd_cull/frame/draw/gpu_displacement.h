#pragma once
/// \file gpu_displacement.h
/// \brief A displacement map and the texture coordinates of a patch set on the device:
/// descriptor set 1 of the displaced draw variant (shaders/shared/displacement_layout.h,
/// shaders/patch/displace.glsl).
///
/// Attach it to a GpuPatchSet (GpuPatchSet::setDisplacement) and every draw of that set
/// (final image, item-buffer oracle, debug views, culled draws) draws the displaced
/// surface; sets without one keep the undisplaced pipelines.

#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/handle.h"
#include "osd_cull/vk/image.h"

#include <glm/vec2.hpp>

#include <memory>
#include <span>
#include <vector>

namespace osd_cull::frame {

/// \brief The bindings of descriptor set 1 of displaced draws.
std::span<const vulkan::DescriptorBinding> displacementSetBindings();

/// \brief Device copy of a map (R32_SFLOAT, mip levels 0..maxLod, sampled with repeat
/// addressing, linear filtering and the map's fixed level of detail) and of the texture
/// coordinates of every patch corner.
class GpuDisplacement {
 public:
  /// \brief `map` must outlive this object. `uvCorners`: 4 per patch in PatchSet order
  /// (PatchExtraction::uvCorners). \throws osd_cull::Error when the corner count is not 4 per patch
  /// (naming a mesh without texture coordinates), or the device cannot filter R32_SFLOAT linearly
  /// or holds no image that large (maxImageDimension2D).
  GpuDisplacement(vulkan::Context& context, const bound::DisplacementMap& map,
                  std::span<const glm::dvec2> uvCorners, uint32_t patchCount);
  GpuDisplacement(const GpuDisplacement&) = delete;
  GpuDisplacement& operator=(const GpuDisplacement&) = delete;

  /// \brief Descriptor set 1 of the displaced draw pipelines.
  VkDescriptorSet descriptorSet() const { return set_; }
  const bound::DisplacementMap& map() const { return map_; }
  /// \brief The displacement's variation along every patch edge (edgeDisplacements()), as
  /// the adaptive levels of the draw use it (binding kDisplaceBindingEdges).
  std::span<const EdgeDisplacement> edgeDisplacements() const { return edges_; }

 private:
  const bound::DisplacementMap& map_;
  vulkan::Image image_;
  vulkan::UniqueSampler sampler_;
  vulkan::Buffer uvs_;
  vulkan::Buffer params_;
  std::vector<EdgeDisplacement> edges_;
  vulkan::Buffer edgeBuffer_;
  vulkan::Buffer ranges_;  // (Dmin, Dmax) per patch: the depth clamp (patch.tesc)
  vulkan::UniqueDescriptorSetLayout setLayout_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace osd_cull::frame
