// bench-cull: cost of the cull kernel per method and patch count, and what culling saves in
// a frame, on BigGuy (or another cage). Prints Markdown tables; see docs/results/backpatch.md.
//
//   bench-cull [--mesh FILE] [--levels 1,2,3] [--views 20] [--tess 4,8,16]
//              [--width 640] [--height 480] [--repeats 3] [--parts 12] [--device X]
//              [--methods empty,tcone/surface,...]
//              [--frame-modes tcone,tcone/surface,tcone/listed,...] [--kernel-tess 4]
//
// Part 1: wall time of one cull submission (counter reset, cull dispatch, draw-command
// dispatch, wait), median over views x repeats, per patch; "empty" is a pass with no test;
// per uniform tessellation level of --kernel-tess (the drawn-triangle tests depend on it).
// The methods run interleaved: for each view and repeat every method once, so that the
// load of a shared machine affects them alike. "compile ms" is the first pass of each
// (pipeline creation, mostly lavapipe's shader compilation).
// Back-patch methods run twice: respecting the drawn triangles (the default) and with
// "/surface", the papers' surface-exact tests (CullSettings::drawnTriangles = false);
// "/listed" adds the listed-triangle test (CullSettings::drawnEnumerate).
// Part 2: frames of sphere views drawn in full and with culling (cull pass + survivors in
// one submission), medians of wall time and tessellation-evaluation invocations. Like for
// like: both sides cull back faces in the rasterizer when the mesh is closed and oriented.
// The modes ("none" and --frame-modes) run interleaved: per view and repeat, each once.
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/vk/context.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;

struct Options {
  std::string mesh = std::string(OSD_CULL_SOURCE_DIR) + "/../shared/data/characters/bigguy.obj";
  std::vector<uint32_t> levels = {1, 2, 3};
  std::vector<uint32_t> tess = {4, 8, 16};
  uint32_t views = 20, width = 640, height = 480, repeats = 3;
  std::string device;
  std::vector<std::string> methods = {"empty",
                                      "frustum",
                                      "tcone",
                                      "tcone/surface",
                                      "ncone",
                                      "ncone/surface",
                                      "tangent-plane",
                                      "tangent-plane/surface",
                                      "tangent-plane-16",
                                      "tangent-plane-16/surface"};
  std::vector<std::string> frameModes = {"tcone", "tcone/surface", "tangent-plane",
                                         "tangent-plane/surface", "all"};
  std::vector<uint32_t> kernelTess = {4};  ///< part 1's tessellation levels
  std::string parts = "12";                ///< which parts run
};

// False after --help.
bool parse(int argc, char** argv, Options& o) {
  return bench::CommandLine("bench-cull", "bench_cull.cpp")
      .imageAndDevice(o.width, o.height, o.repeats, o.device)
      .text("--mesh", o.mesh)
      .numbers("--levels", o.levels)
      .numbers("--tess", o.tess)
      .number("--views", o.views, 1)
      .names("--methods", o.methods)
      .names("--frame-modes", o.frameModes)
      .numbers("--kernel-tess", o.kernelTess)
      .text("--parts", o.parts)
      .parse(argc, argv);
}

using osd_cull::bench::median;

using Mesh = osd_cull::bench::CullMesh;
using osd_cull::bench::loadCullMesh;

frame::CullSettings settingsFor(std::string method, const bound::BackPatchValidity& v) {
  frame::CullSettings s;
  const std::string surface = "/surface", listed = "/listed";
  if (method.ends_with(surface)) {
    s.drawnTriangles = false;
    method.resize(method.size() - surface.size());
  } else if (method.ends_with(listed)) {
    s.drawnEnumerate = true;
    method.resize(method.size() - listed.size());
  }
  s.backPatchValidity = v;
  s.frustum = method == "frustum" || method == "all";
  if (method != "frustum" && method != "empty" && method != "all") s.backPatch = method;
  if (method == "all") s.backPatch = "tangent-plane";
  return s;
}

void kernelCost(vulkan::Context& context, const Options& o) {
  std::printf(
      "\n| level | tess | patches | method | cull rate | ns/patch (median) | ms/pass | compile ms "
      "|\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (uint32_t level : o.levels) {
    const Mesh mesh = loadCullMesh(o.mesh, level);
    frame::GpuPatchSet gpu(context, mesh.patches);
    frame::ViewSetOptions vo;
    vo.count = o.views;
    vo.width = o.width;
    vo.height = o.height;
    const auto cameras = frame::randomViews(frame::boundsOf(mesh.patches.points), vo);
    const uint32_t n = mesh.patches.patchCount();
    std::vector<std::unique_ptr<frame::CullPass>> passes;
    std::vector<double> compileMs;
    for (uint32_t tess : o.kernelTess) {
      frame::TessellationOptions tessellation;
      tessellation.uniformLevel = tess;
      passes.clear();
      compileMs.clear();
      for (const std::string& method : o.methods) {
        const auto start = std::chrono::steady_clock::now();
        passes.push_back(std::make_unique<frame::CullPass>(context, gpu, mesh.patches,
                                                           settingsFor(method, mesh.validity)));
        passes.back()->run(cameras[0], tessellation);  // pipeline creation, first compile
        compileMs.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
      }
      std::vector<std::vector<double>> ms(passes.size());
      std::vector<uint64_t> culled(passes.size(), 0);
      for (const auto& camera : cameras)
        for (uint32_t r = 0; r < o.repeats; ++r)
          for (size_t m = 0; m < passes.size(); ++m) {
            ms[m].push_back(passes[m]->run(camera, tessellation));
            if (r == 0) culled[m] += n - passes[m]->counts().survivors();
          }
      for (size_t m = 0; m < passes.size(); ++m) {
        std::printf("| %u | %u | %u | %s | %.1f%% | %.0f | %.3f | %.0f |\n", level, tess, n,
                    o.methods[m].c_str(),
                    100.0 * double(culled[m]) / double(n) / double(cameras.size()),
                    median(ms[m]) * 1e6 / n, median(ms[m]), compileMs[m]);
      }
      std::fflush(stdout);
    }
  }
}

void frameSavings(vulkan::Context& context, const Options& o) {
  const uint32_t level = o.levels.size() > 1 ? o.levels[1] : o.levels.at(0);
  const Mesh mesh = loadCullMesh(o.mesh, level);
  frame::GpuPatchSet gpu(context, mesh.patches);
  frame::Renderer renderer(context);
  frame::RenderTarget target(context, o.width, o.height);
  frame::ViewSetOptions vo;
  vo.count = o.views;
  vo.width = o.width;
  vo.height = o.height;
  const auto cameras = frame::randomViews(frame::boundsOf(mesh.patches.points), vo);
  std::printf(
      "\nlevel %u, %u patches, %u sphere views, %ux%u, %u repeats; back faces %s in every "
      "row, with and without culling\n\n",
      level, mesh.patches.patchCount(), o.views, o.width, o.height, o.repeats,
      mesh.validity.enabled ? "culled by the rasterizer" : "drawn (mesh not closed/oriented)");
  std::printf(
      "| tess | cull | patches drawn | TES invocations | frame ms (median) | ratio to none |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (uint32_t tess : o.tess) {
    frame::RenderOptions options;
    options.tessellation.uniformLevel = tess;
    options.cullBackFaces = mesh.validity.enabled;
    std::vector<std::string> modes = {"none"};
    modes.insert(modes.end(), o.frameModes.begin(), o.frameModes.end());
    std::vector<std::unique_ptr<frame::CullPass>> passes;
    for (const std::string& mode : modes)
      passes.push_back(mode == "none"
                           ? nullptr
                           : std::make_unique<frame::CullPass>(context, gpu, mesh.patches,
                                                               settingsFor(mode, mesh.validity)));
    const frame::PatchDraw draw{&gpu, &mesh.patches, 0};
    auto frameOnce = [&](size_t m, const frame::Camera& camera) {
      return passes[m] ? frame::renderCulled(renderer, target, camera, *passes[m], {}, options)
                       : renderer.render(target, camera, {&draw, 1}, {}, options);
    };
    for (size_t m = 0; m < modes.size(); ++m) frameOnce(m, cameras[0]);  // warm-up
    std::vector<std::vector<double>> ms(modes.size()), tes(modes.size()), drawn(modes.size());
    for (const auto& camera : cameras)
      for (uint32_t r = 0; r < o.repeats; ++r)
        for (size_t m = 0; m < modes.size(); ++m) {
          const frame::FrameStats s = frameOnce(m, camera);
          ms[m].push_back(s.wallMs);
          tes[m].push_back(double(s.statistics.tessEvaluationInvocations));
          drawn[m].push_back(s.patchesDrawn);
        }
    const double noneMs = median(ms[0]);
    for (size_t m = 0; m < modes.size(); ++m)
      std::printf("| %u | %s | %.0f | %.0f | %.2f | %.2f |\n", tess, modes[m].c_str(),
                  median(drawn[m]), median(tes[m]), median(ms[m]), median(ms[m]) / noneMs);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-cull", [&] {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    vulkan::Context context(bench::contextOptions(o.device));
    std::printf("bench-cull: %s on %s\n", o.mesh.c_str(), context.info().name.c_str());
    if (o.parts.find('1') != std::string::npos) kernelCost(context, o);
    if (o.parts.find('2') != std::string::npos) frameSavings(context, o);
    return 0;
  });
}
