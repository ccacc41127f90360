#pragma once
/// \file face_varying_uv.h
/// \brief Texture coordinates of patches from the cage's face-varying UVs (OBJ `vt`),
/// refined by OpenSubdiv (Far::PrimvarRefiner::InterpolateFaceVarying) and read through the
/// patch table's face-varying channel.
///
/// The patch table holds OpenSubdiv's linear face-varying patches: a patch's texture
/// coordinates are the bilinear interpolation of the refined face's four face-varying
/// values at the patch's level, the linear mapping Sathe's pre-processing assumes. That is
/// exact for FVarInterpolation::All (linear face-varying interpolation); for the smooth
/// rules it is the piecewise-bilinear approximation at the isolation level, and the draw
/// uses the same corners, so the bound (the box of the four corners, exact for bilinear
/// interpolation) is exact for what is drawn.

#include "osd_cull/patch/patch_set.h"

#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/topologyRefiner.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace osd_cull {

namespace Far = OpenSubdiv::Far;

/// \brief Evaluates the texture coordinates of patch corners from a refined refiner and
/// its patch table (built with face-varying tables, see buildAdaptivePatches).
class PatchUVEvaluator {
 public:
  /// \brief Refines `uvs` (the values of face-varying channel 0 of the base level) to
  /// every level of `refiner`.
  /// \throws osd_cull::Error naming `where` when the table has no face-varying channel,
  /// the value count does not match the channel, or the patches are not linear.
  PatchUVEvaluator(const Far::TopologyRefiner& refiner, const Far::PatchTable& table,
                   std::span<const glm::dvec2> uvs, const std::string& where);

  /// \brief Appends the texture coordinates at the patch's corners (0,0), (1,0), (1,1),
  /// (0,1) of its own parameterisation (the one the Bézier and Gregory points use).
  void appendCorners(int array, int index, std::vector<glm::dvec2>& out) const;

 private:
  const Far::PatchTable& table_;
  std::vector<glm::dvec2> values_;  ///< face-varying values of every level, concatenated
  std::vector<int> arrayFirstPatch_;
};

/// \brief Edges where texture coordinates are discontinuous (UV seams) between patches
/// that share the edge in space: counted over `corners` (4 per patch) by matching the
/// patches' corner positions `positions` (4 per patch, the same order). Each seam edge
/// counts once.
uint32_t countUVSeamEdges(std::span<const glm::dvec3> positions,
                          std::span<const glm::dvec2> corners);

/// \brief countUVSeamEdges() of a patch set: the corner positions are the patches' own
/// (evaluated at (0,0), (1,0), (1,1), (0,1)); `corners` as PatchExtraction::uvCorners.
uint32_t countUVSeamEdges(const PatchSet& patches, std::span<const glm::dvec2> corners);

}  // namespace osd_cull
