#include "osd_cull/patch/matrix_composer.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <string>

namespace osd_cull {

MatrixComposer::Rows::Rows(const Far::StencilTableReal<double>* table) {
  if (!table) return;
  sizes = table->GetSizes().data();
  indices = table->GetControlIndices().data();
  weights = table->GetWeights().data();
  offsets.resize(table->GetSizes().size());
  int offset = 0;
  for (std::size_t r = 0; r < offsets.size(); ++r) {
    offsets[r] = offset;
    offset += sizes[r];
  }
}

MatrixComposer::MatrixComposer(const AdaptivePatches& patches, int cageVertices)
    : refined_(patches.refinedStencils.get()),
      local_(patches.localPointStencils),
      refinedCount_(patches.refinedVertexCount),
      cageVertices_(cageVertices),
      stamp_(static_cast<std::size_t>(cageVertices), 0),
      slot_(static_cast<std::size_t>(cageVertices), 0),
      emitted_(static_cast<std::size_t>(patches.refinedVertexCount + patches.localPointCount)) {
  if (!patches.refinedStencils) throw Error("MatrixComposer: no refinement stencils");
  const std::size_t expectedRows =
      patches.patchTable
          ? static_cast<std::size_t>(patches.patchTable->GetNumControlVerticesTotal())
          : 0;
  sizes_.reserve(expectedRows);
  // Rows of typical meshes hold about 13 cage vertices; reserving avoids regrowing tens of MB.
  indices_.reserve(expectedRows * 14);
  weights_.reserve(expectedRows * 14);
}

// Calls f(cage vertex, weight) for each entry of a patch point in cage vertices; a local
// point's entries are its composed stencil and may repeat a vertex.
template <class F>
void MatrixComposer::forEachEntry(int point, F&& f) const {
  if (point < refinedCount_) {
    const auto v = static_cast<std::size_t>(point);
    for (int e = refined_.offsets[v], end = e + refined_.sizes[v]; e < end; ++e)
      f(static_cast<std::size_t>(refined_.indices[e]), refined_.weights[e]);
    return;
  }
  const auto row = static_cast<std::size_t>(point - refinedCount_);
  for (int l = local_.offsets[row], lend = l + local_.sizes[row]; l < lend; ++l) {
    const auto v = static_cast<std::size_t>(local_.indices[l]);
    const double lw = local_.weights[l];
    for (int e = refined_.offsets[v], end = e + refined_.sizes[v]; e < end; ++e)
      f(static_cast<std::size_t>(refined_.indices[e]), lw * refined_.weights[e]);
  }
}

// Expands `count` points into expanded_ (count x support, support sorted once): each
// point's stencil is read once however many rows use it.
void MatrixComposer::collectSupport(const int* points, int count) {
  ++block_;
  support_.clear();
  for (int k = 0; k < count; ++k)
    forEachEntry(points[k], [&](std::size_t column, double) {
      if (stamp_[column] != block_) {
        stamp_[column] = block_;
        support_.push_back(static_cast<int>(column));
      }
    });
  std::sort(support_.begin(), support_.end());
  const std::size_t n = support_.size();
  for (std::size_t i = 0; i < n; ++i)
    slot_[static_cast<std::size_t>(support_[i])] = static_cast<int>(i);
  expanded_.assign(static_cast<std::size_t>(count) * n, 0.0);
  for (int k = 0; k < count; ++k) {
    double* row = expanded_.data() + static_cast<std::size_t>(k) * n;
    forEachEntry(points[k], [&](std::size_t column, double w) { row[slot_[column]] += w; });
  }
}

void MatrixComposer::emitRow(const double* sums) {
  int size = 0;
  for (std::size_t i = 0; i < support_.size(); ++i) {
    if (sums[i] == 0.0) continue;
    indices_.push_back(support_[i]);
    weights_.push_back(sums[i]);
    ++size;
  }
  sizes_.push_back(size);
}

void MatrixComposer::addBezierPatch(const Far::ConstIndexArray& cvs,
                                    const PatchConversion& conversion) {
  if (cvs.size() != 16)
    throw Error("MatrixComposer: a regular patch has " + std::to_string(cvs.size()) +
                " points, expected 16");
  collectSupport(&cvs[0], 16);
  const std::size_t n = support_.size();
  sums_.resize(n);
  for (std::size_t r = 0; r < 16; ++r) {
    std::fill(sums_.begin(), sums_.end(), 0.0);
    for (std::size_t k = 0; k < 16; ++k) {
      const double w = conversion[r][k];
      if (w == 0.0) continue;
      const double* row = expanded_.data() + k * n;
      for (std::size_t i = 0; i < n; ++i) sums_[i] += w * row[i];
    }
    emitRow(sums_.data());
  }
}

void MatrixComposer::addPoints(const Far::ConstIndexArray& points) {
  for (int k = 0; k < points.size(); ++k) {
    Emitted& first = emitted_[static_cast<std::size_t>(points[k])];
    if (first.size >= 0) {
      for (std::size_t e = first.begin; e < first.begin + static_cast<std::size_t>(first.size);
           ++e) {
        indices_.push_back(indices_[e]);
        weights_.push_back(weights_[e]);
      }
      sizes_.push_back(first.size);
      continue;
    }
    first.begin = indices_.size();
    collectSupport(&points[k], 1);
    emitRow(expanded_.data());
    first.size = sizes_.back();
  }
}

PatchPointMatrix MatrixComposer::finish() {
  return PatchPointMatrix(cageVertices_, std::move(sizes_), std::move(indices_),
                          std::move(weights_));
}

}  // namespace osd_cull
