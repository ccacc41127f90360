#pragma once
/// \file adaptive_patches.h
/// \brief Feature-adaptive refinement → Far::PatchTable and the stencils of its points.

#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/topologyRefiner.h>

#include <memory>
#include <optional>

namespace osd_cull {

namespace Far = OpenSubdiv::Far;

/// \brief How irregular patches (around extraordinary vertices) are closed.
enum class EndCap {
  GregoryBasis,  ///< 20-point Gregory-basis patches (OpenSubdiv's default, smoothest)
  BSplineBasis,  ///< 16-point B-spline patches approximating the limit surface
};

/// \brief Options of the adaptive patch table.
struct PatchOptions {
  /// Feature-adaptive isolation level, 0..10. Level 0 is accepted only when every face that
  /// is not a hole is a quad (OpenSubdiv makes no patch for a non-quad face at level 0).
  int isolationLevel = 2;
  /// Shallower level at which smooth irregular features stop being isolated (OpenSubdiv's
  /// AdaptiveOptions::secondaryLevel), 0..isolationLevel; unset: isolate to isolationLevel.
  std::optional<int> secondaryLevel;
  EndCap endCaps = EndCap::GregoryBasis;
  /// Infinitely sharp creases and corners become regular boundary-like patches instead of
  /// being isolated to the last level (OpenSubdiv's useInfSharpPatch).
  bool infSharpPatches = true;
  /// Also build what recomputes the points from a moved cage: the refinement stencils and
  /// the cage -> point matrix (PatchExtraction::matrix). Off (a static mesh): the points are
  /// refined directly, in a fraction of the time and memory (about 1.7 KB per Bézier patch
  /// less), and the matrix is empty.
  bool pointMatrix = true;
};

/// \brief A patch table with double-precision stencils for all of its points.
///
/// Patch point index i (as in Far::PatchTable::GetPatchVertices) is refined vertex i for
/// i < refinedVertexCount (row i of refinedStencils), else local point i - refinedVertexCount
/// (a row of localPointStencils, whose indices are refined vertices). Composing the two
/// gives the point in terms of cage vertices, what
/// Far::StencilTableFactory::AppendLocalPointStencilTable computes.
struct AdaptivePatches {
  /// Owned when built here; for an application's table (adoptPatchTable) a non-owning
  /// pointer (no-op deleter).
  std::shared_ptr<const Far::PatchTable> patchTable;
  /// One stencil per vertex of every refinement level, level 0 included (as identity
  /// stencils); columns are the cage (level 0) vertices. Null when
  /// PatchOptions::pointMatrix is off.
  std::unique_ptr<const Far::StencilTableReal<double>> refinedStencils;
  /// One stencil per local (end-cap) point over refined vertices; owned by patchTable (or
  /// by convertedLocalPointStencils), null when there are no local points.
  const Far::StencilTableReal<double>* localPointStencils = nullptr;
  /// A double copy of a single-precision table's local-point stencils (adoptPatchTable).
  std::unique_ptr<const Far::StencilTableReal<double>> convertedLocalPointStencils;
  int refinedVertexCount = 0;  ///< vertices of all levels (refiner.GetNumVerticesTotal())
  int localPointCount = 0;     ///< end-cap points after them
  double refineMs = 0.0;       ///< adaptive refinement
  double patchTableMs = 0.0;   ///< Far::PatchTableFactory::Create
  double stencilMs = 0.0;      ///< refinement stencils
};

/// \brief Checks options (ranges above) and throws osd_cull::Error naming the bad option.
void checkPatchOptions(const PatchOptions& options);

/// \brief Refines `refiner` adaptively and builds the patch table and stencils.
/// The refiner must be a Catmull-Clark refiner that has not been refined yet.
/// \throws osd_cull::Error for Loop or bilinear refiners ("Loop patches are not extracted
/// yet"), an already refined refiner, or bad options.
AdaptivePatches buildAdaptivePatches(Far::TopologyRefiner& refiner, const PatchOptions& options);

/// \brief Takes a refiner and patch table the application already built (no second
/// refinement): only the refinement stencils are computed here, in double, and the
/// table's local-point stencils are used as they are (float ones widened to double, so
/// the surface is the application's). Both must outlive the result.
///
/// The table must come from this refiner, refined adaptively (RefineAdaptive) with
/// Catmull-Clark rules, with end caps GREGORY_BASIS or BSPLINE_BASIS and without
/// single-crease patches (useSingleCreasePatch = false): patches of type REGULAR and
/// GREGORY_BASIS only.
/// \throws osd_cull::Error naming what does not fit (scheme, uniform refinement, a table
/// of another refiner, the patch type and the option that produced it).
AdaptivePatches adoptPatchTable(const Far::TopologyRefiner& refiner, const Far::PatchTable& table);

/// \brief Refinement stencils (double, one per vertex of every level, level 0 included)
/// of an already refined refiner.
std::unique_ptr<const Far::StencilTableReal<double>> refinementStencils(
    const Far::TopologyRefiner& refiner);

}  // namespace osd_cull
