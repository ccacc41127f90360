#include "osd_cull/measure/calibrate.h"

#include "osd_cull/bound/back_patch.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/plan/cost_model.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/version.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/shader_compiler.h"

#include <osd_cull/shared/cull_layout.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
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

/// \brief The calibration sphere and its views: a closed sphere of Bézier patches filling
/// most of the view, the same patches as Gregory patches, a six-patch sphere for the fixed
/// dispatch cost and a finer one for the cull kernels (culling costs a fraction of a
/// microsecond per patch: the differences between kernels must stand above the
/// submission's noise).
struct SphereRig {
  uint32_t width, height;
  std::vector<uint32_t> levels;  // the tessellation levels of the draw terms RT(tf)
  PatchSet sphere, gregory, tiny, many;
  frame::GpuPatchSet gpu, gpuGregory, gpuTiny, gpuMany;
  frame::Renderer renderer;
  frame::RenderTarget target, small;
  frame::Bounds bounds;
  frame::Camera camera, smallCamera;
  frame::Camera inside;  // from the centre: every patch faces away (the rasterizer discards)
  frame::Camera away;    // looking away: every patch is culled by the frustum (for RT0)
  frame::RenderOptions render;
  const bound::BackPatchValidity closed{true, "calibration sphere: closed, outward"};
  frame::PatchDraw draw, drawGregory;

  SphereRig(vulkan::Context& context, const CalibrateOptions& o)
      : width(o.quick ? 640 : 1280),
        height(o.quick ? 360 : 720),
        levels(o.quick ? std::vector<uint32_t>{1, 4, 8, 16, 32}
                       : std::vector<uint32_t>{1, 2, 4, 8, 12, 16, 24, 32}),
        sphere(scene::bezierSphere({0, 0, 0}, 1.0, o.quick ? 10 : 16)),
        gregory(scene::convertToGregory(sphere, [](uint32_t) { return true; })),
        tiny(scene::bezierSphere({0, 0, 0}, 1.0, 1)),
        many(scene::bezierSphere({0, 0, 0}, 1.0, o.quick ? 24 : 40)),
        gpu(context, sphere),
        gpuGregory(context, gregory),
        gpuTiny(context, tiny),
        gpuMany(context, many),
        renderer(context),
        target(context, width, height),
        small(context, width / 2, height / 2),
        bounds(frame::boundsOf(sphere.points)),
        camera(frame::frameBounds(bounds, {0.3, 0.4, 1.0}, {0, 1, 0}, 40.0, width, height)),
        smallCamera(
            frame::frameBounds(bounds, {0.3, 0.4, 1.0}, {0, 1, 0}, 40.0, width / 2, height / 2)),
        inside(frame::Camera::lookAt({0, 0, 0}, {0.3, 0.4, 1.0}, {0, 1, 0}, 90.0, width, height,
                                     0.01, 10.0)),
        away(frame::Camera::lookAt(camera.eye(), camera.eye() * 2.0, {0, 1, 0}, 40.0, width, height,
                                   0.1, 100.0)),
        draw{&gpu, &sphere, 0},
        drawGregory{&gpuGregory, &gregory, 0} {
    render.cullBackFaces = true;  // like for like: what culled and unculled frames both do
    render.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  }
};

/// \brief The cull passes whose CT is measured: frustum alone, frustum + each back-patch
/// method (drawn-triangle and the papers' surface-exact test), the listed-triangle test
/// against its bound kernel, and the frustum pass on the tiny sphere.
struct CullPasses {
  std::map<std::string, std::unique_ptr<frame::CullPass>> passes, surfacePasses;
  // The listed-triangle test costs per patch about what drawing it costs (it lists the
  // level's triangles): measured on a coarse sphere, against the bound kernel at each level.
  PatchSet listedSphere;
  frame::GpuPatchSet gpuListed;
  std::vector<uint32_t> listedLevels;
  std::map<std::string,
           std::pair<std::unique_ptr<frame::CullPass>, std::unique_ptr<frame::CullPass>>>
      listedPasses;                            // bound, listed
  std::map<std::string, uint32_t> listedRuns;  // "method level": patches reaching the test
  frame::CullPass tinyPass;

  CullPasses(vulkan::Context& context, SphereRig& rig, const CalibrateOptions& o)
      : listedSphere(scene::bezierSphere({0, 0, 0}, 1.0, o.quick ? 6 : 10)),
        gpuListed(context, listedSphere),
        listedLevels(o.quick ? std::vector<uint32_t>{2, 8, 16}
                             : std::vector<uint32_t>{1, 2, 4, 8, 16, 32}),
        tinyPass(context, rig.gpuTiny, rig.tiny, frame::CullSettings{true, "", "", rig.closed}) {
    const bound::BackPatchValidity& closed = rig.closed;
    passes["frustum"] = std::make_unique<frame::CullPass>(
        context, rig.gpuMany, rig.many, frame::CullSettings{true, "", "", closed});
    for (const std::string& m : frame::cullMethodNames(frame::CullStage::BackPatch)) {
      // The fp64 kernels are study variants (docs/results/accuracy-vs-time.md), not plan
      // candidates: the planner only considers calibrated methods.
      if (frame::cullMethod(m).needsFloat64) continue;
      passes[m] = std::make_unique<frame::CullPass>(context, rig.gpuMany, rig.many,
                                                    frame::CullSettings{true, m, "", closed});
      frame::CullSettings surface{true, m, "", closed};
      surface.drawnTriangles = false;  // the papers' surface-exact test
      surfacePasses[m] = std::make_unique<frame::CullPass>(context, rig.gpuMany, rig.many, surface);
      if (frame::cullMethod(m).lanesPerPatch > 1) continue;  // the study lists one-thread kernels
      frame::CullSettings listed{true, m, "", closed};
      listed.drawnEnumerate = true;
      listedPasses[m] = {
          std::make_unique<frame::CullPass>(context, gpuListed, listedSphere,
                                            frame::CullSettings{true, m, "", closed}),
          std::make_unique<frame::CullPass>(context, gpuListed, listedSphere, listed)};
    }
  }
};

/// \brief Two-pass frames: the diagnostic mode times the pyramid and the cull (Hi-Z stage
/// included) at two image sizes and with the tight lookup; tess-factor-0 and filtered
/// frames looking away give RT0.
struct TwoPassFrames {
  frame::CullMesh meshes[1];
  frame::CullFrame diagnostic, diagnosticSmall, diagnosticTight, filtered, factorZero;

  TwoPassFrames(vulkan::Context& context, SphereRig& rig)
      : meshes{{&rig.gpuMany, &rig.many}},
        diagnostic(context, rig.renderer, rig.target, meshes, options(rig, true)),
        diagnosticSmall(context, rig.renderer, rig.small, meshes, options(rig, true)),
        diagnosticTight(context, rig.renderer, rig.target, meshes,
                        options(rig, true, bound::HiZLookup::Tight)),
        filtered(context, rig.renderer, rig.target, meshes, options(rig, false)),
        factorZero(
            context, rig.renderer, rig.target, meshes,
            options(rig, false, bound::HiZLookup::Paper, frame::CullDrawMode::TessFactorZero)) {}

  /// \brief A frame's options: frustum and Hi-Z at tessellation level 1, timed per pass
  /// (`timePasses`) or not, with the Hi-Z lookup and draw mode given.
  static frame::CullFrameOptions options(
      const SphereRig& rig, bool timePasses, bound::HiZLookup lookup = bound::HiZLookup::Paper,
      std::optional<frame::CullDrawMode> drawMode = std::nullopt) {
    frame::CullFrameOptions fo;
    fo.render = rig.render;
    fo.render.tessellation.uniformLevel = 1;
    fo.cull = {true, "", "hiz", rig.closed};
    fo.timePasses = timePasses;
    fo.hiz.lookup = lookup;
    if (drawMode) fo.drawMode = *drawMode;
    return fo;
  }
};

/// \brief Point updates (CPU and GPU paths) and the bounds pass of each back-patch method
/// and displaced extension on a deforming torus cage.
struct PointUpdates {
  CageMesh cage;
  frame::DynamicPatchMesh cpuMesh, gpuMesh;
  double cagePatches;
  std::map<std::string, std::unique_ptr<frame::BoundsPass>> boundsPasses;
  std::vector<glm::dvec3> moved;

  explicit PointUpdates(vulkan::Context& context)
      : cage(scene::torus(24, 16)),
        cpuMesh(context, cage, {}, frame::PointUpdatePath::Cpu),
        gpuMesh(context, cage, {}, frame::PointUpdatePath::Gpu),
        cagePatches(0.0),
        moved(cage.positions.begin(), cage.positions.end()) {
    cpuMesh.cullData(bound::BackPatchMethod::TCone);
    cagePatches = cpuMesh.gpu().patchCount();
    // The bounds pass of each back-patch method on its own (each writes other cull data).
    for (const std::string& m : frame::cullMethodNames(frame::CullStage::BackPatch)) {
      const frame::CullMethod& method = frame::cullMethod(m);
      if (method.needsFloat64 || method.lanesPerPatch > 1 ||
          !frame::BoundsPass::hasCullData(method.reference))
        continue;  // shares the pass of its fp32 / one-thread method (Calibration::boundsMs)
      boundsPasses[m] =
          std::make_unique<frame::BoundsPass>(context, gpuMesh.gpu(), method.reference);
    }
    // The displaced bounds passes (issue 10): the ACoN and CoN cones of a displaced mesh's
    // moved points, per frame; the Full extension needs only the static ranges. The ranges'
    // values do not change the work: a constant one.
    const std::vector<bound::DisplacementRange> ranges(gpuMesh.gpu().patchCount(), {-0.01, 0.01});
    for (const bound::DisplacedExtension extension :
         {bound::DisplacedExtension::ACoN, bound::DisplacedExtension::CoN})
      boundsPasses[bound::toString(extension)] =
          std::make_unique<frame::BoundsPass>(context, gpuMesh.gpu(), extension, ranges);
  }
};

/// \brief Displaced meshes: the displaced draw RT(tf) against the undisplaced one on the UV
/// torus (the displacement lookup in the evaluation stage), and the six displaced kernels
/// against the frustum kernel on a finer one (the displaced bound's extra cost).
struct DisplacedRig {
  PatchExtraction torusDraw, torusCull;
  bound::DisplacementMap map;
  frame::GpuPatchSet gpuTorus, gpuTorusDisplaced, gpuTorusCull;
  frame::GpuDisplacement displacement;
  double nTorusCull;
  frame::Camera torusCamera;
  frame::PatchDraw torusPlain, torusDisplaced;
  const bound::BackPatchValidity torusClosed{true, "calibration torus: closed, outward"};
  frame::CullPass torusFrustum;
  std::map<std::string, std::unique_ptr<frame::CullPass>> displacedPasses;

  DisplacedRig(vulkan::Context& context, const SphereRig& rig, const CalibrateOptions& o)
      : torusDraw(uvTorus(o.quick ? 24 : 48, o.quick ? 12 : 24)),
        torusCull(uvTorus(o.quick ? 64 : 96, o.quick ? 32 : 48)),
        map("procedural", 256, 256, scene::proceduralDisplacementTexels(256), 0.04, 0.5),
        gpuTorus(context, torusDraw.patches),
        gpuTorusDisplaced(context, torusDraw.patches),
        gpuTorusCull(context, torusCull.patches),
        displacement(context, map, torusDraw.uvCorners, torusDraw.patches.patchCount()),
        nTorusCull(torusCull.patches.patchCount()),
        torusCamera(frame::frameBounds(frame::boundsOf(torusDraw.patches.points), {0.3, 0.4, 1.0},
                                       {0, 1, 0}, 40.0, rig.width, rig.height)),
        torusPlain{&gpuTorus, &torusDraw.patches, 0},
        torusDisplaced{&gpuTorusDisplaced, &torusDraw.patches, 0},
        torusFrustum(context, gpuTorusCull, torusCull.patches,
                     frame::CullSettings{true, "", "", torusClosed}) {
    gpuTorusDisplaced.setDisplacement(&displacement);
    for (const frame::CullMethod& m : frame::displacedCullMethods()) {
      frame::CullSettings ds{true, "", "", torusClosed};
      ds.displacementMap = &map;
      ds.uvCorners = torusCull.uvCorners;
      ds.displacedKernel = *m.displaced;
      displacedPasses[m.name] =
          std::make_unique<frame::CullPass>(context, gpuTorusCull, torusCull.patches, ds);
    }
  }
};

/// \brief Standalone Hi-Z pyramids over the two targets' depth (built again and again),
/// one at full resolution.
struct Pyramids {
  frame::HiZPyramid pyramid, pyramidSmall, pyramidFull;

  Pyramids(vulkan::Context& context, SphereRig& rig)
      : pyramid(context, rig.target.depth()),
        pyramidSmall(context, rig.small.depth()),
        pyramidFull(context, rig.target.depth(), fullResolution()) {}

  static frame::HiZOptions fullResolution() {
    frame::HiZOptions o;
    o.fullResolution = true;
    return o;
  }
};

/// \brief Every object the calibration measures, built once before the repeats.
struct Rigs {
  SphereRig& sphere;
  CullPasses& cull;
  TwoPassFrames& frames;
  PointUpdates& points;
  DisplacedRig& displaced;
  Pyramids& pyramids;
};

/// \brief The draw terms of one repeat: RT(tf) per level on the sphere (facing and facing
/// away), the torus plain and displaced, and the Gregory factor at level 8. In repeat 0
/// also the TES invocations per patch of each level (`tes`).
void sampleDraws(Rigs& rigs, uint32_t r, Samples& one,
                 std::vector<std::pair<uint32_t, double>>& tes) {
  SphereRig& g = rigs.sphere;
  frame::Renderer& renderer = g.renderer;
  frame::RenderOptions& render = g.render;
  render.tessellation.uniformLevel = 1;
  const double empty = renderer.render(g.target, g.camera, {}, {}, render).wallMs;
  one["frame"].push_back(empty);
  for (uint32_t level : g.levels) {
    render.tessellation.uniformLevel = level;
    const frame::FrameStats st = renderer.render(g.target, g.camera, {&g.draw, 1}, {}, render);
    one["draw " + std::to_string(level)].push_back(
        st.wallMs - renderer.render(g.target, g.camera, {}, {}, render).wallMs);
    one["back " + std::to_string(level)].push_back(
        renderer.render(g.target, g.inside, {&g.draw, 1}, {}, render).wallMs -
        renderer.render(g.target, g.inside, {}, {}, render).wallMs);
    if (r == 0)
      tes.push_back(
          {level, double(st.statistics.tessEvaluationInvocations) / g.sphere.patchCount()});
  }
  const DisplacedRig& d = rigs.displaced;
  for (uint32_t level : g.levels) {
    render.tessellation.uniformLevel = level;
    one["torus " + std::to_string(level)].push_back(
        renderer.render(g.target, d.torusCamera, {&d.torusPlain, 1}, {}, render).wallMs);
    one["displaced " + std::to_string(level)].push_back(
        renderer.render(g.target, d.torusCamera, {&d.torusDisplaced, 1}, {}, render).wallMs);
  }
  render.tessellation.uniformLevel = 8;
  const double bezier8 = renderer.render(g.target, g.camera, {&g.draw, 1}, {}, render).wallMs;
  one["gregory 8"].push_back(
      renderer.render(g.target, g.camera, {&g.drawGregory, 1}, {}, render).wallMs / bezier8);
}

/// \brief The cheap terms, sampled `sub` times a repeat: the dispatch, each kernel's CT
/// over the frustum kernel (drawn-triangle, surface-exact and displaced) and the Hi-Z
/// builds. Returns the last frustum kernel's time (the Hi-Z stage's CT is measured over it).
double sampleKernels(vulkan::Context& context, Rigs& rigs, uint32_t sub, Samples& one) {
  SphereRig& g = rigs.sphere;
  const frame::TessellationOptions& tess = g.render.tessellation;
  CullPasses& cull = rigs.cull;
  DisplacedRig& d = rigs.displaced;
  Pyramids& p = rigs.pyramids;
  double frustum = 0.0;
  for (uint32_t k = 0; k < sub; ++k) {
    const double submit = timed([&] { context.submit([](VkCommandBuffer) {}); });
    const double tinyMs = cull.tinyPass.run(g.camera, tess);
    one["dispatch"].push_back(tinyMs - submit);
    frustum = cull.passes.at("frustum")->run(g.camera, tess);
    one["cull frustum"].push_back(frustum - tinyMs);
    for (auto& [name, pass] : cull.passes)
      if (name != "frustum") one["cull " + name].push_back(pass->run(g.camera, tess) - frustum);
    for (auto& [name, pass] : cull.surfacePasses)
      one["cull surface " + name].push_back(pass->run(g.camera, tess) - frustum);
    const double torusMs = d.torusFrustum.run(d.torusCamera, tess);
    for (auto& [name, pass] : d.displacedPasses)
      one["cull displaced " + name].push_back(pass->run(d.torusCamera, tess) - torusMs);
    one["hiz build"].push_back(
        timed([&] { p.pyramid.build(context, frame::RenderTarget::kDepthLayout); }));
    one["hiz build full"].push_back(
        timed([&] { p.pyramidFull.build(context, frame::RenderTarget::kDepthLayout); }));
    one["hiz build small"].push_back(
        timed([&] { p.pyramidSmall.build(context, frame::RenderTarget::kDepthLayout); }));
  }
  return frustum;
}

/// \brief The listed-triangle test over its bound kernel at each listed level, with the
/// number of patches that reached it (CullRates::listedRuns).
void sampleListed(Rigs& rigs, Samples& one) {
  CullPasses& cull = rigs.cull;
  for (uint32_t level : cull.listedLevels) {
    frame::TessellationOptions tess = rigs.sphere.render.tessellation;
    tess.uniformLevel = level;
    for (auto& [name, pair] : cull.listedPasses) {
      const std::string key = name + " " + std::to_string(level);
      const double listedMs = pair.second->run(rigs.sphere.camera, tess);
      const double boundMs = pair.first->run(rigs.sphere.camera, tess);
      one["cull listed " + key].push_back(listedMs - boundMs);
      cull.listedRuns[key] = listedTestRuns(pair.first->results());
    }
  }
}

/// \brief The two-pass frames' terms: the Hi-Z stage's CT over the frustum kernel's
/// (`frustum`), the tight lookup's over the paper's, and RT0 looking away.
void sampleFrames(Rigs& rigs, double frustum, Samples& one) {
  TwoPassFrames& f = rigs.frames;
  const SphereRig& g = rigs.sphere;
  const double paperCull = f.diagnostic.render(g.camera, {}).cullMs;
  one["hiz cull"].push_back(paperCull - frustum);
  one["hiz tight"].push_back(f.diagnosticTight.render(g.camera, {}).cullMs - paperCull);
  f.diagnosticSmall.render(g.smallCamera, {});
  one["away tf0"].push_back(f.factorZero.render(g.away, {}).frameMs -
                            f.filtered.render(g.away, {}).frameMs);
}

/// \brief Moves the torus cage a little (in and out by turns, by repeat `r`) and samples
/// the point updates on both paths, the CPU bounds and each bounds pass.
void samplePoints(vulkan::Context& context, Rigs& rigs, uint32_t r, Samples& one) {
  PointUpdates& u = rigs.points;
  for (glm::dvec3& p : u.moved) p *= r % 2 ? 1.001 : 1.0 / 1.001;
  u.cpuMesh.setCagePositions(u.moved);
  u.cpuMesh.update();
  u.gpuMesh.setCagePositions(u.moved);
  u.gpuMesh.update();
  one["points cpu"].push_back(u.cpuMesh.lastTimes().pointsMs);
  one["bounds"].push_back(u.cpuMesh.lastTimes().boundsMs);
  one["points gpu"].push_back(u.gpuMesh.lastTimes().pointsMs);
  const double submit = timed([&] { context.submit([](VkCommandBuffer) {}); });
  for (auto& [name, pass] : u.boundsPasses)
    one["bounds " + name].push_back(pass->run(0.0) - submit);
}

/// \brief The medians of the samples into the calibration's cull terms: CT per patch of
/// each kernel (per patch the listed test runs on, for the listed one), the displaced
/// kernels and the Hi-Z stage.
void fillCullTerms(Calibration& c, const Rigs& rigs,
                   const std::function<double(const std::string&)>& m) {
  const double nMany = rigs.sphere.many.patchCount();
  c.cullDispatchMs = m("dispatch");
  for (const auto& [name, pass] : rigs.cull.passes)
    c.cullMsPerPatch[name] = m("cull " + name) / nMany;
  c.cullMsPerPatch["hiz"] = m("hiz cull") / nMany;
  for (const auto& [name, pass] : rigs.cull.surfacePasses)
    c.surfaceCullMsPerPatch[name] = m("cull surface " + name) / nMany;
  // Per patch the listed test runs on: its cost on a mesh is this times the share of the
  // mesh's patches that reach it (CullRates::listedRuns), which differs from mesh to mesh
  // (on the smooth calibration sphere the bound culls nearly every back-facing patch; on a
  // character a fifth of all patches reach the listed test).
  for (const auto& [name, pair] : rigs.cull.listedPasses)
    for (uint32_t level : rigs.cull.listedLevels) {
      const std::string key = name + " " + std::to_string(level);
      c.listedCullMsPerPatch[name].push_back(
          {level, m("cull listed " + key) / std::max(1.0, double(rigs.cull.listedRuns.at(key)))});
    }
  // A displaced kernel is the Hi-Z stage on its displaced bound: the bound's extra cost over
  // the frustum kernel plus the Hi-Z lookup.
  for (const auto& [name, pass] : rigs.displaced.displacedPasses)
    c.cullMsPerPatch[name] =
        m("cull displaced " + name) / rigs.displaced.nTorusCull + c.cullMsPerPatch["hiz"];
  c.hizTightMsPerPatch = m("hiz tight") / nMany;
}

/// \brief The medians of the samples into the calibration: the draw terms, then the cull
/// terms (fillCullTerms), the Hi-Z builds, point updates and bounds passes. A paired
/// difference below zero (noise) counts as zero cost.
void fillCalibration(Calibration& c, const Rigs& rigs, const Samples& s,
                     const std::vector<std::pair<uint32_t, double>>& tes) {
  const std::function<double(const std::string&)> m = [&](const std::string& name) {
    return std::max(0.0, median(s.at(name)));
  };
  const SphereRig& g = rigs.sphere;
  const double n = g.sphere.patchCount(), nMany = g.many.patchCount();
  c.submitMs = m("frame");
  for (const auto& [level, tesPerPatch] : tes)
    c.draw.push_back({level, m("draw " + std::to_string(level)) / n, tesPerPatch,
                      m("back " + std::to_string(level)) / n});
  c.gregoryDrawFactor = m("gregory 8");
  // Each frame looking away draws every patch twice (both passes) with factor 0.
  c.drawZeroMsPerPatch = m("away tf0") / (2.0 * nMany);
  fillCullTerms(c, rigs, m);
  // RT(tf) of a displaced patch relative to an undisplaced one: the two draws of the same
  // patches less the empty frame; at least 1 (a lookup is never free; below is noise).
  for (uint32_t level : g.levels) {
    const double plain = m("torus " + std::to_string(level)) - c.submitMs;
    const double displaced = m("displaced " + std::to_string(level)) - c.submitMs;
    c.displacedDrawFactor.push_back(
        {level, plain > 0.0 && displaced > 0.0 ? std::max(1.0, displaced / plain) : 1.0});
  }
  const uint32_t width = g.width, height = g.height;
  c.hizBuild = {{plan::hizPixels(uint64_t(width / 2) * (height / 2), false), m("hiz build small")},
                {plan::hizPixels(uint64_t(width) * height, false), m("hiz build")},
                {plan::hizPixels(uint64_t(width) * height, true), m("hiz build full")}};
  const double cagePatches = rigs.points.cagePatches;
  c.pointUpdateCpuMsPerPatch = m("points cpu") / cagePatches;
  c.pointUpdateGpuMsPerPatch = m("points gpu") / cagePatches;
  c.boundsMsPerPatch = m("bounds") / cagePatches;
  for (const auto& [name, pass] : rigs.points.boundsPasses)
    c.boundsMsPerMethod[name] = m("bounds " + name) / cagePatches;
}

}  // namespace

CalibrationKey calibrationKey(const vulkan::Context& context) {
  // The library version and the hash of its embedded kernels: the costs are the kernels',
  // so a build whose kernels changed measures again instead of planning with stale costs.
  char kernels[32];
  std::snprintf(kernels, sizeof(kernels), "%016llx",
                static_cast<unsigned long long>(vulkan::embeddedSpirvWordsHash()));
  return {context.info().name, context.info().driver,
          std::string(libraryVersion()) + " kernels " + kernels};
}

Calibration calibrate(vulkan::Context& context, const CalibrateOptions& o) {
  auto progress = [&](const std::string& line) {
    if (o.progress) o.progress(line);
  };
  Calibration c;
  c.key = calibrationKey(context);
  c.quick = o.quick;
  c.repeats = o.repeats ? o.repeats : (o.quick ? 3 : 7);
  SphereRig sphere(context, o);
  c.patches = sphere.sphere.patchCount();
  progress("building cull passes");
  CullPasses cull(context, sphere, o);
  TwoPassFrames frames(context, sphere);
  progress("building point updates");
  PointUpdates points(context);
  progress("building displaced draws and kernels");
  DisplacedRig displaced(context, sphere, o);
  Pyramids pyramids(context, sphere);
  Rigs rigs{sphere, cull, frames, points, displaced, pyramids};

  Samples s;
  std::vector<std::pair<uint32_t, double>> tes;
  // Each sample is a difference of two submissions made back to back (paired), so that the
  // load of other processes, which changes over seconds, cancels; the cheap ones are
  // sampled `sub` times per repeat.
  const uint32_t sub = 5;
  for (uint32_t r = 0; r <= c.repeats; ++r) {  // repeat 0 warms up (pipelines, caches)
    progress("repeat " + std::to_string(r) + " of " + std::to_string(c.repeats));
    Samples one;
    sampleDraws(rigs, r, one, tes);
    const double frustum = sampleKernels(context, rigs, sub, one);
    sampleListed(rigs, one);
    sampleFrames(rigs, frustum, one);
    samplePoints(context, rigs, r, one);
    if (r == 0) continue;
    for (auto& [name, v] : one) s[name].insert(s[name].end(), v.begin(), v.end());
  }
  fillCalibration(c, rigs, s, tes);
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
