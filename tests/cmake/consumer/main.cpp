// A program outside the osd_cull tree, built against the installed package: it extracts
// the patches of a cube cage and moves the cage through the cage → control-point matrix.
#include <osd_cull/patch/extract_patches.h>
#include <osd_cull/scene/procedural.h>

#include <cstdio>
#include <vector>

int main() {
  const osd_cull::CageMesh cube = osd_cull::scene::cube();
  const osd_cull::PatchExtraction ex = osd_cull::extractPatches(cube);
  std::vector<glm::dvec3> moved = cube.positions;
  for (auto& p : moved) p += glm::dvec3(10.0, 0.0, 0.0);
  std::vector<glm::dvec3> points(ex.patches.points.size());
  ex.matrix.update(moved, points);
  const double shift = points[0].x - ex.patches.points[0].x;  // affine: every point moves by 10
  std::printf("consumer: cube patches=%u shift=%.6f\n", ex.patches.patchCount(), shift);
  return ex.patches.patchCount() > 0 && shift > 9.999999 && shift < 10.000001 ? 0 : 1;
}
