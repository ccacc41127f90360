// A program outside the osd_cull tree, built against the installed package.
#include <osd_cull/patch/refiner.h>

#include <cstdio>

int main() {
  osd_cull::CageMesh cube;
  cube.source = "consumer:cube";
  cube.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  cube.faceSizes = {4, 4, 4, 4, 4, 4};
  cube.faceVertices = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
  const auto summary = osd_cull::summarize(*osd_cull::makeTopologyRefiner(cube));
  std::printf("consumer: cube faces=%d closed=%d\n", summary.faces, summary.closed ? 1 : 0);
  return summary.closed ? 0 : 1;
}
