#pragma once
/// \file bounds_pass.h
/// \brief The bounds pass: one compute dispatch that recomputes, from the current control
/// points of a GpuPatchSet, the per-patch cull data the cone back-patch methods read (cones
/// of TCONE or NCONE for Bézier patches, the Gregory TCONE for Gregory patches, and the
/// drawn-triangle bound's G, H, max |coordinate| and min |Bu x Bv|), in the layout of
/// shaders/shared/cull_layout.h (kConeVec4s vec4 per patch). A CullPass made with
/// cullData() reads it (CullPass's external-cull-data constructor).
///
/// Conservative: every value bounds its double-precision reference (bound::buildPatchCones,
/// bound::bezierDerivativeBounds) computed from the exact control points, given that the
/// device's points differ from those by at most `pointError` per coordinate: the cone holds
/// every direction the reference's cone is built to hold, G, H and the radius are not
/// smaller, min |N| not larger (docs/algorithms/bounds-pass.md derives the margins).
///
/// Run it after every change of the control points and before the cull that reads them;
/// DynamicPatchMesh does this only for frames whose cage moved.

#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/handle.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::frame {

class GpuPatchSet;

/// \brief One patch's bounds as the pass wrote them, widened to double (tests, reports).
struct PatchBounds {
  bound::ConeOfNormals cone;            ///< valid == false: reason says why it never culls
  bound::DerivativeBounds derivatives;  ///< zero for Gregory patches
};

/// \brief The pipeline and output buffer of the bounds pass for one patch set and one cone
/// method. The patch set must outlive the pass.
class BoundsPass {
 public:
  /// \brief `method` selects the Bézier cone: TCone or NCone (Gregory patches always get
  /// the Gregory TCONE).
  /// \throws osd_cull::Error for another method.
  BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu, bound::BackPatchMethod method);
  ~BoundsPass();
  BoundsPass(const BoundsPass&) = delete;
  BoundsPass& operator=(const BoundsPass&) = delete;

  /// \brief Records the dispatch, with barriers from earlier writers of the points (transfer
  /// or compute, in this or an earlier submission) and to later compute readers.
  /// `pointError` as in the file comment (pointErrorBound()). `shrink` > 0 only in tests:
  /// it makes every bound tighter by that much, which the conservativeness test must catch.
  /// \throws osd_cull::Error for a negative or non-finite pointError.
  void record(VkCommandBuffer cmd, double pointError, float shrink = 0.0f);
  /// \brief record() in its own submission; waits and returns the wall time in ms.
  double run(double pointError, float shrink = 0.0f);

  /// \brief The cull data (kConeVec4s vec4 per patch) for CullPass.
  const vulkan::Buffer& cullData() const { return cones_; }
  bound::BackPatchMethod method() const { return method_; }
  /// \brief Dispatches recorded since construction (a static mesh stops adding to it).
  uint64_t dispatchCount() const { return dispatches_; }
  /// \brief The bounds of the last completed pass, read back (waits for the queue).
  std::vector<PatchBounds> readBounds(vulkan::Context& context) const;

 private:
  vulkan::Context& context_;
  const GpuPatchSet& gpu_;
  bound::BackPatchMethod method_;
  vulkan::Buffer cones_;
  vulkan::Buffer scratch_;  // kMaxVectors vec4 per patch, the kernel's working vectors
  vulkan::UniqueDescriptorSetLayout setLayout_;
  vulkan::UniquePipelineLayout layout_;
  vulkan::UniquePipeline pipeline_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkBuffer boundPoints_ = VK_NULL_HANDLE;  // the points buffer the set was written with
  uint64_t dispatches_ = 0;
};

/// \brief The cull data of `cones` and `derivatives` (one per patch) widened back to double.
std::vector<PatchBounds> unpackCullData(std::span<const float> data, uint32_t patchCount);

}  // namespace osd_cull::frame
