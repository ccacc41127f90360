// bench-draw: frame time and tessellation work of the patch draw path for tessellation
// levels 1..64, with draws split by tessellated vertex count (chunked) and as one draw per
// patch type, on BigGuy (isolation level 2, Gregory end caps). Prints Markdown tables; see
// docs/results/draw.md.
//
//   bench-draw [--mesh FILE] [--width 1280] [--height 720] [--repeats 3]
//              [--max-one-draw-level 16] [--depth-clamp-cost] [--displacement-scale 0.64]
//              [--device X]
//
// --depth-clamp-cost instead measures what clamping fragment depth to the control points
// costs (RenderOptions::clampDepthToControlPoints, patch.tesc): at tessellation 1, 4 and 16,
// frames with and without the clamp alternate (--repeats pairs after a warm-up of each),
// and it prints the median wall ms of each and their ratio. A mesh with texture coordinates
// is then also drawn displaced (the procedural map, 256x256, scale --displacement-scale),
// where the clamp takes the nearest corner of the boxes around the control points
// (common/displaced_reach.glsl): undisplaced and displaced rows interleave too.
//
// FILE defaults to ../shared/data/characters/bigguy.obj beside the source tree; without it
// (or with --mesh torus) a bicubic torus of BigGuy's size (--nu 96 --nv 58) stands in.
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;

struct Options {
  uint32_t width = 1280, height = 720, repeats = 3, maxOneDrawLevel = 16, nu = 96, nv = 58;
  std::string device;
  bool depthClampCost = false;
  double displacementScale = 0.64;
  std::string mesh = std::string(OSD_CULL_SOURCE_DIR) + "/../shared/data/characters/bigguy.obj";
};

// False after --help.
bool parse(int argc, char** argv, Options& o) {
  return bench::CommandLine("bench-draw", "bench_draw.cpp")
      .imageAndDevice(o.width, o.height, o.repeats, o.device)
      .text("--mesh", o.mesh)
      .number("--max-one-draw-level", o.maxOneDrawLevel)
      .number("--nu", o.nu)
      .number("--nv", o.nv)
      .flag("--depth-clamp-cost", o.depthClampCost)
      .real("--displacement-scale", o.displacementScale, 0.0)
      .parse(argc, argv);
}

using osd_cull::bench::median;

struct Row {
  double wallMs = 0, gpuMs = 0;
  uint64_t tes = 0, fragments = 0;
  uint32_t draws = 0, visible = 0;
};

Row measure(frame::Renderer& renderer, frame::VisibilityOracle& oracle, frame::RenderTarget& target,
            const frame::Camera& camera, const frame::GpuPatchSet& gpu, const PatchSet& host,
            const frame::RenderOptions& options, uint32_t repeats) {
  Row row;
  std::vector<double> wall, gpuTimes;
  const frame::PatchDraw draw{&gpu, &host, 0};
  renderer.render(target, camera, {&draw, 1}, {}, options);  // warm-up (pipeline JIT)
  for (uint32_t r = 0; r < repeats; ++r) {
    const auto stats = renderer.render(target, camera, {&draw, 1}, {}, options);
    wall.push_back(stats.wallMs);
    gpuTimes.push_back(stats.gpuMs);
    row.tes = stats.statistics.tessEvaluationInvocations;
    row.fragments = stats.statistics.fragmentShaderInvocations;
    row.draws = stats.drawCalls;
  }
  row.wallMs = median(wall);
  row.gpuMs = median(gpuTimes);
  row.visible = oracle.count(target, gpu.patchCount()).visiblePatchCount();
  return row;
}

// --depth-clamp-cost: frames with and without the depth clamp, alternating; `displaced`
// (optional) is the same patch set with a displacement map, interleaved with the plain one.
void depthClampCost(frame::Renderer& renderer, frame::RenderTarget& target,
                    const frame::Camera& camera, const frame::GpuPatchSet& gpu,
                    const frame::GpuPatchSet* displaced, const PatchSet& host, uint32_t repeats) {
  std::printf(
      "| draw | level | clamped ms | unclamped ms | clamped / unclamped |\n"
      "|---|---:|---:|---:|---:|\n");
  const frame::PatchDraw draws[2] = {{&gpu, &host, 0}, {displaced, &host, 0}};
  const int kinds = displaced ? 2 : 1;
  for (uint32_t level : {1u, 4u, 16u}) {
    frame::RenderOptions options[2];
    std::vector<double> wall[2][2];  // [draw][clamped, unclamped]
    for (int k = 0; k < 2; ++k) {
      options[k].tessellation.uniformLevel = level;
      options[k].clampDepthToControlPoints = k == 0;
      for (int d = 0; d < kinds; ++d)
        renderer.render(target, camera, {&draws[d], 1}, {}, options[k]);  // warm-up (JIT)
    }
    for (uint32_t r = 0; r < repeats; ++r)
      for (int d = 0; d < kinds; ++d)
        for (int k = 0; k < 2; ++k)
          wall[d][k].push_back(
              renderer.render(target, camera, {&draws[d], 1}, {}, options[k]).wallMs);
    for (int d = 0; d < kinds; ++d)
      std::printf("| %s | %u | %.1f | %.1f | %.3f |\n", d == 0 ? "plain" : "displaced", level,
                  median(wall[d][0]), median(wall[d][1]), median(wall[d][0]) / median(wall[d][1]));
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-draw", [&] {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    vulkan::Context context(bench::contextOptions(o.device));
    PatchSet set;
    std::vector<glm::dvec2> uvCorners;
    glm::dvec3 up(0, 1, 0), from(0.45, 0.35, 1.0);  // OBJ cages: y up, seen from the front
    if (o.mesh != "torus" && std::filesystem::exists(o.mesh)) {
      PatchExtraction ex = extractPatches(adapters::loadCage(o.mesh));
      set = std::move(ex.patches);
      uvCorners = std::move(ex.uvCorners);
    } else {
      std::fprintf(stderr, "bench-draw: %s not found, using a torus of BigGuy's size\n",
                   o.mesh.c_str());
      // About BigGuy's patch count and Gregory share (5554 patches, 14% Gregory).
      set = scene::convertToGregory(scene::bsplineTorus({o.nu, o.nv, 1.0, 0.4, {0, 0, 0}, -1}),
                                    [](uint32_t p) { return p % 7 == 3; });
      up = {0, 0, 1};
      from = {0.4, -1.0, 0.8};
    }
    frame::GpuPatchSet gpu(context, set);
    frame::RenderTarget target(context, o.width, o.height);
    frame::Renderer renderer(context);
    frame::VisibilityOracle oracle(context);
    const auto camera =
        frame::frameBounds(frame::boundsOf(set.points), from, up, 40.0, o.width, o.height);
    std::printf(
        "device: %s\npatches: %s, %u Bezier + %u Gregory; image %ux%u; median of %u frames\n\n",
        context.info().name.c_str(), set.source.c_str(), set.bezierCount, set.gregoryCount, o.width,
        o.height, o.repeats);
    if (o.depthClampCost) {
      std::unique_ptr<bound::DisplacementMap> map;
      std::unique_ptr<frame::GpuDisplacement> displacement;
      std::unique_ptr<frame::GpuPatchSet> displaced;
      if (!uvCorners.empty()) {
        map = std::make_unique<bound::DisplacementMap>("procedural", 256, 256,
                                                       scene::proceduralDisplacementTexels(256),
                                                       o.displacementScale, 0.5);
        displacement =
            std::make_unique<frame::GpuDisplacement>(context, *map, uvCorners, set.patchCount());
        displaced = std::make_unique<frame::GpuPatchSet>(context, set);
        displaced->setDisplacement(displacement.get());
        std::printf("displaced: procedural map 256x256, scale %g\n\n", o.displacementScale);
      }
      depthClampCost(renderer, target, camera, gpu, displaced.get(), set, o.repeats);
      return 0;
    }
    std::printf(
        "| level | draws | frame ms (wall) | GPU ms | TES invocations | TES / patch | fragment "
        "inv. | patches with pixels | one draw: frame ms | one draw: TES | one draw: patches with "
        "pixels | one draw / chunked time |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (uint32_t level : {1u, 2u, 4u, 8u, 12u, 14u, 16u, 24u, 32u, 48u, 64u}) {
      frame::RenderOptions options;
      options.tessellation.uniformLevel = level;
      const Row chunked = measure(renderer, oracle, target, camera, gpu, set, options, o.repeats);
      const uint32_t used =
          frame::effectiveOptions(options.tessellation, gpu.hasTransitionEdges()).uniformLevel;
      const std::string levelText =
          used == level ? std::to_string(level)
                        : std::to_string(level) + " (clamped to " + std::to_string(used) + ")";
      std::printf("| %s | %u | %.1f | %.1f | %llu | %.0f | %llu | %u |", levelText.c_str(),
                  chunked.draws, chunked.wallMs, chunked.gpuMs,
                  static_cast<unsigned long long>(chunked.tes),
                  double(chunked.tes) / set.patchCount(),
                  static_cast<unsigned long long>(chunked.fragments), chunked.visible);
      if (level <= o.maxOneDrawLevel) {
        options.chunkDraws = false;
        const Row one = measure(renderer, oracle, target, camera, gpu, set, options, o.repeats);
        std::printf(" %.1f | %llu | %u | %.2f |\n", one.wallMs,
                    static_cast<unsigned long long>(one.tes), one.visible,
                    one.wallMs / chunked.wallMs);
      } else {
        std::printf(" - | - | - | - |\n");
      }
      std::fflush(stdout);
    }
    // Adaptive levels for comparison.
    std::printf(
        "\n| adaptive px/segment | draws | frame ms (wall) | TES invocations | patches with pixels "
        "|\n|---:|---:|---:|---:|---:|\n");
    for (double px : {16.0, 8.0, 4.0, 2.0}) {
      frame::RenderOptions options;
      options.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
      options.tessellation.pixelsPerSegment = px;
      const Row r = measure(renderer, oracle, target, camera, gpu, set, options, o.repeats);
      std::printf("| %.0f | %u | %.1f | %llu | %u |\n", px, r.draws, r.wallMs,
                  static_cast<unsigned long long>(r.tes), r.visible);
      std::fflush(stdout);
    }
    return 0;
  });
}
