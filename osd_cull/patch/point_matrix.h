#pragma once
/// \file point_matrix.h
/// \brief The sparse matrix from coarse cage vertices to every patch control point.
///
/// Row r gives control point r of a PatchSet (PatchSet::points order) as a weighted sum
/// of cage vertices. The arrays have the shape of a Far::StencilTable: one stencil per row
/// with `sizes[r]` entries starting at `offsets[r]` in `indices` (cage vertex) and
/// `weights`. A stencil evaluator written for Far::StencilTable (e.g. Osd::CpuEvaluator, or
/// a compute shader reading sizes/offsets/indices/weights) runs it unchanged; the
/// toFarStencilTable() copies are real Far stencil tables for OpenSubdiv's own evaluators.

#include <opensubdiv/far/stencilTable.h>
#include <glm/vec3.hpp>

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull {

/// \brief Compressed-row sparse matrix, cage vertices → patch control points, double weights.
class PatchPointMatrix {
 public:
  PatchPointMatrix() = default;

  /// \brief Takes the rows: `sizes` entries per row, `indices` (column of each entry, in
  /// [0, columnCount)) and `weights`, concatenated row after row. Offsets are derived.
  /// \throws osd_cull::Error if the arrays disagree or an index is out of range.
  PatchPointMatrix(int columnCount, std::vector<int> sizes, std::vector<int> indices,
                   std::vector<double> weights);

  /// \brief Number of rows (patch control points); Far::StencilTable::GetNumStencils().
  int rowCount() const { return static_cast<int>(sizes_.size()); }
  /// \brief Number of columns (cage vertices); Far::StencilTable::GetNumControlVertices().
  int columnCount() const { return columnCount_; }
  /// \brief Number of stored (non-zero) weights.
  std::size_t nonZeroCount() const { return weights_.size(); }

  std::span<const int> sizes() const { return sizes_; }         ///< entries per row
  std::span<const int> offsets() const { return offsets_; }     ///< first entry of each row
  std::span<const int> indices() const { return indices_; }     ///< cage vertex of each entry
  std::span<const double> weights() const { return weights_; }  ///< weight of each entry
  /// \brief The weights rounded to float (for float evaluators and GPU buffers).
  std::span<const float> floatWeights() const { return floatWeights_; }

  /// \brief points[r] = sum of weights * cage[indices] over row r, for all rows.
  /// \throws osd_cull::Error if cage.size() != columnCount() or points.size() != rowCount().
  void update(std::span<const glm::dvec3> cage, std::span<glm::dvec3> points) const;

  /// \brief The same for float xyz arrays (3 floats per vertex/point), e.g. a mapped vertex
  /// buffer, with floatWeights() and float sums, as OpenSubdiv's float stencil evaluation.
  void update(std::span<const float> cageXyz, std::span<float> pointsXyz) const;

  /// \brief A Far::StencilTable (float weights) with the same rows, for Osd evaluators.
  std::unique_ptr<OpenSubdiv::Far::StencilTable> toFarStencilTable() const;
  /// \brief A Far::StencilTableReal<double> with the same rows and exact weights.
  std::unique_ptr<OpenSubdiv::Far::StencilTableReal<double>> toFarStencilTableDouble() const;

 private:
  int columnCount_ = 0;
  std::vector<int> sizes_;
  std::vector<int> offsets_;
  std::vector<int> indices_;
  std::vector<double> weights_;
  std::vector<float> floatWeights_;
};

}  // namespace osd_cull
