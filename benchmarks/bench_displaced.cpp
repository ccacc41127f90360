// bench-displaced: cost per patch of the displaced kernels (Niessner & Loop Fig. 7 left):
// NoDisp (the frustum stage on the control points), Full, ACoN and CoN on OOBB and CAF (the
// frustum stage on the displaced bound), and the host cost of building the cones that a
// moving mesh would rebuild every frame. Prints a Markdown table; docs/results/displacement.md.
//
//   bench-displaced [--mesh FILE] [--levels 2,3,4] [--views 10] [--repeats 3] [--scale S]
//
// Kernel time: wall time of one cull submission (counter reset, cull dispatch, draw-command
// dispatch, wait), the kernels interleaved view by view, median per patch.
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/context.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;
using bound::DisplacedBox;
using bound::DisplacedExtension;


double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) try {
  std::string mesh = std::string(OSD_CULL_SOURCE_DIR) + "/../shared/data/characters/bigguy.obj";
  std::vector<uint32_t> levels = {2, 3, 4};
  uint32_t views = 10, repeats = 3;
  double scale = 0.64;
  if (!bench::CommandLine("bench-displaced", "bench_displaced.cpp")
           .text("--mesh", mesh)
           .numbers("--levels", levels)
           .number("--views", views, 1)
           .number("--repeats", repeats, 1)
           .real("--scale", scale, 0.0)
           .parse(argc, argv))
    return 0;
  const vulkan::ContextOptions contextOptions;
  vulkan::Context context(contextOptions);
  const bound::DisplacementMap map("procedural", 256, 256, scene::proceduralDisplacementTexels(256),
                                   scale, 0.5);
  const CageMesh cage = adapters::loadCage(mesh);
  std::printf("device %s, procedural map scale %g, %u views x %u repeats\n\n",
              context.info().name.c_str(), scale, views, repeats);
  std::printf(
      "| level | patches | kernel | ns/patch (median) | ratio to NoDisp | host cone build ns/patch "
      "|\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (uint32_t level : levels) {
    PatchOptions options;
    options.isolationLevel = static_cast<int>(level);
    const PatchExtraction ex = extractPatches(cage, options);
    const uint32_t n = ex.patches.patchCount();
    frame::GpuPatchSet gpu(context, ex.patches);
    frame::ViewSetOptions vo;
    vo.set = frame::ViewSet::WholeObject;
    vo.count = views;
    const auto cameras = frame::randomViews(frame::boundsOf(ex.patches.points), vo);

    struct Kernel {
      std::string name;
      std::unique_ptr<frame::CullPass> pass;
      std::vector<double> ms;
      double hostNs = 0.0;
    };
    std::vector<Kernel> kernels;
    frame::CullSettings plain;
    plain.frustum = true;
    kernels.push_back(
        {"nodisp", std::make_unique<frame::CullPass>(context, gpu, ex.patches, plain), {}, 0.0});
    for (DisplacedBox box : {DisplacedBox::OOBB, DisplacedBox::CAF})
      for (DisplacedExtension e :
           {DisplacedExtension::Full, DisplacedExtension::ACoN, DisplacedExtension::CoN}) {
        frame::CullSettings s;
        s.frustum = true;
        s.displacementMap = &map;
        s.uvCorners = ex.uvCorners;
        s.displacedKernel = {e, box};
        kernels.push_back({bound::displacedKernelName(e, box),
                           std::make_unique<frame::CullPass>(context, gpu, ex.patches, s),
                           {},
                           0.0});
        // Host cost of the per-patch data a moving mesh would rebuild: the cones.
        const auto c = std::chrono::steady_clock::now();
        for (uint32_t p = 0; p < n; ++p) (void)bound::displacementCone(ex.patches, p, e);
        kernels.back().hostNs = msSince(c) * 1e6 / n;
      }
    for (auto& k : kernels) k.pass->run(cameras[0]);  // warm-up (kernel compile)
    for (const auto& camera : cameras)
      for (uint32_t r = 0; r < repeats; ++r)
        for (auto& k : kernels) k.ms.push_back(k.pass->run(camera));
    const double base = bench::median(kernels[0].ms);
    for (const auto& k : kernels)
      std::printf("| %u | %u | %s | %.0f | %.2f | %.0f |\n", level, n, k.name.c_str(),
                  bench::median(k.ms) * 1e6 / n, bench::median(k.ms) / base, k.hostNs);
    std::fflush(stdout);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench-displaced: %s\n", e.what());
  return 1;
}
