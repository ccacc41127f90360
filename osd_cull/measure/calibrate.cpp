#include "osd_cull/measure/calibrate.h"

#include "osd_cull/bound/back_patch.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/plan/cost_model.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/version.h"
#include "osd_cull/vk/context.h"

#include <osd_cull/shared/cull_layout.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <span>

namespace osd_cull::measure {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double timed(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// Samples named by what they measure; each repeat adds one value to every name.
using Samples = std::map<std::string, std::vector<double>>;

// The built-in torus (scene::torus) with its natural texture coordinates (the angles around
// the ring and around the tube over [0, 1]), the calibration mesh of the displaced draw and
// kernels; the procedural map repeats with period 1, so it is seamless on it.
PatchExtraction uvTorus(int u, int v) {
  CageMesh cage = scene::torus(u, v);
  for (int i = 0; i <= u; ++i)
    for (int j = 0; j <= v; ++j) cage.uvs.emplace_back(double(i) / u, double(j) / v);
  auto uv = [&](int i, int j) { return i * (v + 1) + j; };
  for (int i = 0; i < u; ++i)  // the faces' order and corners are scene::torus's
    for (int j = 0; j < v; ++j)
      cage.faceUVs.insert(cage.faceUVs.end(),
                          {uv(i, j), uv(i + 1, j), uv(i + 1, j + 1), uv(i, j + 1)});
  return extractPatches(cage);
}

// The patches of a drawn-triangle bound pass on which the listed test would run: those
// whose back-patch verdict is DrawnTriangles (the surface faces away, but a drawn triangle
// may not; shaders/cull/cull_main.glsl).
uint32_t listedTestRuns(std::span<const uint32_t> results) {
  return uint32_t(std::count_if(results.begin(), results.end(), [](uint32_t r) {
    return ((r >> shader::kResultShiftBackPatch) & 0xFFu) ==
           uint32_t(bound::BackPatchVerdict::DrawnTriangles);
  }));
}

}  // namespace

CalibrationKey calibrationKey(const vulkan::Context& context) {
  return {context.info().name, context.info().driver, libraryVersion()};
}

Calibration calibrate(vulkan::Context& context, const CalibrateOptions& o) {
  auto progress = [&](const std::string& line) {
    if (o.progress) o.progress(line);
  };
  Calibration c;
  c.key = calibrationKey(context);
  c.quick = o.quick;
  c.repeats = o.repeats ? o.repeats : (o.quick ? 3 : 7);
  const uint32_t width = o.quick ? 640 : 1280, height = o.quick ? 360 : 720;
  const std::vector<uint32_t> levels = o.quick ? std::vector<uint32_t>{1, 4, 8, 16, 32}
                                               : std::vector<uint32_t>{1, 2, 4, 8, 12, 16, 24, 32};

  // The calibration mesh: a closed sphere of Bézier patches filling most of the view, and
  // the same patches as Gregory patches; a six-patch sphere for the fixed dispatch cost.
  const PatchSet sphere = scene::bezierSphere({0, 0, 0}, 1.0, o.quick ? 10 : 16);
  const PatchSet gregory = scene::convertToGregory(sphere, [](uint32_t) { return true; });
  const PatchSet tiny = scene::bezierSphere({0, 0, 0}, 1.0, 1);
  // Culling costs a fraction of a microsecond per patch: measured on a finer sphere, so
  // that the differences between kernels stand above the submission's noise.
  const PatchSet many = scene::bezierSphere({0, 0, 0}, 1.0, o.quick ? 24 : 40);
  c.patches = sphere.patchCount();
  const double n = c.patches, nMany = many.patchCount();
  frame::GpuPatchSet gpu(context, sphere), gpuGregory(context, gregory), gpuTiny(context, tiny),
      gpuMany(context, many);
  frame::Renderer renderer(context);
  frame::RenderTarget target(context, width, height), small(context, width / 2, height / 2);
  const frame::Bounds bounds = frame::boundsOf(sphere.points);
  const frame::Camera camera =
      frame::frameBounds(bounds, {0.3, 0.4, 1.0}, {0, 1, 0}, 40.0, width, height);
  const frame::Camera smallCamera =
      frame::frameBounds(bounds, {0.3, 0.4, 1.0}, {0, 1, 0}, 40.0, width / 2, height / 2);
  // From the centre: every patch faces away (the rasterizer discards its triangles).
  const frame::Camera inside =
      frame::Camera::lookAt({0, 0, 0}, {0.3, 0.4, 1.0}, {0, 1, 0}, 90.0, width, height, 0.01, 10.0);
  // Looking away: every patch is culled by the frustum (for RT0).
  const frame::Camera away = frame::Camera::lookAt(camera.eye(), camera.eye() * 2.0, {0, 1, 0},
                                                   40.0, width, height, 0.1, 100.0);
  frame::RenderOptions render;
  render.cullBackFaces = true;  // like for like: what culled and unculled frames both do
  render.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  const bound::BackPatchValidity closed{true, "calibration sphere: closed, outward"};

  // Cull passes: frustum alone, frustum + each back-patch method, and on the tiny mesh.
  progress("building cull passes");
  std::map<std::string, std::unique_ptr<frame::CullPass>> passes, surfacePasses;
  // The listed-triangle test costs per patch about what drawing it costs (it lists the
  // level's triangles): measured on a coarse sphere, against the bound kernel at each level.
  const PatchSet listedSphere = scene::bezierSphere({0, 0, 0}, 1.0, o.quick ? 6 : 10);
  frame::GpuPatchSet gpuListed(context, listedSphere);
  const std::vector<uint32_t> listedLevels =
      o.quick ? std::vector<uint32_t>{2, 8, 16} : std::vector<uint32_t>{1, 2, 4, 8, 16, 32};
  std::map<std::string,
           std::pair<std::unique_ptr<frame::CullPass>, std::unique_ptr<frame::CullPass>>>
      listedPasses;                            // bound, listed
  std::map<std::string, uint32_t> listedRuns;  // "method level": patches reaching the test
  passes["frustum"] = std::make_unique<frame::CullPass>(context, gpuMany, many,
                                                        frame::CullSettings{true, "", "", closed});
  for (const std::string& m : frame::cullMethodNames(frame::CullStage::BackPatch)) {
    // The fp64 kernels are study variants (docs/results/accuracy-vs-time.md), not plan
    // candidates: the planner only considers calibrated methods.
    if (frame::cullMethod(m).needsFloat64) continue;
    passes[m] = std::make_unique<frame::CullPass>(context, gpuMany, many,
                                                  frame::CullSettings{true, m, "", closed});
    frame::CullSettings surface{true, m, "", closed};
    surface.drawnTriangles = false;  // the papers' surface-exact test
    surfacePasses[m] = std::make_unique<frame::CullPass>(context, gpuMany, many, surface);
    if (frame::cullMethod(m).lanesPerPatch > 1) continue;  // the study lists one-thread kernels
    frame::CullSettings listed{true, m, "", closed};
    listed.drawnEnumerate = true;
    listedPasses[m] = {std::make_unique<frame::CullPass>(context, gpuListed, listedSphere,
                                                         frame::CullSettings{true, m, "", closed}),
                       std::make_unique<frame::CullPass>(context, gpuListed, listedSphere, listed)};
  }
  frame::CullPass tinyPass(context, gpuTiny, tiny, frame::CullSettings{true, "", "", closed});
  // Two-pass frames: the diagnostic mode times the pyramid and the cull (Hi-Z stage
  // included) at two image sizes; tess-factor-0 and filtered frames looking away give RT0.
  const frame::CullMesh meshes[] = {{&gpuMany, &many}};
  frame::CullFrameOptions fo;
  fo.render = render;
  fo.render.tessellation.uniformLevel = 1;
  fo.cull = {true, "", "hiz", closed};
  fo.timePasses = true;
  frame::CullFrame diagnostic(context, renderer, target, meshes, fo);
  frame::CullFrame diagnosticSmall(context, renderer, small, meshes, fo);
  fo.hiz.lookup = bound::HiZLookup::Tight;  // the tight lookup's CT against the paper's
  frame::CullFrame diagnosticTight(context, renderer, target, meshes, fo);
  fo.hiz.lookup = bound::HiZLookup::Paper;
  fo.timePasses = false;
  frame::CullFrame filtered(context, renderer, target, meshes, fo);
  fo.drawMode = frame::CullDrawMode::TessFactorZero;
  frame::CullFrame factorZero(context, renderer, target, meshes, fo);

  // Point updates and the bounds pass on a deforming torus cage.
  progress("building point updates");
  const CageMesh cage = scene::torus(24, 16);
  frame::DynamicPatchMesh cpuMesh(context, cage, {}, frame::PointUpdatePath::Cpu);
  frame::DynamicPatchMesh gpuMesh(context, cage, {}, frame::PointUpdatePath::Gpu);
  cpuMesh.cullData(bound::BackPatchMethod::TCone);
  const double cagePatches = cpuMesh.gpu().patchCount();
  // The bounds pass of each back-patch method on its own (each writes other cull data).
  std::map<std::string, std::unique_ptr<frame::BoundsPass>> boundsPasses;
  for (const std::string& m : frame::cullMethodNames(frame::CullStage::BackPatch)) {
    const frame::CullMethod& method = frame::cullMethod(m);
    if (method.needsFloat64 || method.lanesPerPatch > 1 ||
        !frame::BoundsPass::hasCullData(method.reference))
      continue;  // shares the pass of its fp32 / one-thread method (Calibration::boundsMs)
    boundsPasses[m] = std::make_unique<frame::BoundsPass>(context, gpuMesh.gpu(), method.reference);
  }
  // The displaced bounds passes (issue 10): the ACoN and CoN cones of a displaced mesh's
  // moved points, per frame; the Full extension needs only the static ranges. The ranges'
  // values do not change the work: a constant one.
  const std::vector<bound::DisplacementRange> ranges(gpuMesh.gpu().patchCount(), {-0.01, 0.01});
  for (const bound::DisplacedExtension extension :
       {bound::DisplacedExtension::ACoN, bound::DisplacedExtension::CoN})
    boundsPasses[bound::toString(extension)] =
        std::make_unique<frame::BoundsPass>(context, gpuMesh.gpu(), extension, ranges);
  std::vector<glm::dvec3> moved(cage.positions.begin(), cage.positions.end());

  // Displaced meshes: the displaced draw RT(tf) against the undisplaced one on the UV torus
  // (the displacement lookup in the evaluation stage), and the six displaced kernels against
  // the frustum kernel on a finer one (the displaced bound's extra cost).
  progress("building displaced draws and kernels");
  const PatchExtraction torusDraw = uvTorus(o.quick ? 24 : 48, o.quick ? 12 : 24);
  const PatchExtraction torusCull = uvTorus(o.quick ? 64 : 96, o.quick ? 32 : 48);
  const bound::DisplacementMap map("procedural", 256, 256, scene::proceduralDisplacementTexels(256),
                                   0.04, 0.5);
  frame::GpuPatchSet gpuTorus(context, torusDraw.patches),
      gpuTorusDisplaced(context, torusDraw.patches), gpuTorusCull(context, torusCull.patches);
  frame::GpuDisplacement displacement(context, map, torusDraw.uvCorners,
                                      torusDraw.patches.patchCount());
  gpuTorusDisplaced.setDisplacement(&displacement);
  const double nTorusCull = torusCull.patches.patchCount();
  const frame::Camera torusCamera = frame::frameBounds(
      frame::boundsOf(torusDraw.patches.points), {0.3, 0.4, 1.0}, {0, 1, 0}, 40.0, width, height);
  const frame::PatchDraw torusPlain{&gpuTorus, &torusDraw.patches, 0},
      torusDisplaced{&gpuTorusDisplaced, &torusDraw.patches, 0};
  const bound::BackPatchValidity torusClosed{true, "calibration torus: closed, outward"};
  frame::CullPass torusFrustum(context, gpuTorusCull, torusCull.patches,
                               frame::CullSettings{true, "", "", torusClosed});
  std::map<std::string, std::unique_ptr<frame::CullPass>> displacedPasses;
  for (const frame::CullMethod& m : frame::displacedCullMethods()) {
    frame::CullSettings ds{true, "", "", torusClosed};
    ds.displacementMap = &map;
    ds.uvCorners = torusCull.uvCorners;
    ds.displacedKernel = *m.displaced;
    displacedPasses[m.name] =
        std::make_unique<frame::CullPass>(context, gpuTorusCull, torusCull.patches, ds);
  }

  Samples s;
  std::vector<std::pair<uint32_t, double>> tes;
  // Standalone pyramids over the two targets' depth (built again and again below).
  frame::HiZPyramid pyramid(context, target.depth()), pyramidSmall(context, small.depth());
  frame::HiZOptions fullResolution;
  fullResolution.fullResolution = true;
  frame::HiZPyramid pyramidFull(context, target.depth(), fullResolution);
  const frame::PatchDraw draw{&gpu, &sphere, 0}, drawGregory{&gpuGregory, &gregory, 0};
  // Each sample is a difference of two submissions made back to back (paired), so that the
  // load of other processes, which changes over seconds, cancels; the cheap ones are
  // sampled `sub` times per repeat.
  const uint32_t sub = 5;
  for (uint32_t r = 0; r <= c.repeats; ++r) {  // repeat 0 warms up (pipelines, caches)
    progress("repeat " + std::to_string(r) + " of " + std::to_string(c.repeats));
    Samples one;
    render.tessellation.uniformLevel = 1;
    const double empty = renderer.render(target, camera, {}, {}, render).wallMs;
    one["frame"].push_back(empty);
    for (uint32_t level : levels) {
      render.tessellation.uniformLevel = level;
      const frame::FrameStats st = renderer.render(target, camera, {&draw, 1}, {}, render);
      one["draw " + std::to_string(level)].push_back(
          st.wallMs - renderer.render(target, camera, {}, {}, render).wallMs);
      one["back " + std::to_string(level)].push_back(
          renderer.render(target, inside, {&draw, 1}, {}, render).wallMs -
          renderer.render(target, inside, {}, {}, render).wallMs);
      if (r == 0) tes.push_back({level, double(st.statistics.tessEvaluationInvocations) / n});
    }
    for (uint32_t level : levels) {
      render.tessellation.uniformLevel = level;
      one["torus " + std::to_string(level)].push_back(
          renderer.render(target, torusCamera, {&torusPlain, 1}, {}, render).wallMs);
      one["displaced " + std::to_string(level)].push_back(
          renderer.render(target, torusCamera, {&torusDisplaced, 1}, {}, render).wallMs);
    }
    render.tessellation.uniformLevel = 8;
    const double bezier8 = renderer.render(target, camera, {&draw, 1}, {}, render).wallMs;
    one["gregory 8"].push_back(
        renderer.render(target, camera, {&drawGregory, 1}, {}, render).wallMs / bezier8);
    double frustum = 0.0;
    for (uint32_t k = 0; k < sub; ++k) {
      const double submit = timed([&] { context.submit([](VkCommandBuffer) {}); });
      const double tinyMs = tinyPass.run(camera, render.tessellation);
      one["dispatch"].push_back(tinyMs - submit);
      frustum = passes.at("frustum")->run(camera, render.tessellation);
      one["cull frustum"].push_back(frustum - tinyMs);
      for (auto& [name, pass] : passes)
        if (name != "frustum")
          one["cull " + name].push_back(pass->run(camera, render.tessellation) - frustum);
      for (auto& [name, pass] : surfacePasses)
        one["cull surface " + name].push_back(pass->run(camera, render.tessellation) - frustum);
      const double torusMs = torusFrustum.run(torusCamera, render.tessellation);
      for (auto& [name, pass] : displacedPasses)
        one["cull displaced " + name].push_back(pass->run(torusCamera, render.tessellation) -
                                                torusMs);
      one["hiz build"].push_back(
          timed([&] { pyramid.build(context, frame::RenderTarget::kDepthLayout); }));
      one["hiz build full"].push_back(
          timed([&] { pyramidFull.build(context, frame::RenderTarget::kDepthLayout); }));
      one["hiz build small"].push_back(
          timed([&] { pyramidSmall.build(context, frame::RenderTarget::kDepthLayout); }));
    }
    for (uint32_t level : listedLevels) {
      frame::TessellationOptions tess = render.tessellation;
      tess.uniformLevel = level;
      for (auto& [name, pair] : listedPasses) {
        const std::string key = name + " " + std::to_string(level);
        const double listedMs = pair.second->run(camera, tess);
        const double boundMs = pair.first->run(camera, tess);
        one["cull listed " + key].push_back(listedMs - boundMs);
        listedRuns[key] = listedTestRuns(pair.first->results());
      }
    }
    const double paperCull = diagnostic.render(camera, {}).cullMs;
    one["hiz cull"].push_back(paperCull - frustum);
    one["hiz tight"].push_back(diagnosticTight.render(camera, {}).cullMs - paperCull);
    diagnosticSmall.render(smallCamera, {});
    one["away tf0"].push_back(factorZero.render(away, {}).frameMs -
                              filtered.render(away, {}).frameMs);
    for (glm::dvec3& p : moved) p *= r % 2 ? 1.001 : 1.0 / 1.001;
    cpuMesh.setCagePositions(moved);
    cpuMesh.update();
    gpuMesh.setCagePositions(moved);
    gpuMesh.update();
    one["points cpu"].push_back(cpuMesh.lastTimes().pointsMs);
    one["bounds"].push_back(cpuMesh.lastTimes().boundsMs);
    one["points gpu"].push_back(gpuMesh.lastTimes().pointsMs);
    const double submit = timed([&] { context.submit([](VkCommandBuffer) {}); });
    for (auto& [name, pass] : boundsPasses)
      one["bounds " + name].push_back(pass->run(0.0) - submit);
    if (r == 0) continue;
    for (auto& [name, v] : one) s[name].insert(s[name].end(), v.begin(), v.end());
  }

  // Medians; a paired difference below zero (noise) counts as zero cost.
  auto m = [&](const std::string& name) { return std::max(0.0, median(s.at(name))); };
  c.submitMs = m("frame");
  for (const auto& [level, tesPerPatch] : tes)
    c.draw.push_back({level, m("draw " + std::to_string(level)) / n, tesPerPatch,
                      m("back " + std::to_string(level)) / n});
  c.gregoryDrawFactor = m("gregory 8");
  // Each frame looking away draws every patch twice (both passes) with factor 0.
  c.drawZeroMsPerPatch = m("away tf0") / (2.0 * nMany);
  c.cullDispatchMs = m("dispatch");
  for (const auto& [name, pass] : passes) c.cullMsPerPatch[name] = m("cull " + name) / nMany;
  c.cullMsPerPatch["hiz"] = m("hiz cull") / nMany;
  for (const auto& [name, pass] : surfacePasses)
    c.surfaceCullMsPerPatch[name] = m("cull surface " + name) / nMany;
  // Per patch the listed test runs on: its cost on a mesh is this times the share of the
  // mesh's patches that reach it (CullRates::listedRuns), which differs from mesh to mesh
  // (on the smooth calibration sphere the bound culls nearly every back-facing patch; on a
  // character a fifth of all patches reach the listed test).
  for (const auto& [name, pair] : listedPasses)
    for (uint32_t level : listedLevels) {
      const std::string key = name + " " + std::to_string(level);
      c.listedCullMsPerPatch[name].push_back(
          {level, m("cull listed " + key) / std::max(1.0, double(listedRuns[key]))});
    }
  // A displaced kernel is the Hi-Z stage on its displaced bound: the bound's extra cost over
  // the frustum kernel plus the Hi-Z lookup.
  for (const auto& [name, pass] : displacedPasses)
    c.cullMsPerPatch[name] = m("cull displaced " + name) / nTorusCull + c.cullMsPerPatch["hiz"];
  // RT(tf) of a displaced patch relative to an undisplaced one: the two draws of the same
  // patches less the empty frame; at least 1 (a lookup is never free; below is noise).
  for (uint32_t level : levels) {
    const double plain = m("torus " + std::to_string(level)) - c.submitMs;
    const double displaced = m("displaced " + std::to_string(level)) - c.submitMs;
    c.displacedDrawFactor.push_back(
        {level, plain > 0.0 && displaced > 0.0 ? std::max(1.0, displaced / plain) : 1.0});
  }

  c.hizBuild = {{plan::hizPixels(uint64_t(width / 2) * (height / 2), false), m("hiz build small")},
                {plan::hizPixels(uint64_t(width) * height, false), m("hiz build")},
                {plan::hizPixels(uint64_t(width) * height, true), m("hiz build full")}};
  c.hizTightMsPerPatch = m("hiz tight") / nMany;
  c.pointUpdateCpuMsPerPatch = m("points cpu") / cagePatches;
  c.pointUpdateGpuMsPerPatch = m("points gpu") / cagePatches;
  c.boundsMsPerPatch = m("bounds") / cagePatches;
  for (const auto& [name, pass] : boundsPasses)
    c.boundsMsPerMethod[name] = m("bounds " + name) / cagePatches;
  return c;
}

Calibration deviceCalibration(const vulkan::Context& context, const std::string& file) {
  if (!file.empty()) return plan::loadCalibration(file);
  const CalibrationKey key = calibrationKey(context);
  if (std::optional<Calibration> cached = loadCachedCalibration(key)) return *cached;
  const std::filesystem::path where = calibrationCacheFile(key);
  throw Error(
      "no calibration of device '" + key.device + "' (driver " + key.driver + ", osd_cull " +
      key.library + ") " +
      (where.empty() ? std::string("(the calibration cache is off)") : "in " + where.string()) +
      ": run `osd-cull calibrate --quick` (under 30 s) or `osd-cull calibrate` first");
}

}  // namespace osd_cull::measure
