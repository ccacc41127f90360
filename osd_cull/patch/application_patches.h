#pragma once
/// \file application_patches.h
/// \brief Patches from OpenSubdiv objects the application already made: its refined
/// Far::TopologyRefiner and Far::PatchTable (e.g. those of its Osd::Mesh), with no second
/// refinement.
///
/// \code
///   // mesh: the application's Osd::Mesh (or its own refiner + patch table)
///   osd_cull::ApplicationPatches patches = osd_cull::extractApplicationPatches(
///       *mesh.GetTopologyRefiner(), *mesh.GetFarPatchTable(), cagePositions);
///   // patches.extraction.patches: the PatchSet to cull and draw
///   // patches.fromPatchPoints: control points from the mesh's refined vertex buffer
/// \endcode

#include "osd_cull/patch/extract_patches.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <span>
#include <string>

namespace osd_cull {

/// \brief The cull patch set of an application's refiner and patch table and two ways to
/// recompute its control points when the surface moves.
struct ApplicationPatches {
  /// PatchSet (points from the cage positions given) and the cage → control point matrix
  /// (columns: level-0 vertices), as extractPatches() makes them.
  PatchExtraction extraction;
  /// Rows: PatchSet points; columns: the table's patch points, i.e. the refined vertices
  /// of every level (level 0 first) and then the local (end-cap) points: what an
  /// adaptive Osd::Mesh's vertex buffer holds after Refine(). Each Bézier row is the
  /// B-spline → Bézier conversion of its patch's 16 points, each Gregory row one point.
  PatchPointMatrix fromPatchPoints;
};

/// \brief Builds the patch set from the application's refiner and patch table (see
/// adoptPatchTable() for what they must be); `cage` holds the refiner's level-0 positions,
/// `uvs` (optional) the values of its face-varying channel 0, for which the table must
/// have been built with face-varying tables (PatchExtraction::uvCorners).
/// The refiner and table are only read, and may be destroyed afterwards.
/// \throws osd_cull::Error for a table osd_cull cannot use (named) or a cage of another size.
ApplicationPatches extractApplicationPatches(const Far::TopologyRefiner& refiner,
                                             const Far::PatchTable& table,
                                             std::span<const glm::dvec3> cage,
                                             const std::string& source = {},
                                             std::span<const glm::dvec2> uvs = {});

/// \brief The fromPatchPoints matrix of `table`, whose refiner has `refinedVertexCount`
/// vertices over all levels (TopologyRefiner::GetNumVerticesTotal()).
PatchPointMatrix patchPointMatrix(const Far::PatchTable& table, int refinedVertexCount);

}  // namespace osd_cull
