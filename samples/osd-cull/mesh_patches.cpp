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
  PatchExtraction ex = extractPatches(cage, options);
  out.patches = std::move(ex.patches);
  out.uvCorners = std::move(ex.uvCorners);
  return out;
}

}  // namespace osd_cull::cli
