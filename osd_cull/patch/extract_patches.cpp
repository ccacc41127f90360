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

// Builds the matrix row by row: each row is a weighted sum of stencil rows, accumulated in a
// dense array over the cage vertices and emitted with sorted columns and exact zeros dropped.
class RowComposer {
 public:
  RowComposer(const Far::StencilTableReal<double>& stencils, int columns)
      : sizes_(stencils.GetSizes()),
        offsets_(stencils.GetOffsets()),
        indices_(stencils.GetControlIndices()),
        weights_(stencils.GetWeights()),
        sum_(static_cast<std::size_t>(columns), 0.0),
        stamp_(static_cast<std::size_t>(columns), 0) {}

  // Adds weight * (stencil of patch point `point`) to the current row.
  void add(int point, double weight) {
    const int begin = offsets_[static_cast<std::size_t>(point)];
    const int end = begin + sizes_[static_cast<std::size_t>(point)];
    for (int e = begin; e < end; ++e) {
      const auto column = static_cast<std::size_t>(indices_[static_cast<std::size_t>(e)]);
      if (stamp_[column] != row_) {
        stamp_[column] = row_;
        sum_[column] = 0.0;
        touched_.push_back(static_cast<int>(column));
      }
      sum_[column] += weight * weights_[static_cast<std::size_t>(e)];
    }
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

  std::vector<int> outSizes;
  std::vector<int> outIndices;
  std::vector<double> outWeights;

 private:
  const std::vector<int>& sizes_;
  const std::vector<int>& offsets_;
  const std::vector<int>& indices_;
  const std::vector<double>& weights_;
  std::vector<double> sum_;
  std::vector<uint32_t> stamp_;  // row number + 1 that last touched the column
  std::vector<int> touched_;
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

  RowComposer rows(*adaptive.stencils, cageVertices);
  const std::size_t pointCount = bezier.size() * kBezierPoints + gregory.size() * kGregoryPoints;
  rows.outSizes.reserve(pointCount);

  for (const PatchRef& ref : bezier) {
    const Far::PatchParam param = table.GetPatchParam(ref.array, ref.index);
    const Far::ConstIndexArray cvs = table.GetPatchVertices(ref.array, ref.index);
    const PatchConversion& conversion = bsplineToBezierWeights(param.GetBoundary());
    for (uint32_t r = 0; r < kBezierPoints; ++r) {
      for (int k = 0; k < 16; ++k)
        if (conversion[r][static_cast<std::size_t>(k)] != 0.0)
          rows.add(cvs[k], conversion[r][static_cast<std::size_t>(k)]);
      rows.finishRow();
    }
    set.params.push_back(param);
    set.origins.push_back(bsplinePatchOrigin(param));
  }
  for (const PatchRef& ref : gregory) {
    const Far::ConstIndexArray cvs = table.GetPatchVertices(ref.array, ref.index);
    for (uint32_t k = 0; k < kGregoryPoints; ++k) {
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
