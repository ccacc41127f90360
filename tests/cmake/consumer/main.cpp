// A program outside the osd_cull tree, built against the installed package: it extracts
// the patches of a cube cage and moves the cage through the cage → control-point matrix.
// Every include is <osd_cull/...>: the loaders, the shared GPU layouts (through the cull
// pass header) and the generated version header too.
#include <osd_cull/adapters/load_mesh.h>
#include <osd_cull/frame/cull/cull_pass.h>
#include <osd_cull/patch/extract_patches.h>
#include <osd_cull/scene/procedural.h>
#include <osd_cull/version.h>

#include <cstdio>
#include <cstring>
#include <vector>

int main() {
  const osd_cull::CageMesh cube = osd_cull::scene::cube();
  const osd_cull::PatchExtraction ex = osd_cull::extractPatches(cube);
  std::vector<glm::dvec3> moved = cube.positions;
  for (auto& p : moved) p += glm::dvec3(10.0, 0.0, 0.0);
  std::vector<glm::dvec3> points(ex.patches.points.size());
  ex.matrix.update(moved, points);
  const double shift = points[0].x - ex.patches.points[0].x;  // affine: every point moves by 10
  const bool versionsAgree = std::strcmp(osd_cull::libraryVersion(), osd_cull::kVersion) == 0;
  const bool objKnown = osd_cull::adapters::cageFileExtensions().front() == ".obj";
  std::printf("consumer: osd_cull %s (headers %s)\n", osd_cull::libraryVersion(),
              osd_cull::kVersion);
  std::printf("consumer: cube patches=%u shift=%.6f\n", ex.patches.patchCount(), shift);
  return ex.patches.patchCount() > 0 && shift > 9.999999 && shift < 10.000001 && versionsAgree &&
                 objKnown
             ? 0
             : 1;
}
