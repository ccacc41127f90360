#pragma once
/// \file extract_patches.h
/// \brief The entry point of osd_cull/patch: a cage in, Bézier and Gregory patches and the
/// cage → control-point matrix out.
///
/// Pipeline: makeTopologyRefiner → buildAdaptivePatches (feature-adaptive refinement,
/// Far::PatchTable, refinement + local-point stencils) → per patch, B-spline boundary
/// extrapolation and B-spline → Bézier conversion (bspline_bezier.h) or the 20 Gregory-basis
/// points → one PatchPointMatrix whose rows are every control point of the PatchSet.

#include "osd_cull/patch/adaptive_patches.h"
#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/patch/patch_set.h"
#include "osd_cull/patch/point_matrix.h"
#include "osd_cull/patch/refiner.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace osd_cull {

/// \brief What an extraction produced and what it cost.
struct ExtractionStats {
  uint32_t regular = 0;         ///< PatchOrigin::Regular
  uint32_t boundary = 0;        ///< PatchOrigin::Boundary
  uint32_t corner = 0;          ///< PatchOrigin::Corner
  uint32_t gregory = 0;         ///< PatchOrigin::Gregory
  uint32_t bsplineEndCaps = 0;  ///< PatchOrigin::BSplineEndCap
  uint32_t controlPoints = 0;   ///< rows of the matrix, points of the PatchSet
  std::size_t matrixNonZeros = 0;
  int cageVertices = 0;
  int refinedVertices = 0;    ///< vertices of all refinement levels
  int localPoints = 0;        ///< OpenSubdiv end-cap points
  double topologyMs = 0.0;    ///< cage → Far::TopologyRefiner
  double refineMs = 0.0;      ///< adaptive refinement
  double patchTableMs = 0.0;  ///< Far::PatchTable
  double stencilMs = 0.0;     ///< refinement and local-point stencils
  double matrixMs = 0.0;      ///< the points (and the matrix, when built)
  double totalMs = 0.0;

  uint32_t patches() const { return regular + boundary + corner + gregory + bsplineEndCaps; }
};

/// \brief PatchSet + the matrix that recomputes its points from moved cage vertices.
struct PatchExtraction {
  PatchSet patches;
  /// rows = patches.points, columns = cage vertices; empty (0 x 0) when
  /// PatchOptions::pointMatrix is off
  PatchPointMatrix matrix;
  /// Texture coordinates of the patch corners (0,0), (1,0), (1,1), (0,1), four per patch in
  /// PatchSet order, bilinear over the patch (face_varying_uv.h); empty when the cage has no
  /// texture coordinates.
  std::vector<glm::dvec2> uvCorners;
  /// The base level of the refiner the patches came from (summarize()), read before it was
  /// refined: what bound::backPatchValidity() decides from, without building the refiner a
  /// second time. Left empty by the composition-only overload.
  TopologySummary topology;
  ExtractionStats stats;
};

/// \brief Extracts the patches of a Catmull-Clark cage.
/// \throws osd_cull::Error for an invalid cage (see validate()), Loop or bilinear schemes
/// (not extracted yet), bad options, or a patch type OpenSubdiv should not have produced.
PatchExtraction extractPatches(const CageMesh& cage, const PatchOptions& options = {});

/// \brief The same for a base-level refiner the caller built; `positions` are its level-0
/// vertices. The refiner is refined adaptively in place. With `uvs`, the values of the
/// refiner's face-varying channel 0, PatchExtraction::uvCorners is filled.
PatchExtraction extractPatches(Far::TopologyRefiner& refiner, std::span<const glm::dvec3> positions,
                               const PatchOptions& options = {}, const std::string& source = {},
                               std::span<const glm::dvec2> uvs = {});

/// \brief The composition step alone: the PatchSet and matrix of refinement results (from
/// buildAdaptivePatches() or adoptPatchTable() on `refiner`) for level-0 `positions`, and
/// with `uvs` (face-varying channel 0 of the base level) the uvCorners.
PatchExtraction extractPatches(const Far::TopologyRefiner& refiner, const AdaptivePatches& adaptive,
                               std::span<const glm::dvec3> positions, const std::string& source,
                               std::span<const glm::dvec2> uvs = {});

/// \brief A patch of a Far::PatchTable: patch array and index in it.
struct PatchRef {
  int array;
  int index;
};

/// \brief The patches of a table in PatchSet order: all REGULAR (→ Bézier) patches, then all
/// GREGORY_BASIS ones, each in table order.
struct PatchOrder {
  std::vector<PatchRef> bezier;
  std::vector<PatchRef> gregory;
};

/// \brief PatchOrder of `table`.
/// \throws osd_cull::Error naming `where` for any other patch type.
PatchOrder patchOrder(const Far::PatchTable& table, const std::string& where);

/// \brief The origin of a regular B-spline patch from its PatchParam: BSplineEndCap if
/// OpenSubdiv marks it irregular, else by its boundary edges: none → Regular, one →
/// Boundary, two or more (a corner, or a strip one patch wide) → Corner.
PatchOrigin bsplinePatchOrigin(const Far::PatchParam& param);

}  // namespace osd_cull
