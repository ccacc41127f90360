#include "osd_cull/patch/point_matrix.h"

#include "osd_cull/error.h"

#include <string>

namespace osd_cull {
namespace {

namespace Far = OpenSubdiv::Far;

// Far's stencil tables only have protected constructors taking the arrays; these two
// subclasses expose them. Passing includeCoarseVerts = false and firstOffset = 0 copies
// every row as given.
class FloatStencilTable : public Far::StencilTable {
 public:
  FloatStencilTable(int columns, const std::vector<int>& offsets, const std::vector<int>& sizes,
                    const std::vector<int>& indices, const std::vector<float>& weights)
      : Far::StencilTable(columns, offsets, sizes, indices, weights, false, 0) {}
};

class DoubleStencilTable : public Far::StencilTableReal<double> {
 public:
  DoubleStencilTable(int columns, const std::vector<int>& offsets, const std::vector<int>& sizes,
                     const std::vector<int>& indices, const std::vector<double>& weights)
      : Far::StencilTableReal<double>(columns, offsets, sizes, indices, weights, false, 0) {}
};

}  // namespace

PatchPointMatrix::PatchPointMatrix(int columnCount, std::vector<int> sizes,
                                   std::vector<int> indices, std::vector<double> weights)
    : columnCount_(columnCount),
      sizes_(std::move(sizes)),
      indices_(std::move(indices)),
      weights_(std::move(weights)) {
  if (columnCount_ < 0) throw Error("PatchPointMatrix: negative column count");
  if (indices_.size() != weights_.size())
    throw Error("PatchPointMatrix: " + std::to_string(indices_.size()) + " indices but " +
                std::to_string(weights_.size()) + " weights");
  offsets_.resize(sizes_.size());
  std::size_t offset = 0;
  for (std::size_t r = 0; r < sizes_.size(); ++r) {
    if (sizes_[r] < 0)
      throw Error("PatchPointMatrix: row " + std::to_string(r) + " has a negative size");
    offsets_[r] = static_cast<int>(offset);
    offset += static_cast<std::size_t>(sizes_[r]);
  }
  if (offset != indices_.size())
    throw Error("PatchPointMatrix: row sizes add up to " + std::to_string(offset) +
                ", but there are " + std::to_string(indices_.size()) + " entries");
  for (std::size_t e = 0; e < indices_.size(); ++e)
    if (indices_[e] < 0 || indices_[e] >= columnCount_)
      throw Error("PatchPointMatrix: entry " + std::to_string(e) + " names column " +
                  std::to_string(indices_[e]) + ", out of range [0, " +
                  std::to_string(columnCount_) + ")");
  floatWeights_.assign(weights_.begin(), weights_.end());
}

void PatchPointMatrix::update(std::span<const glm::dvec3> cage,
                              std::span<glm::dvec3> points) const {
  if (cage.size() != static_cast<std::size_t>(columnCount_) || points.size() != sizes_.size())
    throw Error("PatchPointMatrix::update: expected " + std::to_string(columnCount_) +
                " cage vertices and " + std::to_string(sizes_.size()) + " points, got " +
                std::to_string(cage.size()) + " and " + std::to_string(points.size()));
  const int* index = indices_.data();
  const double* weight = weights_.data();
  for (std::size_t r = 0; r < sizes_.size(); ++r) {
    glm::dvec3 sum(0.0);
    for (const int* end = index + sizes_[r]; index != end; ++index, ++weight)
      sum += *weight * cage[*index];
    points[r] = sum;
  }
}

void PatchPointMatrix::update(std::span<const float> cageXyz, std::span<float> pointsXyz) const {
  if (cageXyz.size() != 3 * static_cast<std::size_t>(columnCount_) ||
      pointsXyz.size() != 3 * sizes_.size())
    throw Error("PatchPointMatrix::update: expected " + std::to_string(3 * columnCount_) +
                " cage floats and " + std::to_string(3 * sizes_.size()) + " point floats, got " +
                std::to_string(cageXyz.size()) + " and " + std::to_string(pointsXyz.size()));
  // Float weights and float sums: converting every cage coordinate to double costs ~1.5x
  // here, and the result is stored as float anyway.
  const int* index = indices_.data();
  const float* weight = floatWeights_.data();
  const float* cage = cageXyz.data();
  float* out = pointsXyz.data();
  for (std::size_t r = 0; r < sizes_.size(); ++r) {
    float x = 0.0f, y = 0.0f, z = 0.0f;
    for (const int* end = index + sizes_[r]; index != end; ++index, ++weight) {
      const float* p = cage + 3 * static_cast<std::size_t>(*index);
      x += *weight * p[0];
      y += *weight * p[1];
      z += *weight * p[2];
    }
    out[3 * r + 0] = x;
    out[3 * r + 1] = y;
    out[3 * r + 2] = z;
  }
}

std::unique_ptr<OpenSubdiv::Far::StencilTable> PatchPointMatrix::toFarStencilTable() const {
  return std::make_unique<FloatStencilTable>(columnCount_, offsets_, sizes_, indices_,
                                             floatWeights_);
}

std::unique_ptr<OpenSubdiv::Far::StencilTableReal<double>>
PatchPointMatrix::toFarStencilTableDouble() const {
  return std::make_unique<DoubleStencilTable>(columnCount_, offsets_, sizes_, indices_, weights_);
}

}  // namespace osd_cull
