// bench-cull: cost of the cull kernel per method and patch count, what culling saves in a
// frame, and the break-even cull rate, on BigGuy (or another cage). Prints Markdown tables;
// see docs/results/backpatch.md and docs/results/accuracy-vs-time.md (scripts/study.sh).
//
//   bench-cull [--mesh FILE] [--levels 1,2,3] [--views 20] [--tess 4,8,16]
//              [--width 640] [--height 480] [--repeats 3] [--parts 12] [--device X]
//              [--methods empty,tcone/surface,...]
//              [--frame-modes tcone,tcone/surface,tcone/listed,hiz/full,...] [--kernel-tess 4]
//              [--displacement procedural|MAP] [--displacement-scale 0.64]
//              [--break-even-tess 1,2,4,8,16,32] [--break-even-methods frustum,tcone]
//              [--break-even-views 4] [--floor-grids 316,1000] [--floor-views 3] [--validate]
//
// Method and mode names: "empty" (a pass with no test), "frustum", "all" (frustum +
// tangent plane), a back-patch method ("tcone", ...) with the drawn-triangle bound (the
// default), "/surface" (the papers' surface-exact tests, CullSettings::drawnTriangles =
// false) or "/listed" (the listed-triangle test, CullSettings::drawnEnumerate); Hi-Z
// occlusion "hiz" (half resolution, the paper's lookup level), "hiz/full", "hiz/tight",
// "hiz/full-tight" (HiZOptions::fullResolution, HiZLookup::Tight); a displaced kernel
// ("acon-caf", ..., frame::cullMethods()) on the mesh displaced by --displacement.
//
// Part 1: wall time of one cull submission (counter reset, cull dispatch, draw-command
// dispatch, wait), median over views x repeats, per patch, per uniform tessellation level
// of --kernel-tess (the drawn-triangle tests depend on it). The methods run interleaved:
// for each view and repeat every method once, so that the load of a shared machine affects
// them alike. "compile ms" is the first pass of each (pipeline creation, mostly lavapipe's
// shader compilation). Back-patch and Hi-Z kernels run alone, as `osd-cull verify` runs
// them (Hi-Z and displaced kernels on the pyramid of the view's unculled depth, built
// before the timed passes, not timed).
// Part 2: frames of sphere views drawn in full and with culling, medians of wall time and
// tessellation-evaluation invocations. Like for like: both sides cull back faces in the
// rasterizer when the mesh is closed and oriented (a displaced mesh draws them on both
// sides). Back-patch modes: the cull pass and the survivors in one submission
// (renderCulled). Hi-Z and displaced modes: the two-pass frame (frame::CullFrame, frustum
// and Hi-Z) rendered twice per view, the second timed (the steady state of a still camera:
// last frame's visibility is this view's). Displaced modes are compared with the unculled
// displaced frame ("displaced:none"). The modes run interleaved: per view and repeat each once.
// Part 3: the break-even cull rate (Niessner & Loop §6.3, Fig. 9 left) measured per
// tessellation level. A frustum sweep: the cull pass tests a frustum narrowed by a zoom of
// the projection (1 to 1000) while the frame draws with the real camera, so that a known,
// counted share s of the patches is drawn; per view, the frame time over the unculled
// frame's median is r(s); a least-squares line r = a + b s through the medians per zoom
// gives the crossing r = 1: break-even cull rate x* = (a + b - 1) / b. Each method of
// --break-even-methods (frustum and back-patch stage, drawn-triangle bound) is timed on
// the real frustum too; with the sweep's slope b its intercept a_m is the median of
// r - b s over views and its break-even (a_m + b - 1) / b. All frames interleaved per view.
// Part 4: each kernel next to its floor (issue 24 item 3), on the closed quad-grid torus of
// osd_cull/scene/procedural.h (one Bezier patch per face, --floor-grids N: N^2 patches, so
// that the submission's fixed cost is spread thin). The floor is a plain single-threaded C++
// loop doing the kernel's arithmetic per patch on precomputed float data in
// structure-of-arrays layout, writing a result per patch and appending survivors: the
// frustum box test (the box of the control points against the six clip planes, with the
// kernel's margin), the cone test (NCONE: dot(a, E - l) + sin(g) |E - l| < 0 with the
// kernel's margin), box + cone, and the tangent-plane test (bound::tangentPlaneFactored in
// double: the 64 factored coefficients and their signs). Kernel: median wall time of one
// cull submission (as part 1) over --floor-views views x --repeats, and the process's CPU
// time over it (all threads; a loaded machine disturbs it less); "static" rows set
// CullSettings::staticPoints (precomputed boxes instead of control points); floor: median
// of its loop over the same views and repeats, interleaved with the kernels. Also the CullPass
// construction time per patch (frustum + ncone): with its host cones, and reading the cones
// frame::BoundsPass computes on the GPU (its construction and one run included); and the
// load average before and after.
#include "adapters/image_displacement.h"
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/tangent_plane_factored.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/context.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
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
  std::string displacement;                ///< "procedural" or a map file; empty: none
  double displacementScale = 0.64;
  std::vector<uint32_t> breakEvenTess = {1, 2, 4, 8, 16, 32};
  std::vector<std::string> breakEvenMethods = {"frustum", "tcone", "tangent-plane"};
  uint32_t breakEvenViews = 4;
  std::vector<uint32_t> floorGrids = {316, 1000};  ///< part 4's torus grids
  uint32_t floorViews = 3;
  bool validate = false;  ///< Vulkan validation layers; any message fails the run
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
      .text("--displacement", o.displacement)
      .real("--displacement-scale", o.displacementScale, 0.0)
      .numbers("--break-even-tess", o.breakEvenTess)
      .names("--break-even-methods", o.breakEvenMethods)
      .number("--break-even-views", o.breakEvenViews, 1)
      .numbers("--floor-grids", o.floorGrids)
      .number("--floor-views", o.floorViews, 1)
      .flag("--validate", o.validate)
      .parse(argc, argv);
}

using osd_cull::bench::median;

/// One mesh at one isolation level: drawn as it is and, with --displacement, displaced.
struct Scene {
  bench::CullMesh mesh;
  std::vector<glm::dvec2> uvCorners;
  std::optional<bound::DisplacementMap> map;
  std::unique_ptr<frame::GpuPatchSet> gpu, gpuDisplaced;
  std::unique_ptr<frame::GpuDisplacement> displacement;
  std::vector<frame::Camera> cameras;

  Scene(vulkan::Context& context, const Options& o, uint32_t level, uint32_t views)
      : mesh(bench::loadCullMesh(o.mesh, level)) {
    gpu = std::make_unique<frame::GpuPatchSet>(context, mesh.patches);
    if (!o.displacement.empty()) {
      PatchOptions options;
      options.isolationLevel = static_cast<int>(level);
      uvCorners = extractPatches(adapters::loadCage(o.mesh), options).uvCorners;
      adapters::DisplacementOptions d;
      d.source = o.displacement;
      d.scale = o.displacementScale;
      map.emplace(adapters::loadDisplacementMap(d));
      gpuDisplaced = std::make_unique<frame::GpuPatchSet>(context, mesh.patches);
      displacement = std::make_unique<frame::GpuDisplacement>(context, *map, uvCorners,
                                                              mesh.patches.patchCount());
      gpuDisplaced->setDisplacement(displacement.get());
    }
    frame::ViewSetOptions vo;
    vo.count = views;
    vo.width = o.width;
    vo.height = o.height;
    cameras = frame::randomViews(frame::boundsOf(mesh.patches.points), vo);
  }
  uint32_t patches() const { return mesh.patches.patchCount(); }
};

/// What a method or frame-mode name asks for (see the top of this file).
struct Mode {
  std::string name;
  frame::CullSettings settings;          ///< the kernel's stages (part 1: the method alone)
  std::optional<frame::HiZOptions> hiz;  ///< Hi-Z occlusion: the pyramid's options
  bool displaced = false;                ///< a displaced kernel on the displaced mesh
};

Mode parseMode(const std::string& name, const Scene& scene) {
  Mode mode{name, {}, std::nullopt, false};
  frame::CullSettings& s = mode.settings;
  s.backPatchValidity = scene.mesh.validity;
  s.frustum = false;
  std::string method = name;
  const size_t slash = method.find('/');
  const std::string option = slash == std::string::npos ? "" : method.substr(slash + 1);
  method.resize(std::min(slash, method.size()));
  if (method == "hiz") {
    if (option != "" && option != "full" && option != "tight" && option != "full-tight")
      throw Error("'" + name + "': Hi-Z options are /full, /tight, /full-tight");
    mode.hiz = frame::HiZOptions{};
    mode.hiz->fullResolution = option.starts_with("full");
    mode.hiz->lookup =
        option.ends_with("tight") ? bound::HiZLookup::Tight : bound::HiZLookup::Paper;
    s.occlusion = "hiz";
    return mode;
  }
  if (option == "surface")
    s.drawnTriangles = false;
  else if (option == "listed")
    s.drawnEnumerate = true;
  else if (!option.empty())
    throw Error("'" + name + "': the back-patch options are /surface and /listed");
  if ((method == "frustum" || method == "empty") && !option.empty())
    throw Error("'" + name + "': " + method + " takes no option");
  if (method == "frustum" || method == "all") s.frustum = true;
  if (method == "all") s.backPatch = "tangent-plane";
  if (method == "frustum" || method == "all" || method == "empty") return mode;
  const frame::CullMethod& m = frame::cullMethod(method);  // throws for unknown names
  if (m.displaced) {
    if (!scene.map) throw Error("'" + name + "' is a displaced kernel: give --displacement");
    mode.displaced = true;
    mode.hiz = frame::HiZOptions{};
    s.occlusion = method;
    s.displacementMap = &*scene.map;
    s.uvCorners = scene.uvCorners;
    s.displacedKernel = *m.displaced;
    s.backPatchValidity = {false, frame::kDisplacedBackPatchNote};
  } else if (m.stage == frame::CullStage::BackPatch) {
    s.backPatch = method;
  } else {
    throw Error("'" + name + "' is neither a back-patch, Hi-Z nor displaced method");
  }
  return mode;
}

/// The unculled depth of a view and Hi-Z pyramids over it, for the occlusion kernels.
class ViewDepth {
 public:
  ViewDepth(vulkan::Context& context, const Options& o, const Scene& scene, bool displaced)
      : context_(context),
        target_(context, o.width, o.height),
        draw_{displaced ? scene.gpuDisplaced.get() : scene.gpu.get(), &scene.mesh.patches, 0} {
    render_.cullBackFaces = scene.mesh.validity.enabled && !displaced;
  }
  /// The stage set of a pyramid with `options` (made on first use).
  VkDescriptorSet stageSet(const frame::HiZOptions& options) {
    const auto key = std::make_pair(options.fullResolution, options.lookup);
    auto& p = pyramids_[key];
    if (!p.pyramid) {
      p.pyramid = std::make_unique<frame::HiZPyramid>(context_, target_.depth(), options);
      p.stage = std::make_unique<frame::HiZCullStage>(context_, *p.pyramid);
    }
    return p.stage->set();
  }
  /// Draws the view unculled at `tess` and builds every pyramid over its depth.
  void prepare(frame::Renderer& renderer, const frame::Camera& camera, uint32_t tess) {
    if (pyramids_.empty()) return;
    render_.tessellation.uniformLevel = tess;
    renderer.render(target_, camera, {&draw_, 1}, {}, render_);
    for (auto& [key, p] : pyramids_) p.pyramid->build(context_, frame::RenderTarget::kDepthLayout);
  }

 private:
  struct Pyramid {
    std::unique_ptr<frame::HiZPyramid> pyramid;
    std::unique_ptr<frame::HiZCullStage> stage;
  };
  vulkan::Context& context_;
  frame::RenderTarget target_;
  frame::PatchDraw draw_;
  frame::RenderOptions render_;
  std::map<std::pair<bool, bound::HiZLookup>, Pyramid> pyramids_;
};

void kernelCost(vulkan::Context& context, const Options& o) {
  std::printf(
      "\n| level | tess | patches | method | cull rate | ns/patch (median) | ms/pass | compile ms "
      "|\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  frame::Renderer renderer(context);
  for (uint32_t level : o.levels) {
    const Scene scene(context, o, level, o.views);
    const uint32_t n = scene.patches();
    std::vector<Mode> modes;
    for (const std::string& method : o.methods) modes.push_back(parseMode(method, scene));
    ViewDepth depth(context, o, scene, false);
    std::optional<ViewDepth> displacedDepth;
    if (scene.map) displacedDepth.emplace(context, o, scene, true);
    std::vector<std::unique_ptr<frame::CullPass>> passes;
    std::vector<VkDescriptorSet> sets;
    for (const Mode& m : modes) {
      passes.push_back(std::make_unique<frame::CullPass>(
          context, m.displaced ? *scene.gpuDisplaced : *scene.gpu, scene.mesh.patches, m.settings));
      sets.push_back(!m.hiz ? VK_NULL_HANDLE
                            : (m.displaced ? *displacedDepth : depth).stageSet(*m.hiz));
    }
    for (uint32_t tess : o.kernelTess) {
      bench::progress("kernels: level " + std::to_string(level) + ", tess " + std::to_string(tess));
      frame::TessellationOptions tessellation;
      tessellation.uniformLevel = tess;
      auto prepare = [&](const frame::Camera& camera) {
        depth.prepare(renderer, camera, tess);
        if (displacedDepth) displacedDepth->prepare(renderer, camera, tess);
      };
      prepare(scene.cameras[0]);
      std::vector<double> compileMs;
      for (size_t m = 0; m < passes.size(); ++m) {
        const auto start = std::chrono::steady_clock::now();
        passes[m]->run(scene.cameras[0], tessellation, sets[m]);  // first compile (or cache)
        compileMs.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
      }
      std::vector<std::vector<double>> ms(passes.size());
      std::vector<uint64_t> culled(passes.size(), 0);
      for (const auto& camera : scene.cameras) {
        prepare(camera);
        for (uint32_t r = 0; r < o.repeats; ++r)
          for (size_t m = 0; m < passes.size(); ++m) {
            ms[m].push_back(passes[m]->run(camera, tessellation, sets[m]));
            if (r == 0) culled[m] += n - passes[m]->counts().survivors();
          }
      }
      for (size_t m = 0; m < passes.size(); ++m) {
        std::printf("| %u | %u | %u | %s | %.1f%% | %.0f | %.3f | %.0f |\n", level, tess, n,
                    modes[m].name.c_str(),
                    100.0 * double(culled[m]) / double(n) / double(scene.cameras.size()),
                    median(ms[m]) * 1e6 / n, median(ms[m]), compileMs[m]);
      }
      std::fflush(stdout);
    }
  }
}

/// One frame's figures.
struct FrameResult {
  double ms = 0.0;
  double tes = 0.0;    ///< tessellation-evaluation invocations
  double drawn = 0.0;  ///< patches drawn
};

/// A frame mode of part 2: draws a view and says what it cost.
struct FrameMode {
  std::string name;
  size_t baseline = 0;  ///< the index of the unculled mode it is compared with
  std::function<FrameResult(const frame::Camera&)> frame;
};

/// The frame level: the second of --levels when there are several (part 2 and 3).
uint32_t frameLevel(const Options& o) { return o.levels.size() > 1 ? o.levels[1] : o.levels.at(0); }

class FrameBench {
 public:
  FrameBench(vulkan::Context& context, const Options& o, uint32_t views)
      : context_(context),
        o_(o),
        scene_(context, o, frameLevel(o), views),
        renderer_(context),
        target_(context, o.width, o.height) {}

  const Scene& scene() const { return scene_; }
  frame::Renderer& renderer() { return renderer_; }
  frame::RenderTarget& target() { return target_; }

  /// Render options at `tess`: back faces culled by the rasterizer on a closed, oriented,
  /// undisplaced mesh, with and without culling alike.
  frame::RenderOptions renderOptions(uint32_t tess, bool displaced) const {
    frame::RenderOptions options;
    options.tessellation.uniformLevel = tess;
    options.cullBackFaces = scene_.mesh.validity.enabled && !displaced;
    return options;
  }

  /// The unculled frame of the mesh (displaced or not).
  FrameMode unculled(const std::string& name, uint32_t tess, bool displaced) {
    const frame::RenderOptions options = renderOptions(tess, displaced);
    const frame::PatchDraw draw{displaced ? scene_.gpuDisplaced.get() : scene_.gpu.get(),
                                &scene_.mesh.patches, 0};
    return {
        name, 0, [this, options, draw](const frame::Camera& camera) {
          const frame::FrameStats s = renderer_.render(target_, camera, {&draw, 1}, {}, options);
          return FrameResult{s.wallMs, double(s.statistics.tessEvaluationInvocations),
                             double(s.patchesDrawn)};
        }};
  }

  /// A culled frame of `mode` (see the top of this file), its cull pass testing `cullView`
  /// of the frame's camera (the break-even sweep narrows it; identity: the camera itself).
  FrameMode culled(const Mode& mode, uint32_t tess,
                   std::function<frame::Camera(const frame::Camera&)> cullView = {}) {
    const frame::RenderOptions options = renderOptions(tess, mode.displaced);
    // Each mode draws from its own copy of the patches (a GpuPatchSet holds few draw-list
    // descriptor sets).
    sets_.push_back(std::make_unique<frame::GpuPatchSet>(context_, scene_.mesh.patches));
    frame::GpuPatchSet& gpu = *sets_.back();
    if (mode.displaced) gpu.setDisplacement(scene_.displacement.get());
    if (!mode.hiz) {
      passes_.push_back(
          std::make_unique<frame::CullPass>(context_, gpu, scene_.mesh.patches, mode.settings));
      frame::CullPass& pass = *passes_.back();
      return {
          mode.name, 0, [this, &pass, options, cullView](const frame::Camera& camera) {
            const frame::Camera cullCamera = cullView ? cullView(camera) : camera;
            frame::FrameStats s = renderer_.renderWith(
                target_, camera, {}, options,
                [&](VkCommandBuffer cmd) { pass.record(cmd, cullCamera, options.tessellation); },
                [&](VkCommandBuffer cmd) {
                  return pass.recordDraws(cmd, renderer_, camera, options);
                });
            return FrameResult{s.wallMs, double(s.statistics.tessEvaluationInvocations),
                               double(pass.counts().survivors())};
          }};
    }
    // Hi-Z: the two-pass frame with the frustum and occlusion stages.
    frame::CullMesh mesh{&gpu, &scene_.mesh.patches};
    frame::CullFrameOptions fo;
    fo.render = options;
    fo.cull = {true, "", "hiz", scene_.mesh.validity};
    fo.hiz = *mode.hiz;
    if (mode.displaced) {
      mesh.displacementMap = mode.settings.displacementMap;
      mesh.uvCorners = mode.settings.uvCorners;
      mesh.displacedKernel = mode.settings.displacedKernel;
      fo.cull.backPatchValidity = mode.settings.backPatchValidity;
    }
    meshes_.push_back(std::make_unique<frame::CullMesh>(mesh));
    frames_.push_back(std::make_unique<frame::CullFrame>(context_, renderer_, target_,
                                                         std::span(meshes_.back().get(), 1), fo));
    frame::CullFrame& cullFrame = *frames_.back();
    return {mode.name, 0, [&cullFrame](const frame::Camera& camera) {
              cullFrame.render(camera, {});  // this view's visibility
              const frame::CullFrameStats s = cullFrame.render(camera, {});
              return FrameResult{
                  s.frameMs,
                  double(s.pass1.tessEvaluationInvocations + s.pass2.tessEvaluationInvocations),
                  double(s.drawnPass1 + s.drawnPass2)};
            }};
  }

  /// Runs `modes` interleaved (per view and repeat each once) after a warm-up of each.
  std::vector<std::vector<FrameResult>> run(std::vector<FrameMode>& modes,
                                            std::span<const frame::Camera> cameras) {
    for (FrameMode& m : modes) m.frame(cameras[0]);  // warm-up (pipelines)
    std::vector<std::vector<FrameResult>> results(modes.size());
    for (const auto& camera : cameras)
      for (uint32_t r = 0; r < o_.repeats; ++r)
        for (size_t m = 0; m < modes.size(); ++m) results[m].push_back(modes[m].frame(camera));
    return results;
  }

  /// Drops the passes and frames of the last modes (between tessellation levels).
  void clear() {
    frames_.clear();
    meshes_.clear();
    passes_.clear();
    sets_.clear();
  }

 private:
  vulkan::Context& context_;
  const Options& o_;
  Scene scene_;
  frame::Renderer renderer_;
  frame::RenderTarget target_;
  std::vector<std::unique_ptr<frame::GpuPatchSet>> sets_;
  std::vector<std::unique_ptr<frame::CullPass>> passes_;
  std::vector<std::unique_ptr<frame::CullMesh>> meshes_;
  std::vector<std::unique_ptr<frame::CullFrame>> frames_;
};

template <typename F>
std::vector<double> each(const std::vector<FrameResult>& v, F f) {
  std::vector<double> out;
  for (const FrameResult& r : v) out.push_back(f(r));
  return out;
}

void frameSavings(vulkan::Context& context, const Options& o) {
  FrameBench bench(context, o, o.views);
  const Scene& scene = bench.scene();
  std::printf(
      "\nlevel %u, %u patches, %u sphere views, %ux%u, %u repeats; back faces %s in every "
      "row, with and without culling%s\n\n",
      frameLevel(o), scene.patches(), o.views, o.width, o.height, o.repeats,
      scene.mesh.validity.enabled ? "culled by the rasterizer" : "drawn (mesh not closed/oriented)",
      scene.map ? " (displaced rows: drawn, and compared with displaced:none)" : "");
  std::printf(
      "| tess | cull | patches drawn | TES invocations | frame ms (median) | ratio to none |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (uint32_t tess : o.tess) {
    bench::progress("frames: tess " + std::to_string(tess));
    std::vector<FrameMode> modes = {bench.unculled("none", tess, false)};
    std::optional<size_t> displacedNone;
    for (const std::string& name : o.frameModes) {
      const Mode mode = parseMode(name, scene);
      if (mode.displaced && !displacedNone) {
        displacedNone = modes.size();
        modes.push_back(bench.unculled("displaced:none", tess, true));
        modes.back().baseline = *displacedNone;
      }
      modes.push_back(bench.culled(mode, tess));
      modes.back().baseline = mode.displaced ? *displacedNone : 0;
    }
    const auto results = bench.run(modes, scene.cameras);
    for (size_t m = 0; m < modes.size(); ++m) {
      const auto ms = [](const FrameResult& r) { return r.ms; };
      std::printf("| %u | %s | %.0f | %.0f | %.2f | %.2f |\n", tess, modes[m].name.c_str(),
                  median(each(results[m], [](const FrameResult& r) { return r.drawn; })),
                  median(each(results[m], [](const FrameResult& r) { return r.tes; })),
                  median(each(results[m], ms)),
                  median(each(results[m], ms)) / median(each(results[modes[m].baseline], ms)));
    }
    std::fflush(stdout);
    bench.clear();
  }
}

/// Least squares y = a + b x.
std::pair<double, double> fitLine(const std::vector<std::pair<double, double>>& xy) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(xy.size());
  for (const auto& [x, y] : xy) {
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double d = n * sxx - sx * sx;
  if (xy.size() < 2 || d <= 0.0) throw Error("the break-even fit needs two shares");
  const double b = (n * sxy - sx * sy) / d;
  return {(sy - b * sx) / n, b};
}

void breakEven(vulkan::Context& context, const Options& o) {
  FrameBench bench(context, o, o.breakEvenViews);
  const Scene& scene = bench.scene();
  const uint32_t n = scene.patches();
  // Zooms of the cull pass's projection: the frustum keeps the central 1/zoom of the image.
  const std::vector<double> zooms = {1.0, 2.0, 2.6, 3.3, 4.5, 1000.0};
  std::printf(
      "\nbreak-even: level %u, %u patches, %u sphere views, %ux%u, %u repeats; share drawn s "
      "and frame ratio r to the unculled frame of the same view (median of its repeats); "
      "sweep: frustum of a zoomed projection\n\n",
      frameLevel(o), n, o.breakEvenViews, o.width, o.height, o.repeats);
  std::printf("| tess | method | zoom | share drawn | ratio to none | none ms (median) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  std::vector<std::string> summary;
  for (uint32_t tess : o.breakEvenTess) {
    bench::progress("break-even: tess " + std::to_string(tess));
    std::vector<FrameMode> modes = {bench.unculled("none", tess, false)};
    Mode frustum = parseMode("frustum", scene);
    for (double zoom : zooms) {
      modes.push_back(bench.culled(frustum, tess, [zoom](const frame::Camera& c) {
        frame::Camera zoomed = c;
        zoomed.projection = glm::scale(glm::dmat4(1.0), glm::dvec3(zoom, zoom, 1.0)) * c.projection;
        return zoomed;
      }));
    }
    for (const std::string& name : o.breakEvenMethods) {
      Mode m = parseMode(name, scene);
      if (m.hiz || m.settings.occlusion.size())
        throw Error("'" + name + "': the break-even methods are frustum and back-patch methods");
      m.settings.frustum = true;
      modes.push_back(bench.culled(m, tess));
    }
    const auto results = bench.run(modes, scene.cameras);
    // Per view: each frame over the median unculled frame of that view.
    const uint32_t per = o.repeats;
    auto shareAndRatio = [&](size_t m) {
      std::vector<double> s, r;
      for (size_t i = 0; i < results[m].size(); ++i) {
        std::vector<double> none;
        for (size_t j = (i / per) * per; j < (i / per + 1) * per; ++j)
          none.push_back(results[0][j].ms);
        s.push_back(results[m][i].drawn / n);
        r.push_back(results[m][i].ms / median(none));
      }
      return std::make_pair(s, r);
    };
    const double noneMs = median(each(results[0], [](const FrameResult& r) { return r.ms; }));
    std::vector<std::pair<double, double>> sweep;
    for (size_t z = 0; z < zooms.size(); ++z) {
      const auto [s, r] = shareAndRatio(1 + z);
      sweep.push_back({median(s), median(r)});
      std::printf("| %u | frustum | %g | %.3f | %.3f | %.2f |\n", tess, zooms[z], median(s),
                  median(r), noneMs);
    }
    const auto [a, b] = fitLine(sweep);
    char line[256];
    std::snprintf(line, sizeof line, "| %u | frustum sweep | %.2f | %.3f | %.3f | %.1f%% |", tess,
                  noneMs * 1e6 / n, a, b, 100.0 * (a + b - 1.0) / b);
    summary.push_back(line);
    for (size_t k = 0; k < o.breakEvenMethods.size(); ++k) {
      const auto [s, r] = shareAndRatio(1 + zooms.size() + k);
      std::vector<double> intercepts;
      for (size_t i = 0; i < s.size(); ++i) intercepts.push_back(r[i] - b * s[i]);
      const double am = median(intercepts);
      std::printf("| %u | %s | 1 | %.3f | %.3f | %.2f |\n", tess, o.breakEvenMethods[k].c_str(),
                  median(s), median(r), noneMs);
      std::snprintf(line, sizeof line, "| %u | %s | %.2f | %.3f | %.3f | %.1f%% |", tess,
                    o.breakEvenMethods[k].c_str(), noneMs * 1e6 / n, am, b,
                    100.0 * (am + b - 1.0) / b);
      summary.push_back(line);
    }
    std::fflush(stdout);
    bench.clear();
  }
  std::printf("\nbreak-even summary: r = a + b s, x* = (a + b - 1) / b\n\n");
  std::printf(
      "| tess | method | RT ns/patch (unculled frame / patches) | a | b | break-even x* |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const std::string& l : summary) std::printf("%s\n", l.c_str());
  std::fflush(stdout);
}

/// CPU time of the process in ms (every thread: lavapipe's workers too), which a loaded
/// machine disturbs much less than wall time.
double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

/// Part 4's per-patch data, float, structure of arrays: the box of the control points (the
/// kernel's own, frame::packPatchBoxes) and the NCONE cone (what the floors read).
struct FloorData {
  std::vector<float> box[6];  ///< min x, y, z, max x, y, z
  std::vector<float> apex[3], axis[3], sinAngle;
  std::vector<uint8_t> coneValid;
};

FloorData floorData(const PatchSet& set, std::span<const bound::ConeOfNormals> cones) {
  FloorData d;
  const uint32_t n = set.patchCount();
  for (auto& v : d.box) v.resize(n);
  for (int c = 0; c < 3; ++c) {
    d.apex[c].resize(n);
    d.axis[c].resize(n);
  }
  d.sinAngle.resize(n);
  d.coneValid.resize(n);
  const std::vector<float> boxes = frame::packPatchBoxes(set);  // what the kernel reads
  for (uint32_t p = 0; p < n; ++p) {
    for (size_t c = 0; c < 6; ++c) d.box[c][p] = boxes[c * n + p];
    for (int c = 0; c < 3; ++c) {
      d.apex[c][p] = float(cones[p].apex[c]);
      d.axis[c][p] = float(cones[p].axis[c]);
    }
    d.sinAngle[p] = float(cones[p].sinAngle);
    d.coneValid[p] = cones[p].valid ? 1 : 0;
  }
  return d;
}

/// The floor loops: results[p] and the appended survivors, as the kernel writes them.
class FloorLoops {
 public:
  FloorLoops(const PatchSet& set, const FloorData& d)
      : set_(set), d_(d), results_(set.patchCount()), list_(set.patchCount()) {}

  /// Frustum: the box against the six planes of `viewProj` (p . (x, 1) >= 0 inside), culled
  /// when the box's largest value is below -margin times its magnitude.
  double frustum(const glm::mat4& viewProj) {
    return time([&] { run(viewProj, false, {}); });
  }
  /// NCONE: the cone test alone.
  double cone(const glm::vec3& eye) {
    return time([&] { runCone(eye); });
  }
  /// Box, then cone for the patches inside.
  double frustumCone(const glm::mat4& viewProj, const glm::vec3& eye) {
    return time([&] { run(viewProj, true, eye); });
  }
  /// Tangent plane: the 64 factored coefficients (double) and their signs per Bezier patch.
  double tangentPlane(const glm::dvec3& eye) {
    return time([&] {
      uint32_t count = 0;
      for (uint32_t p = 0; p < set_.bezierCount; ++p) {
        const bound::TangentPlaneFactored f =
            bound::tangentPlaneFactored(set_.controlPoints(p), eye);
        bool positive = false;
        for (int i = 0; i < 64; ++i) positive = positive || f.d[i] + f.bound[i] > 0.0;
        results_[p] = positive ? 1u : 0u;
        if (positive) list_[count++] = p;
      }
      survivors_ = count;
    });
  }
  uint32_t survivors() const { return survivors_; }

 private:
  template <typename F>
  double time(F f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  }
  bool coneCulls(uint32_t p, const glm::vec3& e, float eyeLength) const {
    const float dx = e.x - d_.apex[0][p], dy = e.y - d_.apex[1][p], dz = e.z - d_.apex[2][p];
    const float lhs = d_.axis[0][p] * dx + d_.axis[1][p] * dy + d_.axis[2][p] * dz +
                      d_.sinAngle[p] * std::sqrt(dx * dx + dy * dy + dz * dz);
    const float apexLength =
        std::sqrt(d_.apex[0][p] * d_.apex[0][p] + d_.apex[1][p] * d_.apex[1][p] +
                  d_.apex[2][p] * d_.apex[2][p]);
    return d_.coneValid[p] && lhs < -shader::kCullRelativeMargin * (eyeLength + apexLength);
  }
  void runCone(const glm::vec3& e) {
    const uint32_t n = set_.patchCount();
    const float eyeLength = glm::length(e);
    uint32_t count = 0;
    for (uint32_t p = 0; p < n; ++p) {
      const bool culled = coneCulls(p, e, eyeLength);
      results_[p] = culled ? 2u : 0u;
      if (!culled) list_[count++] = p;
    }
    survivors_ = count;
  }
  void run(const glm::mat4& m, bool withCone, const glm::vec3& e) {
    // Plane k: row combination of the matrix (x + w, w - x, y + w, w - y, z, w - z).
    const glm::mat4 t = glm::transpose(m);  // t[r] = row r
    const glm::vec4 planes[6] = {t[3] + t[0], t[3] - t[0], t[3] + t[1],
                                 t[3] - t[1], t[2],        t[3] - t[2]};
    glm::vec4 absPlanes[6];
    for (int k = 0; k < 6; ++k) absPlanes[k] = glm::abs(planes[k]);
    const float eyeLength = glm::length(e);
    const uint32_t n = set_.patchCount();
    uint32_t count = 0;
    for (uint32_t p = 0; p < n; ++p) {
      const float cx = 0.5f * (d_.box[0][p] + d_.box[3][p]),
                  ex = 0.5f * (d_.box[3][p] - d_.box[0][p]);
      const float cy = 0.5f * (d_.box[1][p] + d_.box[4][p]),
                  ey = 0.5f * (d_.box[4][p] - d_.box[1][p]);
      const float cz = 0.5f * (d_.box[2][p] + d_.box[5][p]),
                  ez = 0.5f * (d_.box[5][p] - d_.box[2][p]);
      uint32_t code = 6;
      for (uint32_t k = 0; k < 6; ++k) {
        const glm::vec4& q = planes[k];
        const glm::vec4& a = absPlanes[k];
        const float reach = a.x * ex + a.y * ey + a.z * ez;
        const float top = q.x * cx + q.y * cy + q.z * cz + q.w + reach;
        const float mag =
            a.x * std::abs(cx) + a.y * std::abs(cy) + a.z * std::abs(cz) + a.w + reach;
        if (top < -shader::kCullRelativeMargin * mag) {
          code = k;
          break;
        }
      }
      bool culled = code < 6;
      if (!culled && withCone) culled = coneCulls(p, e, eyeLength);
      results_[p] = culled ? code : 6u;
      if (!culled) list_[count++] = p;
    }
    survivors_ = count;
  }
  const PatchSet& set_;
  const FloorData& d_;
  std::vector<uint32_t> results_, list_;
  uint32_t survivors_ = 0;
};

// A kernel of the floors table and its floor loop (nullptr: none), with their samples.
struct FloorRow {
  std::string kernel, floor;
  std::unique_ptr<frame::CullPass> pass;
  std::function<double(const frame::Camera&)> floorMs;
  std::vector<double> ms, cpuMs, floorSamples, floorCpuMs;
  uint64_t culled = 0;
};

// Every kernel, then its floor loop, per camera and repeat (interleaved); the culls of the
// first repeat of each camera.
void measureFloorRows(std::vector<FloorRow>& rows, const std::vector<frame::Camera>& cameras,
                      const frame::TessellationOptions& tessellation, uint32_t repeats,
                      uint32_t n) {
  for (FloorRow& r : rows) r.pass->run(cameras[0], tessellation);  // compile (or cache)
  for (const frame::Camera& camera : cameras)
    for (uint32_t rep = 0; rep < repeats; ++rep)
      for (FloorRow& r : rows) {
        double cpu = processCpuMs();
        r.ms.push_back(r.pass->run(camera, tessellation));
        r.cpuMs.push_back(processCpuMs() - cpu);
        if (rep == 0) r.culled += n - r.pass->counts().survivors();
        if (!r.floorMs) continue;
        cpu = processCpuMs();
        r.floorSamples.push_back(r.floorMs(camera));
        r.floorCpuMs.push_back(processCpuMs() - cpu);
      }
}

// The floors table: per kernel its ns/patch, its floor's and their ratio (GPU and CPU time),
// construction cost where timed, and the tangent plane / ncone ratios.
void printFloorRows(const std::vector<FloorRow>& rows, uint32_t n, size_t views,
                    double constructionMs, double gpuConstructionMs) {
  auto nsPerPatch = [&](const std::vector<double>& ms) { return median(ms) * 1e6 / n; };
  for (const FloorRow& r : rows) {
    const double kernel = nsPerPatch(r.ms);
    const double rate = 100.0 * double(r.culled) / double(n) / double(views);
    const double kernelCpu = nsPerPatch(r.cpuMs);
    char floorNs[32] = "-", ratio[32] = "-", floorCpu[32] = "-", cpuRatio[32] = "-", build[32] = "";
    if (!r.floorSamples.empty()) {
      std::snprintf(floorNs, sizeof floorNs, "%.2f", nsPerPatch(r.floorSamples));
      std::snprintf(ratio, sizeof ratio, "%.1f", kernel / nsPerPatch(r.floorSamples));
      std::snprintf(floorCpu, sizeof floorCpu, "%.2f", nsPerPatch(r.floorCpuMs));
      std::snprintf(cpuRatio, sizeof cpuRatio, "%.1f", kernelCpu / nsPerPatch(r.floorCpuMs));
    }
    if (r.kernel == "frustum + ncone/surface")
      std::snprintf(build, sizeof build, "%.2f (host cones)", constructionMs * 1e3 / n);
    if (r.kernel == "frustum + ncone/surface, GPU cones")
      std::snprintf(build, sizeof build, "%.2f (bounds pass)", gpuConstructionMs * 1e3 / n);
    std::printf("| %u | %s | %.1f%% | %.1f | %s | %s | %s | %.1f | %s | %s | %s |\n", n,
                r.kernel.c_str(), rate, kernel, r.floor.c_str(), floorNs, ratio, kernelCpu,
                floorCpu, cpuRatio, build);
  }
  auto kernelOf = [&](const std::string& name, bool cpu) {
    for (const FloorRow& r : rows)
      if (r.kernel == name) return nsPerPatch(cpu ? r.cpuMs : r.ms);
    return 0.0;
  };
  std::printf(
      "| %u | tangent plane / ncone | | %.1f (surface), %.1f (drawn) | | | | %.1f (surface), "
      "%.1f (drawn) | | | |\n",
      n, kernelOf("tangent-plane/surface", false) / kernelOf("ncone/surface", false),
      kernelOf("tangent-plane", false) / kernelOf("ncone", false),
      kernelOf("tangent-plane/surface", true) / kernelOf("ncone/surface", true),
      kernelOf("tangent-plane", true) / kernelOf("ncone", true));
  std::fflush(stdout);
}

void kernelFloors(vulkan::Context& context, const Options& o) {
  std::printf("\nkernels against their floors (%s at the start)\n\n",
              bench::machineState().c_str());
  std::printf(
      "| patches | kernel | cull rate | kernel ns/patch | floor | floor ns/patch | ratio | kernel "
      "CPU ns/patch | floor CPU ns/patch | CPU ratio | CullPass us/patch |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (uint32_t grid : o.floorGrids) {
    bench::progress("floors: grid " + std::to_string(grid));
    PatchOptions po;
    po.isolationLevel = 1;
    const PatchExtraction ex = extractPatches(scene::torus(int(grid), int(grid), 1.0, 0.4), po);
    const PatchSet& set = ex.patches;
    const uint32_t n = set.patchCount();
    frame::GpuPatchSet gpu(context, set);
    const bound::BackPatchValidity closed{true, "closed torus"};
    auto settings = [&](bool frustum, const std::string& backPatch, bool drawn,
                        bool staticPoints = false) {
      return frame::CullSettings{.frustum = frustum,
                                 .backPatch = backPatch,
                                 .backPatchValidity = closed,
                                 .drawnTriangles = drawn,
                                 .staticPoints = staticPoints};
    };
    // Construction first, timed: frustum + ncone builds the host cones.
    const auto start = std::chrono::steady_clock::now();
    auto ncone =
        std::make_unique<frame::CullPass>(context, gpu, set, settings(true, "ncone", false));
    const double constructionMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // The same pass reading cones the bounds pass computes on the GPU (as a deforming mesh
    // does, DynamicPatchMesh): construction without the host cones.
    const auto gpuStart = std::chrono::steady_clock::now();
    frame::BoundsPass bounds(context, gpu, bound::BackPatchMethod::NCone);
    double maxAbs = 0.0;
    for (const glm::dvec3& q : set.points)
      maxAbs = std::max({maxAbs, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
    bounds.run(1.01 * std::ldexp(1.0, -24) * maxAbs);  // the float points' error
    auto nconeGpuCones = std::make_unique<frame::CullPass>(
        context, gpu, set, settings(true, "ncone", false), bounds.cullData());
    const double gpuConstructionMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - gpuStart)
            .count();
    const FloorData data = floorData(set, ncone->cones());
    FloorLoops floors(set, data);
    auto eyeOf = [](const frame::Camera& c) {
      return bound::makeCullView(c.viewProjection()).eye.value_or(glm::dvec3(0.0));
    };
    auto viewProj = [](const frame::Camera& c) { return glm::mat4(c.viewProjection()); };
    std::vector<FloorRow> rows;
    auto add = [&](const std::string& kernel, std::unique_ptr<frame::CullPass> pass,
                   const std::string& floor, std::function<double(const frame::Camera&)> f) {
      rows.push_back({kernel, floor, std::move(pass), std::move(f), {}, {}, {}, {}, 0});
    };
    auto pass = [&](bool frustum, const std::string& backPatch, bool drawn,
                    bool staticPoints = false) {
      return std::make_unique<frame::CullPass>(context, gpu, set,
                                               settings(frustum, backPatch, drawn, staticPoints));
    };
    add("empty", pass(false, "", false), "-", nullptr);
    add("frustum", pass(true, "", false), "box",
        [&](const frame::Camera& c) { return floors.frustum(viewProj(c)); });
    add("frustum/static", pass(true, "", false, true), "box",
        [&](const frame::Camera& c) { return floors.frustum(viewProj(c)); });
    add("ncone/surface", pass(false, "ncone", false), "cone",
        [&](const frame::Camera& c) { return floors.cone(glm::vec3(eyeOf(c))); });
    add("frustum + ncone/surface", std::move(ncone), "box + cone", [&](const frame::Camera& c) {
      return floors.frustumCone(viewProj(c), glm::vec3(eyeOf(c)));
    });
    add("frustum + ncone/surface, GPU cones", std::move(nconeGpuCones), "box + cone",
        [&](const frame::Camera& c) {
          return floors.frustumCone(viewProj(c), glm::vec3(eyeOf(c)));
        });
    add("frustum + ncone/surface, static", pass(true, "ncone", false, true), "box + cone",
        [&](const frame::Camera& c) {
          return floors.frustumCone(viewProj(c), glm::vec3(eyeOf(c)));
        });
    add("ncone", pass(false, "ncone", true), "cone",
        [&](const frame::Camera& c) { return floors.cone(glm::vec3(eyeOf(c))); });
    add("ncone/static", pass(false, "ncone", true, true), "cone",
        [&](const frame::Camera& c) { return floors.cone(glm::vec3(eyeOf(c))); });
    add("tangent-plane/surface", pass(false, "tangent-plane", false), "tangent plane",
        [&](const frame::Camera& c) { return floors.tangentPlane(eyeOf(c)); });
    add("tangent-plane", pass(false, "tangent-plane", true), "tangent plane", nullptr);
    frame::ViewSetOptions vo;
    vo.count = o.floorViews;
    vo.width = o.width;
    vo.height = o.height;
    const auto cameras = frame::randomViews(frame::boundsOf(set.points), vo);
    frame::TessellationOptions tessellation;
    tessellation.uniformLevel = o.kernelTess.at(0);
    measureFloorRows(rows, cameras, tessellation, o.repeats, n);
    printFloorRows(rows, n, cameras.size(), constructionMs, gpuConstructionMs);
    std::fflush(stdout);
  }
  std::printf("\n(%s at the end)\n", bench::machineState().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-cull", [&] {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    vulkan::ContextOptions co = bench::contextOptions(o.device);
    co.validation = o.validate;
    vulkan::Context context(co);
    std::printf("bench-cull: %s on %s\n", o.mesh.c_str(), context.info().name.c_str());
    if (o.parts.find('1') != std::string::npos) kernelCost(context, o);
    if (o.parts.find('2') != std::string::npos) frameSavings(context, o);
    if (o.parts.find('3') != std::string::npos) breakEven(context, o);
    if (o.parts.find('4') != std::string::npos) kernelFloors(context, o);
    if (context.validationLog() && context.validationLog()->count() > 0)
      throw Error("Vulkan validation messages:\n" + context.validationLog()->summary());
    return 0;
  });
}
