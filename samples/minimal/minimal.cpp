// The smallest complete use of osd_cull: a Catmull-Clark cage in, a rendered PNG out.
//
//   minimal [MESH.obj] [OUT.png]
//
// 1. load a cage (adapters/) or take a built-in one (osd_cull/scene),
// 2. extract Bézier and Gregory patches from OpenSubdiv's adaptive patch table,
// 3. move the cage and update every control point through the one sparse matrix,
// 4. upload the patches and draw them with the Vulkan tessellation pipeline.
#include "adapters/load_mesh.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "adapters/image_png.h"
#include "osd_cull/frame/draw/render_target.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/context.h"

#include <cstdio>
#include <exception>
#include <vector>

int main(int argc, char** argv) try {
  using namespace osd_cull;
  const CageMesh cage = argc > 1 ? adapters::loadCage(argv[1]) : scene::defaultMesh();
  const char* out = argc > 2 ? argv[2] : "minimal.png";

  PatchExtraction ex = extractPatches(cage, PatchOptions{.isolationLevel = 2});
  std::printf("%s: %u Bezier + %u Gregory patches\n", cage.source.c_str(), ex.patches.bezierCount,
              ex.patches.gregoryCount);

  // Animation: a new cage gives new control points in one sparse matrix-vector product.
  std::vector<glm::dvec3> moved = cage.positions;
  for (glm::dvec3& p : moved) p.y *= 1.1;
  ex.matrix.update(moved, ex.patches.points);

  vulkan::Context context;  // lavapipe unless $OSD_CULL_DEVICE names another device
  frame::GpuPatchSet gpu(context, ex.patches);
  const uint32_t width = 480, height = 360;
  const frame::Camera camera = frame::frameBounds(frame::boundsOf(ex.patches.points),
                                                  {1.0, 0.6, 1.4}, {0.0, 1.0, 0.0}, 40.0, width, height);
  frame::RenderTarget target(context, width, height);
  frame::Renderer renderer(context);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 6;
  const frame::FrameStats stats = renderer.render(target, camera, gpu, &ex.patches, options);
  adapters::writePng(out, adapters::colorImage(width, height, target.readColor(context)));
  std::printf("drew %u patches, %llu tessellation-evaluation invocations, %.1f ms; wrote %s\n",
              stats.patchesDrawn,
              static_cast<unsigned long long>(stats.statistics.tessEvaluationInvocations),
              stats.wallMs, out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "minimal: error: %s\n", e.what());
  return 1;
}
