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
  out.backPatch =
      bound::backPatchValidity(summarize(*makeTopologyRefiner(cage)), bound::signedVolume(cage));
  // The commands never move the cage: no cage -> point matrix (a fraction of the time and
  // memory at a million patches).
  PatchOptions pointsOnly = options;
  pointsOnly.pointMatrix = false;
  out.patches = extractPatches(cage, pointsOnly).patches;
  return out;
}

}  // namespace osd_cull::cli
