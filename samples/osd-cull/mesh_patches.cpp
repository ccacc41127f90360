#include "mesh_patches.h"

#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"

namespace osd_cull::cli {

MeshPatches meshPatches(const LoadedMesh& mesh, const PatchOptions& options) {
  MeshPatches out;
  out.name = mesh.name;
  if (mesh.bezier) {
    out.patches = *mesh.bezier;
    out.backPatch = {false,
                     "a Bezier patch file carries no topology to show that the surface is "
                     "closed and oriented outward"};
    return out;
  }
  const CageMesh& cage = *mesh.cage;
  out.notes = cage.notes;
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
