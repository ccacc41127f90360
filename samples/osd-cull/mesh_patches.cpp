#include "mesh_patches.h"

#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/loaded_scene.h"

#include <cstdio>
#include <optional>

namespace osd_cull::cli {
namespace {

/// The note of a recentred mesh: what was removed, and what it means for the user's own
/// coordinates.
std::string recentreNote(const glm::dvec3& offset) {
  char text[256];
  std::snprintf(text, sizeof(text),
                "the mesh lies far from the origin: recentred by (%.9g, %.9g, %.9g), its "
                "bounding-box centre, so that it is drawn and culled in fp32 coordinates near "
                "the origin",
                offset.x, offset.y, offset.z);
  return text;
}

}  // namespace

MeshPatches meshPatches(const LoadedMesh& mesh, const PatchOptions& options) {
  MeshPatches out;
  out.name = mesh.name;
  if (mesh.bezier) {
    out.patches = *mesh.bezier;
    out.recentreOffset = scene::recentreFar(out.patches.points);
    if (out.recentreOffset != glm::dvec3(0.0))
      out.notes.push_back(recentreNote(out.recentreOffset));
    out.backPatch = {false,
                     "a Bezier patch file carries no topology to show that the surface is "
                     "closed and oriented outward"};
    return out;
  }
  // Recentred before refinement, as scenes are (scene::makeSceneMesh): the patch points are
  // then computed near the origin too. The cage is copied only when it is far.
  std::optional<CageMesh> recentred;
  if (scene::farMeshOffset(mesh.cage->positions) != glm::dvec3(0.0)) {
    recentred = *mesh.cage;
    out.recentreOffset = scene::recentreFar(recentred->positions);
  }
  const CageMesh& cage = recentred ? *recentred : *mesh.cage;
  out.notes = cage.notes;
  if (recentred) out.notes.push_back(recentreNote(out.recentreOffset));
  // The commands never move the cage: no cage -> point matrix (a fraction of the time and
  // memory at a million patches).
  PatchOptions pointsOnly = options;
  pointsOnly.pointMatrix = false;
  bound::CullablePatches c = bound::cullablePatches(cage, pointsOnly);  // checks the scheme first
  out.backPatch = std::move(c.backPatch);
  out.patches = std::move(c.extraction.patches);
  out.uvCorners = std::move(c.extraction.uvCorners);
  return out;
}

}  // namespace osd_cull::cli
