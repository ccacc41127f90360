#pragma once
/// \file matrix_composer.h
/// \brief Builds the PatchPointMatrix: rows that are linear combinations of patch points,
/// expanded to cage vertices through OpenSubdiv's refinement and local-point stencils.

#include "osd_cull/patch/adaptive_patches.h"
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/point_matrix.h"

#include <cstddef>
#include <vector>

namespace osd_cull {

/// \brief Appends matrix rows patch by patch, then hands over the finished matrix.
///
/// A patch point (Far::PatchTable::GetPatchVertices index) is a refined vertex (one
/// refinement stencil over cage vertices) or a local point (a local-point stencil over
/// refined vertices, composed here with their stencils, as AppendLocalPointStencilTable
/// would). Each row keeps its cage vertices sorted and drops exact zeros.
class MatrixComposer {
 public:
  MatrixComposer(const AdaptivePatches& patches, int cageVertices);

  /// \brief Appends the 16 rows of a Bézier patch: row r = sum over k of
  /// conversion[r][k] * point cvs[k] (cvs: the 16 B-spline points of a REGULAR patch).
  void addBezierPatch(const Far::ConstIndexArray& cvs, const PatchConversion& conversion);

  /// \brief Appends one row per point, the point itself (the 20 points of a GREGORY_BASIS
  /// patch). A point shared with an earlier patch is composed once and its row copied.
  void addPoints(const Far::ConstIndexArray& points);

  /// \brief Number of rows appended so far.
  std::size_t rowCount() const { return sizes_.size(); }

  /// \brief The matrix of all rows appended (the composer is left empty).
  PatchPointMatrix finish();

 private:
  struct Rows {  // a stencil table as arrays, with offsets (Far fills them only on request)
    const int* sizes = nullptr;
    const int* indices = nullptr;
    const double* weights = nullptr;
    std::vector<int> offsets;
    explicit Rows(const Far::StencilTableReal<double>* table);
  };
  struct Emitted {  // where the row of a shared point went
    std::size_t begin = 0;
    int size = -1;
  };

  template <class F>
  void forEachEntry(int point, F&& f) const;
  void collectSupport(const int* points, int count);
  void emitRow(const double* sums);

  Rows refined_;
  Rows local_;
  int refinedCount_;
  int cageVertices_;
  std::vector<uint32_t> stamp_;  // per cage vertex: the block that last used it
  std::vector<int> slot_;        // per cage vertex: its position in support_
  uint32_t block_ = 0;
  std::vector<int> support_;      // sorted cage vertices of the current block
  std::vector<double> expanded_;  // points x support: the block's points over its support
  std::vector<double> sums_;
  std::vector<Emitted> emitted_;  // per patch point, for shared Gregory points
  std::vector<int> sizes_;
  std::vector<int> indices_;
  std::vector<double> weights_;
};

}  // namespace osd_cull
