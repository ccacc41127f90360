#pragma once
/// \file gpu_patch_set.h
/// \brief A PatchSet's control points, PatchParams and draw list in device buffers.

#include "osd_cull/patch/patch_set.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>

namespace osd_cull::vk {
class Context;
}

namespace osd_cull::frame {

/// \brief Device copy of a PatchSet, in the layout the draw and cull shaders read
/// (shaders/shared/draw_layout.h):
/// - points(): float array, control point i at floats [pointOffset() + i*pointStride(), +3)
///   (stride 4 here: x, y, z, 1); PatchSet point order. An evaluator (e.g. GPU stencils)
///   may write this buffer directly.
/// - params(): two uints per patch, Far::PatchParam field0 and field1.
/// - drawList(): patch indices, all Bézier patches then all Gregory (identity order); a
///   draw of slots [first, first + n) draws drawList[first .. first + n).
class GpuPatchSet {
 public:
  GpuPatchSet(vk::Context& context, const PatchSet& patches);

  /// \brief Replaces all control points (same count and layout), e.g. after animation.
  /// \throws osd_cull::Error when the count differs.
  void updatePoints(vk::Context& context, std::span<const glm::dvec3> points);

  uint32_t bezierCount() const { return bezierCount_; }
  uint32_t gregoryCount() const { return gregoryCount_; }
  uint32_t patchCount() const { return bezierCount_ + gregoryCount_; }
  uint32_t pointCount() const { return pointCount_; }
  uint32_t pointStride() const { return 4; }
  uint32_t pointOffset() const { return 0; }
  /// \brief Draw-list slot of the first Gregory patch (== bezierCount()).
  uint32_t firstGregorySlot() const { return bezierCount_; }

  const vk::Buffer& points() const { return points_; }
  const vk::Buffer& params() const { return params_; }
  const vk::Buffer& drawList() const { return drawList_; }
  /// \brief A descriptor set with points, params and draw list at the bindings of
  /// patchSetBindings() (shaders/shared/draw_layout.h kBinding*).
  VkDescriptorSet descriptorSet() const { return set_; }
  /// \brief A descriptor set like descriptorSet() but reading the draw list from
  /// `drawList` (e.g. survivors a cull pass appended). Up to kMaxDrawListSets per set;
  /// `drawList` must outlive every draw that uses the returned set.
  /// \throws osd_cull::Error when the sets are used up.
  VkDescriptorSet descriptorSetWithDrawList(vk::Context& context, const vk::Buffer& drawList);
  static constexpr uint32_t kMaxDrawListSets = 63;

 private:
  uint32_t bezierCount_ = 0;
  uint32_t gregoryCount_ = 0;
  uint32_t pointCount_ = 0;
  vk::Buffer points_;
  vk::Buffer params_;
  vk::Buffer drawList_;
  vk::UniqueDescriptorSetLayout setLayout_;
  std::unique_ptr<vk::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  uint32_t extraSets_ = 0;
};

/// \brief The descriptor bindings of a patch set (points, params, draw list), visible
/// to every stage.
std::span<const vk::DescriptorBinding> patchSetBindings();

/// \brief Packs points as float x, y, z, 1 (the points() layout).
std::vector<float> packPoints(std::span<const glm::dvec3> points);

}  // namespace osd_cull::frame
