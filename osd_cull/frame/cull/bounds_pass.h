#pragma once
/// \file bounds_pass.h
/// \brief The bounds pass: one compute dispatch that recomputes, from the current control
/// points of a GpuPatchSet, the per-patch cull data that depends on them, in the layout of
/// shaders/shared/cull_layout.h (kConeVec4s vec4 per patch). Two kinds of output:
/// - back-patch cull data for CullPass's external-cull-data constructor: the cones of TCONE
///   or NCONE for Bézier patches, the Gregory TCONE for Gregory patches, and the
///   drawn-triangle bound's G, H, max |coordinate| and min |Bu x Bv|; for the tangent-plane
///   methods the Gregory TCONE and G, H (their Bézier test reads only the points);
/// - displaced cull data (Nießner & Loop §4.2): each patch's Dmin/Dmax (static, uploaded
///   once) and the cone of normals of the extension (ACoN: TCONE, CoN: NCONE; Gregory
///   patches the Gregory TCONE; Full: none), in the layout of frame::packDisplacedPatches.
///
/// Conservative: every value bounds its double-precision reference (bound::buildPatchCones,
/// bound::bezierDerivativeBounds, bound::displacementCone) computed from the exact control
/// points, given that the device's points differ from those by at most `pointError` per
/// coordinate: the cone holds every direction the reference's cone is built to hold, G, H
/// and the radius are not smaller, min |N| not larger (docs/algorithms/bounds-pass.md
/// derives the margins).
///
/// Run it after every change of the control points and before the cull that reads them;
/// DynamicPatchMesh does this only for frames whose cage moved.
///
/// Limits: the output (64 bytes per patch) and the ranges (8) are bound as descriptors, the
/// same limit as CullPass's cones; the kernel's working vectors live in shared memory (no
/// per-patch scratch buffer), and the dispatch spreads over x and y past
/// maxComputeWorkGroupCount[0] groups.

#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/displaced_bounds.h"
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
struct BoundsPipeline;

/// \brief One patch's bounds as the pass wrote them, widened to double (tests, reports).
struct PatchBounds {
  bound::ConeOfNormals cone;            ///< valid == false: reason says why it never culls
  bound::DerivativeBounds derivatives;  ///< zero for Gregory patches
};

/// \brief The pipeline and output buffer of the bounds pass for one patch set and one cull
/// method (or displaced extension). The patch set must outlive the pass.
class BoundsPass {
 public:
  /// \brief Back-patch cull data of `method`: TCone or NCone (the Bézier cone), or
  /// TangentPlane (no Bézier cone; G and H). Gregory patches always get the Gregory TCONE.
  /// \throws osd_cull::Error for another method, or an output beyond maxStorageBufferRange.
  BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu, bound::BackPatchMethod method);
  /// \brief Displaced cull data of `extension` (see the file comment); `ranges` holds each
  /// patch's Dmin/Dmax (DisplacementMap::displacementOver of its UV region), one per patch.
  /// \throws osd_cull::Error for a range count other than the patch count, a range that is
  /// not finite or not Dmin <= 0 <= Dmax, or a buffer beyond maxStorageBufferRange.
  BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu, bound::DisplacedExtension extension,
             std::span<const bound::DisplacementRange> ranges);
  ~BoundsPass();
  BoundsPass(const BoundsPass&) = delete;
  BoundsPass& operator=(const BoundsPass&) = delete;

  /// \brief Whether a back-patch method has cull data a BoundsPass can compute (TCone,
  /// NCone, TangentPlane).
  static bool hasCullData(bound::BackPatchMethod method);

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
  /// \brief The back-patch method (None for a displaced pass).
  bound::BackPatchMethod method() const { return method_; }
  /// \brief Whether the output is displaced cull data, and of which extension.
  bool displaced() const { return displaced_; }
  bound::DisplacedExtension extension() const { return extension_; }
  /// \brief False when the output does not depend on the points (displaced Full: only the
  /// static ranges), so a moved cage need not run the pass again.
  bool dependsOnPoints() const;
  /// \brief Dispatches recorded since construction (a static mesh stops adding to it).
  uint64_t dispatchCount() const { return dispatches_; }
  /// \brief The bounds of the last completed pass, read back (waits for the queue).
  /// \throws osd_cull::Error for a displaced pass (readDisplaced()).
  std::vector<PatchBounds> readBounds(vulkan::Context& context) const;
  /// \brief The displaced data of the last completed pass, widened to double.
  /// \throws osd_cull::Error for a back-patch pass (readBounds()).
  std::vector<bound::DisplacedPatch> readDisplaced(vulkan::Context& context) const;

 private:
  BoundsPass(vulkan::Context& context, const GpuPatchSet& gpu, uint32_t coneCode,
             uint32_t outputKind, std::span<const float> ranges);

  vulkan::Context& context_;
  const GpuPatchSet& gpu_;
  bound::BackPatchMethod method_ = bound::BackPatchMethod::None;
  bool displaced_ = false;
  bound::DisplacedExtension extension_ = bound::DisplacedExtension::Full;
  uint32_t coneCode_ = 0;    // kBounds{TCone,NCone,TangentPlane,NoCone}
  uint32_t outputKind_ = 0;  // kBoundsOutput{BackPatch,Displaced}
  vulkan::Buffer cones_;
  vulkan::Buffer ranges_;  // (Dmin, Dmax) float pairs; one unused pair for back-patch data
  std::shared_ptr<const BoundsPipeline> pipeline_;  // shared by the passes of a device
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkBuffer boundPoints_ = VK_NULL_HANDLE;  // the points buffer the set was written with
  uint64_t dispatches_ = 0;
};

/// \brief The cull data of `cones` and `derivatives` (one per patch) widened back to double.
std::vector<PatchBounds> unpackCullData(std::span<const float> data, uint32_t patchCount);

}  // namespace osd_cull::frame
