#include "osd_cull/patch/extract_patches.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/refiner.h"

#include <opensubdiv/far/patchDescriptor.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <vector>

namespace osd_cull {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A stencil table's rows as plain arrays, with offsets computed here (Far fills offsets only
// on request).
struct StencilRows {
  const int* sizes = nullptr;
  std::vector<int> offsets;
  const int* indices = nullptr;
  const double* weights = nullptr;

  explicit StencilRows(const Far::StencilTableReal<double>* table) {
    if (!table) return;
    sizes = table->GetSizes().data();
    indices = table->GetControlIndices().data();
    weights = table->GetWeights().data();
    offsets.resize(table->GetSizes().size());
    int offset = 0;
    for (std::size_t r = 0; r < offsets.size(); ++r) {
      offsets[r] = offset;
      offset += table->GetSizes()[r];
    }
  }
};

// Builds the matrix row by row: each row is a weighted sum of patch points, each patch point
// a refined vertex (one refinement stencil) or a local point (a local-point stencil over
// refined vertices, composed here). Sums are accumulated in a dense array over the cage
// vertices and emitted with sorted columns and exact zeros dropped.
class RowComposer {
 public:
  RowComposer(const AdaptivePatches& patches, int columns)
      : refined_(patches.refinedStencils.get()),
        local_(patches.localPointStencils),
        refinedCount_(patches.refinedVertexCount),
        sum_(static_cast<std::size_t>(columns), 0.0),
        stamp_(static_cast<std::size_t>(columns), 0),
        slot_(static_cast<std::size_t>(columns), 0) {}

  // Adds weight * (patch point `point`) to the current row.
  void add(int point, double weight) {
    if (point < refinedCount_) {
      addRefined(point, weight);
      return;
    }
    const auto row = static_cast<std::size_t>(point - refinedCount_);
    const int begin = local_.offsets[row];
    for (int e = begin, end = begin + local_.sizes[row]; e < end; ++e)
      addRefined(local_.indices[e], weight * local_.weights[e]);
  }

  // Appends the current row to the output arrays and starts the next one.
  void finishRow() {
    std::sort(touched_.begin(), touched_.end());
    int size = 0;
    for (int column : touched_) {
      const double w = sum_[static_cast<std::size_t>(column)];
      if (w == 0.0) continue;
      outIndices.push_back(column);
      outWeights.push_back(w);
      ++size;
    }
    outSizes.push_back(size);
    touched_.clear();
    ++row_;
  }

  // Appends a copy of an emitted row (a point shared by several patches).
  void repeatRow(std::size_t row) {
    const std::size_t begin = rowOffset(row), size = static_cast<std::size_t>(outSizes[row]);
    for (std::size_t e = begin; e < begin + size; ++e) {
      outIndices.push_back(outIndices[e]);
      outWeights.push_back(outWeights[e]);
    }
    outSizes.push_back(static_cast<int>(size));
    ++row_;
  }

  // Emits the 16 rows of one Bézier patch: row r = sum over k of conversion[r][k] * point
  // cvs[k]. The 16 points are expanded to cage vertices once into a dense block over their
  // joint support (sorted once), and the conversion is applied to the block.
  void addBezierPatch(const Far::ConstIndexArray& cvs, const PatchConversion& conversion) {
    support_.clear();
    for (int k = 0; k < 16; ++k)
      forEachEntry(cvs[k], [&](std::size_t column, double) {
        if (stamp_[column] != row_) {
          stamp_[column] = row_;
          support_.push_back(static_cast<int>(column));
        }
      });
    std::sort(support_.begin(), support_.end());
    const std::size_t n = support_.size();
    for (std::size_t i = 0; i < n; ++i) slot_[static_cast<std::size_t>(support_[i])] = static_cast<int>(i);
    block_.assign(16 * n, 0.0);
    for (int k = 0; k < 16; ++k) {
      double* row = block_.data() + static_cast<std::size_t>(k) * n;
      forEachEntry(cvs[k], [&](std::size_t column, double w) { row[slot_[column]] += w; });
    }
    rowSum_.resize(n);
    for (std::size_t r = 0; r < 16; ++r) {
      std::fill(rowSum_.begin(), rowSum_.end(), 0.0);
      for (std::size_t k = 0; k < 16; ++k) {
        const double w = conversion[r][k];
        if (w == 0.0) continue;
        const double* row = block_.data() + k * n;
        for (std::size_t i = 0; i < n; ++i) rowSum_[i] += w * row[i];
      }
      int size = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (rowSum_[i] == 0.0) continue;
        outIndices.push_back(support_[i]);
        outWeights.push_back(rowSum_[i]);
        ++size;
      }
      outSizes.push_back(size);
      ++row_;
    }
  }

  std::size_t rowCount() const { return outSizes.size(); }

  std::vector<int> outSizes;
  std::vector<int> outIndices;
  std::vector<double> outWeights;

 private:
  // Calls f(cage vertex, weight) for each entry of patch point `point` in cage vertices
  // (a local point's entries are its composed stencil, possibly repeating a vertex).
  template <class F>
  void forEachEntry(int point, F&& f) const {
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

  void addRefined(int vertex, double weight) {
    const auto v = static_cast<std::size_t>(vertex);
    const int begin = refined_.offsets[v];
    for (int e = begin, end = begin + refined_.sizes[v]; e < end; ++e) {
      const auto column = static_cast<std::size_t>(refined_.indices[e]);
      if (stamp_[column] != row_) {
        stamp_[column] = row_;
        sum_[column] = 0.0;
        touched_.push_back(static_cast<int>(column));
      }
      sum_[column] += weight * refined_.weights[e];
    }
  }

  std::size_t rowOffset(std::size_t row) {
    // Offsets of emitted rows, extended lazily (only shared points ask).
    while (emittedOffsets_.size() <= row) {
      const std::size_t r = emittedOffsets_.size();
      emittedOffsets_.push_back(r == 0 ? 0 : emittedOffsets_[r - 1] + static_cast<std::size_t>(outSizes[r - 1]));
    }
    return emittedOffsets_[row];
  }

  StencilRows refined_;
  StencilRows local_;
  int refinedCount_;
  std::vector<double> sum_;
  std::vector<uint32_t> stamp_;  // row number + 1 that last touched the column
  std::vector<int> touched_;
  std::vector<int> slot_;        // column → position in support_ (valid for the current patch)
  std::vector<int> support_;     // sorted cage vertices used by the current patch
  std::vector<double> block_;    // 16 x support: the patch's points over its support
  std::vector<double> rowSum_;
  std::vector<std::size_t> emittedOffsets_;
  uint32_t row_ = 1;
};

struct PatchRef {
  int array;
  int index;
};

}  // namespace

PatchOrigin bsplinePatchOrigin(const Far::PatchParam& param) {
  if (!param.IsRegular()) return PatchOrigin::BSplineEndCap;
  switch (std::popcount(static_cast<unsigned>(param.GetBoundary()) & 15u)) {
    case 0: return PatchOrigin::Regular;
    case 1: return PatchOrigin::Boundary;
    default: return PatchOrigin::Corner;
  }
}

PatchExtraction extractPatches(const CageMesh& cage, const PatchOptions& options) {
  const std::string where = cage.source.empty() ? std::string("mesh") : cage.source;
  checkPatchOptions(options);
  if (cage.scheme != Scheme::CatmullClark)
    throw Error(where + ": " +
                (cage.scheme == Scheme::Loop ? "Loop patches are not extracted yet"
                                             : "bilinear patches are not extracted yet") +
                "; osd_cull extracts Catmull-Clark (catmark) patches only");
  const auto start = Clock::now();
  std::unique_ptr<Far::TopologyRefiner> refiner = makeTopologyRefiner(cage);
  const double topologyMs = msSince(start);
  PatchExtraction out = extractPatches(*refiner, cage.positions, options, cage.source);
  out.stats.topologyMs = topologyMs;
  out.stats.totalMs += topologyMs;
  return out;
}

PatchExtraction extractPatches(Far::TopologyRefiner& refiner, std::span<const glm::dvec3> positions,
                               const PatchOptions& options, const std::string& source) {
  const std::string where = source.empty() ? std::string("mesh") : source;
  const int cageVertices = refiner.GetLevel(0).GetNumVertices();
  if (positions.size() != static_cast<std::size_t>(cageVertices))
    throw Error(where + ": " + std::to_string(positions.size()) + " positions for a cage of " +
                std::to_string(cageVertices) + " vertices");

  AdaptivePatches adaptive;
  try {
    adaptive = buildAdaptivePatches(refiner, options);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  const Far::PatchTable& table = *adaptive.patchTable;

  const auto start = Clock::now();
  // Bézier patches first, then Gregory (patch_set.h), each in patch-table order.
  std::vector<PatchRef> bezier, gregory;
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    const Far::PatchDescriptor::Type type = table.GetPatchArrayDescriptor(a).GetType();
    std::vector<PatchRef>* list = type == Far::PatchDescriptor::REGULAR         ? &bezier
                                  : type == Far::PatchDescriptor::GREGORY_BASIS ? &gregory
                                                                                : nullptr;
    if (!list)
      throw Error(where + ": OpenSubdiv produced patches of type " + std::to_string(static_cast<int>(type)) +
                  "; only REGULAR and GREGORY_BASIS patches are extracted");
    for (int p = 0; p < table.GetNumPatches(a); ++p) list->push_back({a, p});
  }

  PatchExtraction out;
  PatchSet& set = out.patches;
  ExtractionStats& stats = out.stats;
  set.source = source;
  set.bezierCount = static_cast<uint32_t>(bezier.size());
  set.gregoryCount = static_cast<uint32_t>(gregory.size());
  set.params.reserve(set.patchCount());
  set.origins.reserve(set.patchCount());

  RowComposer rows(adaptive, cageVertices);
  const std::size_t pointCount = bezier.size() * kBezierPoints + gregory.size() * kGregoryPoints;
  rows.outSizes.reserve(pointCount);
  // Rows of BigGuy-like meshes hold about 13 entries; reserving avoids regrowing ~30 MB.
  rows.outIndices.reserve(pointCount * 14);
  rows.outWeights.reserve(pointCount * 14);

  for (const PatchRef& ref : bezier) {
    const Far::PatchParam param = table.GetPatchParam(ref.array, ref.index);
    const Far::ConstIndexArray cvs = table.GetPatchVertices(ref.array, ref.index);
    rows.addBezierPatch(cvs, bsplineToBezierWeights(param.GetBoundary()));
    set.params.push_back(param);
    set.origins.push_back(bsplinePatchOrigin(param));
  }
  // Gregory points are shared by neighbouring patches (shareEndCapPatchPoints): compose
  // each once, copy its row for the other patches.
  std::vector<int> firstRowOfPoint(static_cast<std::size_t>(adaptive.refinedVertexCount + adaptive.localPointCount), -1);
  for (const PatchRef& ref : gregory) {
    const Far::ConstIndexArray cvs = table.GetPatchVertices(ref.array, ref.index);
    for (uint32_t k = 0; k < kGregoryPoints; ++k) {
      int& first = firstRowOfPoint[static_cast<std::size_t>(cvs[static_cast<int>(k)])];
      if (first >= 0) {
        rows.repeatRow(static_cast<std::size_t>(first));
        continue;
      }
      first = static_cast<int>(rows.rowCount());
      rows.add(cvs[static_cast<int>(k)], 1.0);
      rows.finishRow();
    }
    set.params.push_back(table.GetPatchParam(ref.array, ref.index));
    set.origins.push_back(PatchOrigin::Gregory);
  }

  out.matrix = PatchPointMatrix(cageVertices, std::move(rows.outSizes), std::move(rows.outIndices),
                                std::move(rows.outWeights));
  set.points.resize(pointCount);
  out.matrix.update(positions, set.points);

  for (PatchOrigin origin : set.origins) {
    switch (origin) {
      case PatchOrigin::Regular: ++stats.regular; break;
      case PatchOrigin::Boundary: ++stats.boundary; break;
      case PatchOrigin::Corner: ++stats.corner; break;
      case PatchOrigin::Gregory: ++stats.gregory; break;
      case PatchOrigin::BSplineEndCap: ++stats.bsplineEndCaps; break;
      case PatchOrigin::Input: break;
    }
  }
  stats.controlPoints = static_cast<uint32_t>(pointCount);
  stats.matrixNonZeros = out.matrix.nonZeroCount();
  stats.cageVertices = cageVertices;
  stats.refinedVertices = adaptive.refinedVertexCount;
  stats.localPoints = adaptive.localPointCount;
  stats.refineMs = adaptive.refineMs;
  stats.patchTableMs = adaptive.patchTableMs;
  stats.stencilMs = adaptive.stencilMs;
  stats.matrixMs = msSince(start);
  stats.totalMs = stats.refineMs + stats.patchTableMs + stats.stencilMs + stats.matrixMs;
  return out;
}

}  // namespace osd_cull
