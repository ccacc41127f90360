#include "osd_cull/patch/extract_patches.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/face_varying_uv.h"
#include "osd_cull/patch/matrix_composer.h"
#include "osd_cull/patch/refiner.h"

#include <opensubdiv/far/patchDescriptor.h>

#include <bit>
#include <chrono>
#include <optional>
#include <vector>

namespace osd_cull {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct PatchRef {
  int array;
  int index;
};

}  // namespace

PatchOrigin bsplinePatchOrigin(const Far::PatchParam& param) {
  if (!param.IsRegular()) return PatchOrigin::BSplineEndCap;
  switch (std::popcount(static_cast<unsigned>(param.GetBoundary()) & 15u)) {
    case 0:
      return PatchOrigin::Regular;
    case 1:
      return PatchOrigin::Boundary;
    default:
      return PatchOrigin::Corner;
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
  PatchExtraction out = extractPatches(*refiner, cage.positions, options, cage.source, cage.uvs);
  out.stats.topologyMs = topologyMs;
  out.stats.totalMs += topologyMs;
  return out;
}

PatchExtraction extractPatches(Far::TopologyRefiner& refiner, std::span<const glm::dvec3> positions,
                               const PatchOptions& options, const std::string& source,
                               std::span<const glm::dvec2> uvs) {
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
      throw Error(where + ": OpenSubdiv produced patches of type " +
                  std::to_string(static_cast<int>(type)) +
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

  std::optional<PatchUVEvaluator> uvEvaluator;
  if (!uvs.empty()) uvEvaluator.emplace(refiner, table, uvs, where);
  MatrixComposer rows(adaptive, cageVertices);
  for (const PatchRef& ref : bezier) {
    const Far::PatchParam param = table.GetPatchParam(ref.array, ref.index);
    rows.addBezierPatch(table.GetPatchVertices(ref.array, ref.index),
                        bsplineToBezierWeights(param.GetBoundary()));
    set.params.push_back(param);
    set.origins.push_back(bsplinePatchOrigin(param));
    if (uvEvaluator) uvEvaluator->appendCorners(ref.array, ref.index, out.uvCorners);
  }
  for (const PatchRef& ref : gregory) {
    rows.addPoints(table.GetPatchVertices(ref.array, ref.index));
    set.params.push_back(table.GetPatchParam(ref.array, ref.index));
    set.origins.push_back(PatchOrigin::Gregory);
    if (uvEvaluator) uvEvaluator->appendCorners(ref.array, ref.index, out.uvCorners);
  }
  const std::size_t pointCount = bezier.size() * kBezierPoints + gregory.size() * kGregoryPoints;
  if (rows.rowCount() != pointCount)
    throw Error(where + ": composed " + std::to_string(rows.rowCount()) + " rows for " +
                std::to_string(pointCount) + " control points");
  out.matrix = rows.finish();
  set.points.resize(pointCount);
  out.matrix.update(positions, set.points);

  for (PatchOrigin origin : set.origins) {
    switch (origin) {
      case PatchOrigin::Regular:
        ++stats.regular;
        break;
      case PatchOrigin::Boundary:
        ++stats.boundary;
        break;
      case PatchOrigin::Corner:
        ++stats.corner;
        break;
      case PatchOrigin::Gregory:
        ++stats.gregory;
        break;
      case PatchOrigin::BSplineEndCap:
        ++stats.bsplineEndCaps;
        break;
      case PatchOrigin::Input:
        break;
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
