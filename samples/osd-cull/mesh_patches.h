#pragma once
/// \file mesh_patches.h
/// \brief A loaded mesh turned into patches, with the per-mesh back-patch decision, as the
/// culling subcommands (render, verify) need it.

#include "mesh_source.h"

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/patch/adaptive_patches.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace osd_cull::cli {

/// \brief Patches of a mesh and whether back-patch culling may be used on it.
struct MeshPatches {
  std::string name;
  PatchSet patches;
  bound::BackPatchValidity backPatch;
  /// What the loader ignored or found unusual (CageMesh::notes): commands print these as
  /// `note: ...`, so that e.g. a dropped `vertexedit` tag is never silent.
  std::vector<std::string> notes;
  /// Texture coordinates of the patch corners, 4 per patch (PatchExtraction::uvCorners);
  /// empty without texture coordinates.
  std::vector<glm::dvec2> uvCorners;
  /// Subtracted from every position at load when the mesh lies far from the origin
  /// (scene::recentreFar, the recentring scenes use; zero otherwise): `patches` are in the file's
  /// coordinates minus this offset, and a camera or occluder given in the file's coordinates must
  /// be moved by it too. A note says so when it is not zero.
  glm::dvec3 recentreOffset{0.0};
};

/// \brief Extracts the patches of a cage (bound::backPatchValidity from its topology and
/// signed volume) or takes a Bézier patch file as is (back-patch culling off: a patch file
/// carries no topology to show that it is closed). A mesh far from the origin is recentred
/// first (MeshPatches::recentreOffset), as scenes are, so that it is drawn and culled with
/// the precision of an origin mesh.
MeshPatches meshPatches(const LoadedMesh& mesh, const PatchOptions& options);

}  // namespace osd_cull::cli
