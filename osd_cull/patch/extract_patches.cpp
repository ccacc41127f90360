#include "osd_cull/patch/extract_patches.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/face_varying_uv.h"
#include "osd_cull/patch/matrix_composer.h"
#include "osd_cull/patch/refiner.h"

#include <opensubdiv/far/patchDescriptor.h>
#include <opensubdiv/far/primvarRefiner.h>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <array>
#include <bit>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

namespace osd_cull {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// One non-zero weight of a B-spline -> Bézier conversion (a regular patch has 100 of 256).
struct ConversionTerm {
  uint8_t row;
  uint8_t column;
  double weight;
};

std::vector<ConversionTerm> nonZeroTerms(const PatchConversion& conversion) {
  std::vector<ConversionTerm> out;
  for (uint8_t r = 0; r < 16; ++r)
    for (uint8_t k = 0; k < 16; ++k)
      if (conversion[r][k] != 0.0) out.push_back({r, k, conversion[r][k]});
  return out;
}

// A position as OpenSubdiv's primvar refiner and stencil tables want it.
struct Position {
  glm::dvec3 p{0.0};
  void Clear(void* = nullptr) { p = glm::dvec3(0.0); }
  void AddWithWeight(const Position& src, double weight) { p += weight * src.p; }
};

// Positions of every patch point (Far::PatchTable::GetPatchVertices index): the vertices of
// all refinement levels, refined level by level (what the refinement stencils give, without
// building them), then the local (end-cap) points from their stencils.
std::vector<Position> patchPointPositions(const Far::TopologyRefiner& refiner,
                                          const AdaptivePatches& adaptive,
                                          std::span<const glm::dvec3> cage) {
  std::vector<Position> out(static_cast<std::size_t>(adaptive.refinedVertexCount) +
                            static_cast<std::size_t>(adaptive.localPointCount));
  for (std::size_t v = 0; v < cage.size(); ++v) out[v].p = cage[v];
  Far::PrimvarRefinerReal<double> primvar(refiner);
  Position* level = out.data();
  for (int l = 1; l <= refiner.GetMaxLevel(); ++l) {
    Position* next = level + refiner.GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, level, next);
    level = next;
  }
  if (adaptive.localPointStencils)
    adaptive.localPointStencils->UpdateValues(out.data(), out.data() + adaptive.refinedVertexCount);
  return out;
}

}  // namespace

PatchOrder patchOrder(const Far::PatchTable& table, const std::string& where) {
  PatchOrder order;
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    const Far::PatchDescriptor::Type type = table.GetPatchArrayDescriptor(a).GetType();
    std::vector<PatchRef>* list = type == Far::PatchDescriptor::REGULAR         ? &order.bezier
                                  : type == Far::PatchDescriptor::GREGORY_BASIS ? &order.gregory
                                                                                : nullptr;
    if (!list)
      throw Error(where + ": OpenSubdiv produced patches of type " +
                  std::to_string(static_cast<int>(type)) +
                  "; only REGULAR and GREGORY_BASIS patches are extracted");
    for (int p = 0; p < table.GetNumPatches(a); ++p) list->push_back({a, p});
  }
  return order;
}

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
  refiner.reset();
#ifdef __GLIBC__
  // The refiner and the patch table were many small allocations that glibc keeps in its
  // heap after they are freed: about 130 bytes per patch of resident memory for the rest of
  // the process at a million patches (docs/results/scale.md). Hand the free pages back.
  malloc_trim(0);
#endif
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

  const TopologySummary topology = summarize(refiner);
  AdaptivePatches adaptive;
  try {
    adaptive = buildAdaptivePatches(refiner, options);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  PatchExtraction out = extractPatches(refiner, adaptive, positions, source, uvs);
  out.topology = topology;
  return out;
}

PatchExtraction extractPatches(const Far::TopologyRefiner& refiner, const AdaptivePatches& adaptive,
                               std::span<const glm::dvec3> positions, const std::string& source,
                               std::span<const glm::dvec2> uvs) {
  const std::string where = source.empty() ? std::string("mesh") : source;
  const int cageVertices = refiner.GetLevel(0).GetNumVertices();
  if (positions.size() != static_cast<std::size_t>(cageVertices))
    throw Error(where + ": " + std::to_string(positions.size()) + " positions for a cage of " +
                std::to_string(cageVertices) + " vertices");
  const Far::PatchTable& table = *adaptive.patchTable;

  const auto start = Clock::now();
  // Bézier patches first, then Gregory (patch_set.h), each in patch-table order.
  const PatchOrder order = patchOrder(table, where);
  const std::vector<PatchRef>& bezier = order.bezier;
  const std::vector<PatchRef>& gregory = order.gregory;

  PatchExtraction out;
  PatchSet& set = out.patches;
  ExtractionStats& stats = out.stats;
  set.source = source;
  set.bezierCount = static_cast<uint32_t>(bezier.size());
  set.gregoryCount = static_cast<uint32_t>(gregory.size());
  set.params.reserve(set.patchCount());
  set.origins.reserve(set.patchCount());

  const std::size_t pointCount = bezier.size() * kBezierPoints + gregory.size() * kGregoryPoints;
  std::optional<PatchUVEvaluator> uvEvaluator;
  if (!uvs.empty()) uvEvaluator.emplace(refiner, table, uvs, where);
  for (const PatchRef& ref : bezier) {
    const Far::PatchParam param = table.GetPatchParam(ref.array, ref.index);
    set.params.push_back(param);
    set.origins.push_back(bsplinePatchOrigin(param));
    if (uvEvaluator) uvEvaluator->appendCorners(ref.array, ref.index, out.uvCorners);
  }
  for (const PatchRef& ref : gregory) {
    set.params.push_back(table.GetPatchParam(ref.array, ref.index));
    set.origins.push_back(PatchOrigin::Gregory);
    if (uvEvaluator) uvEvaluator->appendCorners(ref.array, ref.index, out.uvCorners);
  }
  if (adaptive.refinedStencils) {  // PatchOptions::pointMatrix: the cage -> points matrix
    MatrixComposer rows(adaptive, cageVertices);
    for (std::size_t p = 0; p < bezier.size(); ++p)
      rows.addBezierPatch(table.GetPatchVertices(bezier[p].array, bezier[p].index),
                          bsplineToBezierWeights(set.params[p].GetBoundary()));
    for (const PatchRef& ref : gregory)
      rows.addPoints(table.GetPatchVertices(ref.array, ref.index));
    if (rows.rowCount() != pointCount)
      throw Error(where + ": composed " + std::to_string(rows.rowCount()) + " rows for " +
                  std::to_string(pointCount) + " control points");
    out.matrix = rows.finish();
    set.points.resize(pointCount);
    out.matrix.update(positions, set.points);
  } else {
    // The same points without the matrix: each Bézier point is its conversion row applied to
    // the 16 B-spline points (bspline_bezier.h), each Gregory point a patch point.
    const std::vector<Position> at = patchPointPositions(refiner, adaptive, positions);
    std::array<std::vector<ConversionTerm>, 16> terms;  // per boundary mask, on first use
    // Appended, not resized and overwritten: at a million patches touching the 384 MB of
    // points twice costs more than computing them (docs/results/scale.md).
    set.points.reserve(pointCount);
    for (std::size_t p = 0; p < bezier.size(); ++p) {
      const Far::ConstIndexArray cvs = table.GetPatchVertices(bezier[p].array, bezier[p].index);
      const unsigned mask = static_cast<unsigned>(set.params[p].GetBoundary()) & 15u;
      if (terms[mask].empty()) terms[mask] = nonZeroTerms(bsplineToBezierWeights(mask));
      glm::dvec3 cv[16];
      for (int k = 0; k < 16; ++k) cv[k] = at[static_cast<std::size_t>(cvs[k])].p;
      glm::dvec3 point[kBezierPoints] = {};
      for (const ConversionTerm& t : terms[mask]) point[t.row] += t.weight * cv[t.column];
      set.points.insert(set.points.end(), point, point + kBezierPoints);
    }
    for (const PatchRef& ref : gregory) {
      const Far::ConstIndexArray cvs = table.GetPatchVertices(ref.array, ref.index);
      for (int k = 0; k < cvs.size(); ++k) set.points.push_back(at[cvs[k]].p);
    }
    if (set.points.size() != pointCount)
      throw Error(where + ": refined " + std::to_string(set.points.size()) + " points for " +
                  std::to_string(pointCount) + " control points");
  }

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
