#pragma once
/// \file gpu_patch_set.h
/// \brief A PatchSet's control points, PatchParams and draw list in device buffers.

#include "osd_cull/patch/patch_set.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <utility>
#include <vector>
#include <memory>
#include <span>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::frame {

class GpuDisplacement;

/// \brief Device copy of a PatchSet, in the layout the draw and cull shaders read
/// (shaders/shared/draw_layout.h):
/// - points(): float array, control point i at floats [pointOffset() + i*pointStride(), +3)
///   (stride kOwnPointStride = 3 for the set's own buffer: x, y, z, 12 bytes a point, 192 a
///   Bézier patch); PatchSet point order. An evaluator
///   may write this buffer directly, or readPointsFrom() makes the set read another buffer
///   (e.g. osd::GpuPointUpdate::points(), stride 3 or 4).
/// - params(): two uints per patch, Far::PatchParam field0 and field1.
/// - drawList(): patch indices, all Bézier patches then all Gregory (identity order); a
///   draw of slots [first, first + n) draws drawList[first .. first + n).
///
/// Shaders read points with controlPoint() (shaders/common/control_points.glsl). On a device
/// with bufferDeviceAddress the points binding holds a PointSource record with the points'
/// address (pointBinding()), so points() may be larger than maxStorageBufferRange (more
/// than 524,288 Bézier patches on lavapipe); without it the binding holds points() itself
/// and a larger buffer is an error that names both.
class GpuPatchSet {
 public:
  /// \throws osd_cull::Error when the PatchSet is inconsistent or a buffer exceeds a device
  /// limit (named) that no address path lifts.
  GpuPatchSet(vulkan::Context& context, const PatchSet& patches);
  GpuPatchSet(const GpuPatchSet&) = delete;
  GpuPatchSet& operator=(const GpuPatchSet&) = delete;

  /// \brief Replaces all control points (same count and layout), e.g. after animation.
  /// \throws osd_cull::Error when the count differs or readPointsFrom() is in effect.
  void updatePoints(vulkan::Context& context, std::span<const glm::dvec3> points);

  uint32_t bezierCount() const { return bezierCount_; }
  uint32_t gregoryCount() const { return gregoryCount_; }
  uint32_t patchCount() const { return bezierCount_ + gregoryCount_; }
  uint32_t pointCount() const { return pointCount_; }
  /// \brief Whether any patch has a transition edge (see effectiveOptions()).
  bool hasTransitionEdges() const { return transitionEdges_; }
  /// \brief Makes every draw read control points from `points` (borrowed: it must outlive
  /// the set's use) with `stride` floats per point from float `offset` on, instead of the
  /// set's own buffer. Call between frames (not while a draw using the set is pending).
  /// \throws osd_cull::Error when stride < 3, the buffer is too small for pointCount(), or
  /// (without bufferDeviceAddress) it exceeds maxStorageBufferRange.
  void readPointsFrom(vulkan::Context& context, const vulkan::Buffer& points, uint32_t stride,
                      uint32_t offset = 0);
  uint32_t pointStride() const { return pointStride_; }
  uint32_t pointOffset() const { return pointOffset_; }
  /// \brief Draws of this set displace the surface with `displacement` (borrowed: it must
  /// outlive the set's use; nullptr: undisplaced, the default). Call between frames.
  void setDisplacement(const GpuDisplacement* displacement) { displacement_ = displacement; }
  const GpuDisplacement* displacement() const { return displacement_; }
  /// \brief Draw-list slot of the first Gregory patch (== bezierCount()).
  uint32_t firstGregorySlot() const { return bezierCount_; }

  /// \brief The buffer draws read control points from (the set's own, or readPointsFrom's).
  const vulkan::Buffer& points() const { return *pointSource_; }
  /// \brief Whether shaders read the points through a device address (the variant define
  /// OSD_CULL_POINTS_BDA of every shader that includes control_points.glsl).
  bool pointsByAddress() const { return pointsByAddress_; }
  /// \brief What the points binding holds: the PointSource record (pointsByAddress()) or
  /// points(). A set bound to it follows readPointsFrom().
  const vulkan::Buffer& pointBinding() const {
    return pointsByAddress_ ? pointRecord_ : *pointSource_;
  }
  const vulkan::Buffer& params() const { return params_; }
  const vulkan::Buffer& drawList() const { return drawList_; }
  /// \brief A descriptor set with points, params and draw list at the bindings of
  /// patchSetBindings() (shaders/shared/draw_layout.h kBinding*).
  VkDescriptorSet descriptorSet() const { return set_; }
  /// \brief A descriptor set like descriptorSet() but reading the draw list from
  /// `drawList` (e.g. survivors a cull pass appended). Up to kMaxDrawListSets at a time;
  /// `drawList` must outlive every draw that uses the returned set, and the set is given
  /// back with releaseDrawListSet() before `drawList` goes (CullPass does, when destroyed).
  /// \throws osd_cull::Error when the sets are used up.
  VkDescriptorSet descriptorSetWithDrawList(vulkan::Context& context,
                                            const vulkan::Buffer& drawList);
  /// \brief Returns a set of descriptorSetWithDrawList() (no command buffer that uses it
  /// may still run); a set this patch set did not make is ignored.
  void releaseDrawListSet(VkDescriptorSet set);
  static constexpr uint32_t kMaxDrawListSets = 15;
  /// \brief Adaptive levels of every patch, `tessLevelSlots()` views (instances) of them:
  /// slot s, patch p at uvec2 entry s * patchCount() + p (shaders/shared/draw_layout.h
  /// kBindingTessLevels; written by TessLevelsPass, read by draws with
  /// PatchDraw::tessLevelSlot and by the cull kernel).
  const vulkan::Buffer& tessLevels() const { return tessLevels_; }
  uint32_t tessLevelSlots() const { return tessLevelSlots_; }
  /// \brief Grows tessLevels() to at least `slots` slots (one when constructed) and
  /// rewrites the descriptor sets the set made; a set written by writeDescriptorSet() before
  /// must be written again. Call between frames.
  void reserveTessLevelSlots(vulkan::Context& context, uint32_t slots);
  /// \brief Floats per point in the set's own buffer (x, y, z).
  static constexpr uint32_t kOwnPointStride = 3;
  /// \brief Writes points (the current source, see readPointsFrom()), params, `drawList` and
  /// tessLevels()
  /// into `set`, a set the caller allocated with a layout of patchSetBindings() (for
  /// callers that own their sets and pools).
  void writeDescriptorSet(VkDevice device, VkDescriptorSet set,
                          const vulkan::Buffer& drawList) const;

 private:
  void writePointRecord();

  uint32_t bezierCount_ = 0;
  uint32_t gregoryCount_ = 0;
  uint32_t pointCount_ = 0;
  bool transitionEdges_ = false;
  vulkan::Buffer points_;
  const vulkan::Buffer* pointSource_ = &points_;
  bool pointsByAddress_ = false;
  vulkan::Buffer pointRecord_;  // shader::PointSource, host-written
  uint32_t pointStride_ = kOwnPointStride;
  uint32_t pointOffset_ = 0;
  vulkan::Buffer params_;
  vulkan::Buffer drawList_;
  vulkan::UniqueDescriptorSetLayout setLayout_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  uint32_t extraSets_ = 0;
  std::vector<std::pair<VkDescriptorSet, const vulkan::Buffer*>> extraSetLists_;
  vulkan::Buffer tessLevels_;
  uint32_t tessLevelSlots_ = 0;
  const GpuDisplacement* displacement_ = nullptr;
};

/// \brief The descriptor bindings of a patch set (points, params, draw list, levels), visible
/// to every stage.
std::span<const vulkan::DescriptorBinding> patchSetBindings();

/// \brief The value of the OSD_CULL_POINTS_BDA define for shaders that read points on this
/// context ("1" with bufferDeviceAddress, else "0"); matches GpuPatchSet::pointsByAddress().
const char* pointsByAddressDefine(const vulkan::Context& context);

/// \brief Packs points as float x, y, z, 1 (a vec4 vertex layout, e.g. triangle meshes).
std::vector<float> packPoints(std::span<const glm::dvec3> points);

}  // namespace osd_cull::frame
