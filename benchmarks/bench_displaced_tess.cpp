// bench-displaced-tess: the cost of displacement-aware adaptive tessellation
// (docs/algorithms/displacement.md, "Tessellation"): TES invocations, frame wall time and
// GPU time of the displaced draw with the edge-variation levels (`--displaced-tess edge`)
// against the undisplaced levels (`none`), the same views, the two interleaved view by view
// and repeat by repeat (the order alternating); and the crack pixels of each. Prints a
// Markdown table; docs/results/displacement.md section 4.
//
//   bench-displaced-tess [--mesh FILE] [--level 2] [--views 8] [--repeats 5] [--scale 0.64]
//                        [--pixels 4,8] [--size 512] [--device X]
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/frame/verify/crack_count.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/context.h"

#include <array>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;
using frame::DisplacedTessellation;

struct Figures {
  std::vector<double> wallMs;  // median over the repeats, per view
  std::vector<double> gpuMs;
  uint64_t tes = 0;  // TES invocations summed over the views (exact, one repeat)
  uint64_t cracks = 0;
};

int measure(const std::string& mesh, uint32_t level, uint32_t views, uint32_t repeats,
            uint32_t size, double scale, const std::vector<uint32_t>& pixels,
            const std::string& device) {
  vulkan::Context context(bench::contextOptions(device));
  PatchOptions patchOptions;
  patchOptions.isolationLevel = static_cast<int>(level);
  const PatchExtraction ex = extractPatches(adapters::loadCage(mesh), patchOptions);
  const bound::DisplacementMap map("procedural", 256, 256, scene::proceduralDisplacementTexels(256),
                                   scale, 0.5);
  frame::GpuPatchSet gpu(context, ex.patches);
  frame::GpuDisplacement displacement(context, map, ex.uvCorners, ex.patches.patchCount());
  gpu.setDisplacement(&displacement);
  frame::RenderTarget target(context, size, size);
  frame::Renderer renderer(context);
  const frame::PatchDraw draw{&gpu, &ex.patches, 0};

  frame::ViewSetOptions viewOptions;
  viewOptions.set = frame::ViewSet::WholeObject;
  viewOptions.count = views;
  viewOptions.width = size;
  viewOptions.height = size;
  const auto cameras = frame::randomViews(frame::boundsOf(ex.patches.points), viewOptions);

  std::printf(
      "device %s; %s level %u: %u patches; procedural map 256x256, scale %g; %u whole-object "
      "views %ux%u, %u repeats, back faces drawn\n\n",
      context.info().name.c_str(), mesh.c_str(), level, ex.patches.patchCount(), scale, views, size,
      size, repeats);
  std::printf(
      "| px/segment | levels | TES invocations (all views) | frame ms (median of view medians) "
      "| GPU ms | crack pixels (all views) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  constexpr std::array<DisplacedTessellation, 2> kModes = {DisplacedTessellation::Ignore,
                                                           DisplacedTessellation::EdgeVariation};
  for (uint32_t px : pixels) {
    std::array<Figures, 2> figures;
    frame::RenderOptions options;
    options.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
    options.tessellation.pixelsPerSegment = px;
    options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
    for (DisplacedTessellation mode : kModes) {  // warm-up: pipelines, caches
      options.tessellation.displaced = mode;
      renderer.render(target, cameras[0], {&draw, 1}, {}, options);
    }
    std::vector<double> viewRatios;
    for (const frame::Camera& camera : cameras) {
      std::array<std::vector<double>, 2> wall, gpuTime;
      for (uint32_t r = 0; r < repeats; ++r)
        for (size_t k = 0; k < kModes.size(); ++k) {
          const size_t m = (r % 2 == 0) ? k : kModes.size() - 1 - k;  // alternate the order
          options.tessellation.displaced = kModes[m];
          const frame::FrameStats stats = renderer.render(target, camera, {&draw, 1}, {}, options);
          wall[m].push_back(stats.wallMs);
          gpuTime[m].push_back(stats.gpuMs);
          if (r == 0) figures[m].tes += stats.statistics.tessEvaluationInvocations;
        }
      for (size_t m = 0; m < kModes.size(); ++m) {
        figures[m].wallMs.push_back(bench::median(wall[m]));
        figures[m].gpuMs.push_back(bench::median(gpuTime[m]));
        options.tessellation.displaced = kModes[m];
        figures[m].cracks += frame::countCracks(context, renderer, target, camera, draw, options,
                                                frame::kSeamCrackWidth);
      }
      viewRatios.push_back(figures[1].wallMs.back() / figures[0].wallMs.back());
    }
    for (size_t m = 0; m < kModes.size(); ++m)
      std::printf("| %u | %s | %llu | %.1f | %.1f | %llu |\n", px, frame::toString(kModes[m]),
                  static_cast<unsigned long long>(figures[m].tes), bench::median(figures[m].wallMs),
                  bench::median(figures[m].gpuMs),
                  static_cast<unsigned long long>(figures[m].cracks));
    std::printf("| %u | edge / none | %.3f | %.3f (median of per-view ratios %.3f) | %.3f | |\n",
                px, double(figures[1].tes) / double(figures[0].tes),
                bench::median(figures[1].wallMs) / bench::median(figures[0].wallMs),
                bench::median(viewRatios),
                bench::median(figures[1].gpuMs) / bench::median(figures[0].gpuMs));
  }
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::fprintf(stderr, "validation reported %zu messages\n", size_t(log->count()));
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-displaced-tess", [&] {
    std::string mesh = (bench::dataDir() / "characters" / "bigguy.obj").string(), device;
    uint32_t level = 2, views = 8, repeats = 5, size = 512;
    double scale = 0.64;
    std::vector<uint32_t> pixels = {4, 8};
    bench::CommandLine options("bench-displaced-tess", "bench_displaced_tess.cpp");
    options.text("--mesh", mesh)
        .number("--level", level)
        .number("--views", views, 1)
        .number("--repeats", repeats, 1)
        .number("--size", size, 16)
        .numbers("--pixels", pixels)
        .real("--scale", scale, -1e30)
        .text("--device", device);
    if (!options.parse(argc, argv)) return 0;
    return measure(mesh, level, views, repeats, size, scale, pixels, device);
  });
}
