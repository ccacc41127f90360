#pragma once
/// \file dynamic_patch_mesh.h
/// \brief A patch mesh whose cage moves: the per-frame cage input of an animated mesh.
///
/// DynamicPatchMesh owns the host cage, the patch set (host copy and GpuPatchSet), the
/// cage → control point update and the bounds passes of the cone methods:
///
///   DynamicPatchMesh mesh(context, cage, {}, PointUpdatePath::Gpu);
///   CullPass pass(context, mesh.gpu(), mesh.patches(), settings,
///                 mesh.cullData(bound::BackPatchMethod::TCone));
///   each frame:
///     mesh.setCagePositions(positions);      // all vertices, or a range (start, count)
///     mesh.update();                         // only if the cage moved: points, bounds
///     ... cull and draw as for a static mesh (CullPass, CullFrame) ...
///
/// setCagePositions() is OpenSubdiv's UpdateVertexBuffer(src, start, count) for the cage
/// (double or float xyz). update() then recomputes the control points through the patch
/// point matrix (osd_cull/patch/point_matrix.h), on the CPU in double (uploaded as float) or
/// on the GPU with the Vulkan stencil evaluator (osd/gpu_point_update.h, float), as
/// PointUpdatePath says, and runs the bounds pass of every back-patch method and displaced
/// extension in use (frame/cull/bounds_pass.h) in one submission. A frame whose cage did
/// not move runs nothing (counters() proves it). Temporal visibility (CullFrame) needs
/// nothing else: the two-pass frame simply re-tests the moved patches.
///
/// Every back-patch method has per-frame cull data (cullData(): tcone, ncone and, for their
/// Gregory patches, the tangent-plane methods; BoundsPass::hasCullData), and so has every
/// displaced kernel (displacedCullData(): the cones of ACoN and CoN, Nießner & Loop §4.2,
/// next to the static Dmin/Dmax of the map), so a deforming mesh can be culled with any of
/// them:
///
///   CullSettings s;  s.displacementMap = &map;  s.uvCorners = uvCorners;
///   s.occlusion = "con-caf";  // or displacedKernel = {CoN, CAF} with another occlusion
///   CullPass pass(context, mesh.gpu(), mesh.patches(), s,
///                 mesh.displacedCullData(map, uvCorners, bound::DisplacedExtension::CoN));

#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/patch/extract_patches.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}
namespace osd_cull::osd {
class DeviceContext;
class GpuPointUpdate;
}  // namespace osd_cull::osd

namespace osd_cull::frame {

/// \brief Where control points are recomputed from the cage.
enum class PointUpdatePath {
  Cpu,  ///< PatchPointMatrix::update in double, uploaded as float
  Gpu,  ///< osd::GpuPointUpdate (float stencils in a compute shader), no host copy per frame
};

/// \brief "cpu", "gpu".
const char* toString(PointUpdatePath path);

/// \brief Work counters of a DynamicPatchMesh (a static mesh stops adding to them).
struct DynamicMeshCounters {
  uint64_t pointUpdates = 0;      ///< control point recomputations
  uint64_t boundsDispatches = 0;  ///< bounds pass dispatches, all methods and extensions
};

/// \brief Wall time of the last update() that ran, in ms.
struct DynamicMeshTimes {
  double pointsMs = 0.0;  ///< cage → control points (and their upload)
  double boundsMs = 0.0;  ///< the bounds passes (one submission, waited for)
};

/// \brief See the file comment.
class DynamicPatchMesh {
 public:
  /// \brief Takes the patches and matrix of `extraction` and the cage positions they were
  /// extracted from (`cage.size()` == extraction.matrix.columnCount()).
  /// \throws osd_cull::Error for a size mismatch or NaN/Inf positions.
  DynamicPatchMesh(vulkan::Context& context, PatchExtraction extraction,
                   std::span<const glm::dvec3> cage, PointUpdatePath path = PointUpdatePath::Cpu);
  /// \brief Extracts the patches of `cage` (osd_cull::extractPatches) first.
  DynamicPatchMesh(vulkan::Context& context, const CageMesh& cage, const PatchOptions& options = {},
                   PointUpdatePath path = PointUpdatePath::Cpu);
  ~DynamicPatchMesh();
  DynamicPatchMesh(const DynamicPatchMesh&) = delete;
  DynamicPatchMesh& operator=(const DynamicPatchMesh&) = delete;

  /// \brief Sets cage vertices [start, start + positions.size()) for the next update().
  /// \throws osd_cull::Error naming the range or the first NaN/Inf vertex (nothing is
  /// changed then).
  void setCagePositions(std::span<const glm::dvec3> positions, int start = 0);
  /// \brief The same from packed float xyz (3 floats per vertex).
  void setCagePositions(std::span<const float> xyz, int start = 0);
  /// \brief Whether setCagePositions() was called since the last update().
  bool cageMoved() const { return moved_; }
  std::span<const glm::dvec3> cage() const { return cage_; }
  int cageVertexCount() const { return static_cast<int>(cage_.size()); }

  /// \brief When the cage moved: recomputes the control points and runs the bounds passes;
  /// waits for both. Otherwise nothing. Returns whether it ran.
  bool update();

  /// \brief The cull data of a back-patch method (TCone, NCone, TangentPlane) for
  /// CullPass, recomputed by every update() that runs. The first call for a method makes its
  /// bounds pass and runs it once.
  /// \throws osd_cull::Error for a method without cull data (see BoundsPass::hasCullData).
  const vulkan::Buffer& cullData(bound::BackPatchMethod method);
  /// \brief The bounds pass of `method`, nullptr before cullData(method).
  const BoundsPass* boundsPass(bound::BackPatchMethod method) const;

  /// \brief The displaced cull data of `extension` for a CullPass whose settings give the
  /// same `map` and `uvCorners` (PatchExtraction::uvCorners of this mesh, 4 per patch) and
  /// a displaced kernel of this extension. Dmin/Dmax are computed once (they do not move
  /// with the cage); the cones (ACoN, CoN) are recomputed by every update() that runs (Full
  /// has none and is not rerun). The first call for an extension makes its bounds pass and
  /// runs it once; `map` is borrowed only for that call, and later calls for the extension
  /// return the data of the first call's map and UVs.
  /// \throws osd_cull::Error for no or the wrong number of UV corners.
  const vulkan::Buffer& displacedCullData(const bound::DisplacementMap& map,
                                          std::span<const glm::dvec2> uvCorners,
                                          bound::DisplacedExtension extension);
  /// \brief The displaced bounds pass of `extension`, nullptr before displacedCullData().
  const BoundsPass* displacedBoundsPass(bound::DisplacedExtension extension) const;

  GpuPatchSet& gpu() { return *gpu_; }
  /// \brief The host patch set with the current control points in double (computed from the
  /// cage on demand with the GPU path). CullPass and the references read it.
  const PatchSet& patches();
  const PatchPointMatrix& matrix() const { return matrix_; }
  PointUpdatePath path() const { return path_; }
  /// \brief A bound of |device coordinate - exact coordinate| of the current control points
  /// (float rounding; with the GPU path also the float stencil sums): the bounds pass's
  /// pointError.
  double pointError() const { return pointError_; }
  DynamicMeshCounters counters() const;
  const DynamicMeshTimes& lastTimes() const { return times_; }

 private:
  void updatePoints();

  vulkan::Context& context_;
  PointUpdatePath path_;
  PatchSet host_;
  PatchPointMatrix matrix_;
  std::vector<glm::dvec3> cage_;
  std::unique_ptr<GpuPatchSet> gpu_;
  std::unique_ptr<osd::DeviceContext> device_;      // GPU path
  std::unique_ptr<osd::GpuPointUpdate> gpuUpdate_;  // GPU path
  double stencilErrorFactor_ = 0.0;                 // max over rows of (entries + 2) sum |w|
  std::map<bound::BackPatchMethod, std::unique_ptr<BoundsPass>> bounds_;
  std::map<bound::DisplacedExtension, std::unique_ptr<BoundsPass>> displacedBounds_;
  bool moved_ = false;
  bool hostStale_ = false;
  double pointError_ = 0.0;
  uint64_t pointUpdates_ = 0;
  DynamicMeshTimes times_;
};

}  // namespace osd_cull::frame
