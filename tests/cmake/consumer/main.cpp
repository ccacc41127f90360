// A program outside the osd_cull tree, built against the installed package: it extracts
// the patches of a cube cage, moves the cage through the cage → control-point matrix, and
// culls the patches on the GPU (lavapipe) for a camera framing the cube and one looking away
// from it, with the SPIR-V the library embeds (it does not link glslang).
// Every include is <osd_cull/...>: the loaders, the shared GPU layouts (through the cull
// pass header) and the generated version header too.
#include <osd_cull/adapters/load_mesh.h>
#include <osd_cull/frame/camera.h>
#include <osd_cull/frame/cull/cull_pass.h>
#include <osd_cull/frame/draw/gpu_patch_set.h>
#include <osd_cull/patch/extract_patches.h>
#include <osd_cull/scene/procedural.h>
#include <osd_cull/version.h>
#include <osd_cull/vk/context.h>

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

  // Frustum culling on the GPU: every patch survives a camera that frames the cube, none one
  // that looks away from it.
  osd_cull::vulkan::Context context;
  osd_cull::frame::GpuPatchSet gpu(context, ex.patches);
  osd_cull::frame::CullPass pass(context, gpu, ex.patches, osd_cull::frame::CullSettings{});
  const auto bounds = osd_cull::frame::boundsOf(ex.patches.points);
  const auto framed =
      osd_cull::frame::frameBounds(bounds, {1.0, 0.5, 2.0}, {0.0, 1.0, 0.0}, 40.0, 64, 48);
  const auto away = osd_cull::frame::Camera::lookAt({0.0, 0.0, 5.0}, {0.0, 0.0, 10.0},
                                                    {0.0, 1.0, 0.0}, 40.0, 64, 48, 0.1, 100.0);
  pass.run(framed);
  const uint32_t framedSurvivors = pass.counts().survivors();
  pass.run(away);
  const uint32_t awaySurvivors = pass.counts().survivors();
  std::printf("consumer: cull survivors framed=%u away=%u\n", framedSurvivors, awaySurvivors);
  return ex.patches.patchCount() > 0 && shift > 9.999999 && shift < 10.000001 && versionsAgree &&
                 objKnown && framedSurvivors == ex.patches.patchCount() && awaySurvivors == 0
             ? 0
             : 1;
}
