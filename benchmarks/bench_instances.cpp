// Instanced culling (docs/algorithms/instances.md, "Measured: one dispatch per patch set"):
// N instances of the creased cube (level 2) in a grid, each spinning, culled by the two-pass
// frame (frustum, tangent plane, Hi-Z) with all instances in one cull dispatch per view
// (CullFrameOptions::batchInstances) against one dispatch per instance. Frames of the two
// frames alternate (interleaved); the cull time is the wall clock of the cull submission of
// CullFrameOptions::timePasses (cull kernel, result copies and visibility updates).
//
// Usage: bench-instances [--counts 1,10,40,160] [--frames N] [--tess L]
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/scene_description.h"
#include "osd_cull/vk/context.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

struct Args {
  std::vector<uint32_t> counts = {1, 10, 40, 160};
  uint32_t frames = 20;
  uint32_t tess = 2;
};

int run(const Args& a) {
  vulkan::Context context;
  const CageMesh cage = scene::creasedCube();
  bound::CullablePatches cullable = bound::cullablePatches(cage, PatchOptions{2});
  const PatchSet patches = std::move(cullable.extraction.patches);
  const bound::BackPatchValidity validity = std::move(cullable.backPatch);
  frame::GpuPatchSet gpu(context, patches);
  frame::Renderer renderer(context);
  std::printf(
      "creased cube, %u patches per instance, %u frames per mode (interleaved), tess %u, "
      "160 x 120, frustum + tangent-plane + hiz, device %s\n\n",
      patches.patchCount(), a.frames, a.tess, context.info().name.c_str());
  std::printf("%9s %10s %12s %12s %8s %14s %14s %8s\n", "instances", "patches", "dispatches/f",
              "(separate)", "", "cull ms batch", "cull ms sep.", "ratio");
  for (uint32_t n : a.counts) {
    const uint32_t side = uint32_t(std::ceil(std::sqrt(double(n))));
    std::vector<frame::CullMesh> meshes;
    for (uint32_t i = 0; i < n; ++i)
      meshes.push_back({.gpu = &gpu,
                        .host = &patches,
                        .model = scene::composeTransform({3.0 * (i % side), 3.0 * (i / side), 0},
                                                         {0, 0, 0}, {1, 1, 1}),
                        .backPatchValidity = validity});
    frame::CullFrameOptions options;
    options.render.tessellation.uniformLevel = a.tess;
    options.render.cullBackFaces = true;
    options.cull.backPatch = "tangent-plane";
    options.timePasses = true;
    frame::RenderTarget targetA(context, 160, 120), targetB(context, 160, 120);
    options.batchInstances = true;
    frame::CullFrame batched(context, renderer, targetA, meshes, options);
    options.batchInstances = false;
    frame::CullFrame separate(context, renderer, targetB, meshes, options);
    const frame::Bounds bounds{{-1.5, -1.5, -1.5}, {3.0 * side, 3.0 * side, 1.5}};
    std::vector<double> msA, msB;
    uint64_t dispatchesA = 0, dispatchesB = 0;
    for (uint32_t f = 0; f < a.frames + 2; ++f) {
      const frame::Camera camera =
          frame::orbit(frame::frameBounds(bounds, {0.3, -1.0, 0.8}, {0, 0, 1}, 40.0, 160, 120),
                       bounds.center(), {0, 0, 1}, 9.0 * f);
      for (size_t i = 0; i < meshes.size(); ++i) {
        const glm::dmat4 spin =
            meshes[i].model * scene::composeTransform({}, {0, 0, 7.0 * f}, {1, 1, 1});
        batched.setModel(i, spin);
        separate.setModel(i, spin);
      }
      const uint64_t before[2] = {batched.cullDispatches(), separate.cullDispatches()};
      const frame::CullFrameStats sA = batched.render(camera, {});
      const frame::CullFrameStats sB = separate.render(camera, {});
      if (sA.culled() != sB.culled())
        throw Error("batched and separate frames culled " + std::to_string(sA.culled()) + " and " +
                    std::to_string(sB.culled()) + " patches");
      if (f < 2) continue;  // warm-up
      msA.push_back(sA.cullMs);
      msB.push_back(sB.cullMs);
      dispatchesA = batched.cullDispatches() - before[0];
      dispatchesB = separate.cullDispatches() - before[1];
    }
    const double a50 = bench::median(msA), b50 = bench::median(msB);
    std::printf("%9u %10u %12llu %12llu %8s %14.3f %14.3f %8.2f\n", n, n * patches.patchCount(),
                static_cast<unsigned long long>(dispatchesA),
                static_cast<unsigned long long>(dispatchesB), "", a50, b50, b50 / a50);
  }
  std::printf("\nratio = separate / batched (median cull ms; > 1: one dispatch is faster)\n");
  return 0;
}

}  // namespace
}  // namespace osd_cull

int main(int argc, char** argv) {
  return osd_cull::bench::run("bench-instances", [&] {
    osd_cull::Args a;
    const bool go = osd_cull::bench::CommandLine("bench-instances", "bench_instances.cpp")
                        .numbers("--counts", a.counts)
                        .number("--frames", a.frames, 1)
                        .number("--tess", a.tess, 1)
                        .parse(argc, argv);
    return go ? osd_cull::run(a) : 0;
  });
}
