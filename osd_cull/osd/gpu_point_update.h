#pragma once
/// \file gpu_point_update.h
/// \brief Per-frame update of patch control points on the GPU: new cage positions in,
/// every control point of the patch set out, in a device buffer the cull and draw passes
/// read.
///
/// The cage → control point map is linear (a sparse matrix, osd_cull/patch/point_matrix.h);
/// it is uploaded once as a VkStencilTable and run by VkComputeEvaluator each frame, in
/// one submission with the upload of the cage positions.

#include "osd_cull/osd/compute_evaluator.h"
#include "osd_cull/osd/device_context.h"
#include "osd_cull/osd/stencil_table.h"
#include "osd_cull/osd/vertex_buffer.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull {
class PatchPointMatrix;
}

namespace osd_cull::osd {

/// \brief The matrix on the device plus the buffers of one mesh's per-frame update.
class GpuPointUpdate {
 public:
  /// \brief Layout of the output buffer.
  struct Options {
    /// Floats per control point: 3 (packed xyz) or 4 (xyz1, for std430 vec4 arrays; the
    /// fourth float is set to 1 once).
    int pointStride = 3;
  };

  /// \brief Uploads the matrix (compressed rows: `sizes[r]` entries of row r from
  /// `offsets[r]` in `indices` and `weights`, columns = cage vertices). Double weights
  /// are rounded to float, as OpenSubdiv's float evaluators use them.
  /// \throws osd_cull::Error when the arrays disagree or an index is >= cageVertexCount.
  GpuPointUpdate(DeviceContext& deviceContext, int cageVertexCount, std::span<const int> sizes,
                 std::span<const int> offsets, std::span<const int> indices,
                 std::span<const double> weights, const Options& options);
  GpuPointUpdate(DeviceContext& deviceContext, int cageVertexCount, std::span<const int> sizes,
                 std::span<const int> offsets, std::span<const int> indices,
                 std::span<const double> weights)
      : GpuPointUpdate(deviceContext, cageVertexCount, sizes, offsets, indices, weights,
                       Options{}) {}

  /// \brief Uploads a patch point matrix (rows in PatchSet::points order, see
  /// osd_cull/patch/extract_patches.h).
  GpuPointUpdate(DeviceContext& deviceContext, const PatchPointMatrix& matrix,
                 const Options& options);
  GpuPointUpdate(DeviceContext& deviceContext, const PatchPointMatrix& matrix)
      : GpuPointUpdate(deviceContext, matrix, Options{}) {}

  /// \brief Uploads new cage positions (cageVertexCount() x, y, z floats) and computes
  /// every control point; submitted, not waited for. `cageXyz` may be reused at once.
  /// \returns the submission's ticket (DeviceContext::wait).
  /// \throws osd_cull::Error when the size is not 3 * cageVertexCount().
  uint64_t update(std::span<const float> cageXyz);
  /// \brief The same from double positions (rounded to float).
  uint64_t update(std::span<const glm::dvec3> cage);
  /// \brief Computes every control point from positions already on the device: vertex i
  /// of `source` (x, y, z floats at source.desc.offset + i * source.desc.stride, length 3)
  /// is matrix column i. For an adaptive Osd::Mesh's vertex buffer after Refine() use the
  /// ApplicationPatches::fromPatchPoints matrix; for the application's own buffer of cage
  /// positions the cage matrix. Submitted, not waited for, ordered after earlier work on
  /// the queue (a buffer another queue writes needs the application's semaphore first).
  /// \returns the submission's ticket.
  /// \throws osd_cull::Error when the source holds fewer vertices than the matrix reads or
  /// its descriptor is not 3 floats per vertex.
  uint64_t updateFrom(const EvaluatorBinding& source);
  /// \brief updateFrom() an Osd vertex buffer (e.g. `*mesh.GetVertexBuffer()` of a VkMesh),
  /// positions at float `firstElement` of each vertex.
  uint64_t updateFrom(const VkVertexBuffer& source, int firstElement = 0);
  /// \brief Waits for the latest update.
  void wait() const;

  int cageVertexCount() const { return cage_.GetNumVertices(); }
  int pointCount() const { return points_.GetNumVertices(); }
  int pointStride() const { return points_.GetNumElements(); }
  /// \brief The control points (pointCount() x pointStride() floats). Updates are ordered
  /// before later submissions on the queue; a reader needs no extra barrier.
  const vulkan::Buffer& points() const { return points_.buffer(); }
  /// \brief The points read back as pointCount() x pointStride() floats (waits).
  std::vector<float> readback() const { return points_.readback(); }

 private:
  DeviceContext& deviceContext_;
  VkStencilTable matrix_;
  VkVertexBuffer cage_;
  VkVertexBuffer points_;
  VkComputeEvaluator evaluator_;
  std::vector<float> scratch_;  // double → float conversion of update(dvec3)
  uint64_t lastTicket_ = 0;
};

}  // namespace osd_cull::osd
