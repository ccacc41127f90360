// bench-plan: the effect plan (osd_cull/plan) against its two fixed alternatives, for
// docs/results/plan.md. Per case and tessellation level, over the same orbit of cameras at
// the same image size, three frames per camera back to back (interleaved): no culling
// (Renderer::render), all culling (CullFrame: frustum, back-patch, Hi-Z occlusion, two
// passes) and the planned frame (the stages the planner chose for that frame, learning the
// rates as it plays). Back faces are culled by the rasterizer on all three sides where the
// mesh is closed (like for like); the three run in each of their six orders in turn.
// Prints per level the medians, planned / min(none, all) and whether it is within 5%, and
// the planner's predicted frame time against the measured one and whether it is within 25%.
//
//   bench-plan [--cases builtin,bigguy,animated,displaced] [--tess 1,2,4,8,16,32] [--frames 4]
//              [--adaptive 8,...] (screen-space adaptive levels, PIXELS per segment, after --tess)
//              [--mesh FILE,...] [--level 2] (held-out meshes: OBJ cages, cases of their own)
//              [--scale S] [--translate T] (of the --mesh points) [--orbit DEG] (per frame;
//              default one turn over --frames)
//              [--warmup 4] [--width 1280] [--height 720] [--calibration FILE] [--csv FILE]
//              [--per-frame] (each measured frame: the three sides' ms, the order, the plan)
//              [--device X]   (--repeats is accepted and unused: --frames sets the medians)
//
// The animated case deforms BigGuy's cage with a wave every frame; its control-point
// update and bounds passes run before the three frames and are not in their times (the
// same work on each side), nor in the prediction compared with them. The displaced case
// draws BigGuy with the procedural displacement map (scale 0.64, as bench-displaced) on all
// three sides; *all* culls it with frustum + con-caf occlusion (no back-patch stage: those
// tests bound the undisplaced surface), the plan picks its displaced bound by cost. After each
// case a summary line counts the levels planned within 5% of the best fixed choice and
// predicted within 25%. The calibration is this device's cached one (`osd-cull calibrate`),
// measured with --quick when there is none (or when it is of an older format).
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/measure/calibrate.h"
#include "osd_cull/plan/planner.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/scene/loaded_scene.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/session/mesh_session.h"
#include "osd_cull/vk/context.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;
using bench::median;

struct Options {
  std::vector<std::string> cases = {"builtin", "bigguy", "animated", "displaced"};
  std::vector<uint32_t> tess = {1, 2, 4, 8, 16, 32};
  std::vector<uint32_t> adaptive;   // pixels per segment
  std::vector<std::string> meshes;  // OBJ files
  uint32_t level = 2;
  double orbit = 0.0;      // degrees per frame; 0: one turn over --frames
  double scale = 1.0;      // of the --mesh cases' points
  double translate = 0.0;  // added to their x, y and z (far from the origin)
  uint32_t frames = 4, warmup = 4, width = 1280, height = 720, repeats = 1;
  std::string calibration, csv, device;
  bool perFrame = false;  // each measured frame's three times and the plan, to stderr
};

bench::CommandLine commandLine(Options& o) {
  return bench::CommandLine("bench-plan", "bench_plan.cpp")
      .names("--cases", o.cases)
      .numbers("--tess", o.tess)
      .numbers("--adaptive", o.adaptive)
      .names("--mesh", o.meshes)
      .number("--level", o.level, 1)
      .real("--orbit", o.orbit, 0.0)
      .real("--scale", o.scale, 1e-12)
      .real("--translate", o.translate, -1e12)
      .number("--frames", o.frames, 1)
      .number("--warmup", o.warmup)
      .imageAndDevice(o.width, o.height, o.repeats, o.device)
      .text("--calibration", o.calibration)
      .text("--csv", o.csv)
      .flag("--per-frame", o.perFrame);
}

// A mesh to draw: static patches, or a deforming cage.
struct Case {
  std::string name;
  PatchSet patches;  // static
  std::unique_ptr<frame::DynamicPatchMesh> dynamic;
  std::unique_ptr<scene::CageAnimation> animation;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0, 0, 1}, viewDirection{0, 0, 1};
  bound::BackPatchValidity validity;
  // A displaced mesh: its map and texture coordinates (PatchExtraction::uvCorners).
  std::unique_ptr<bound::DisplacementMap> map;
  std::vector<glm::dvec2> uvCorners;
  const PatchSet& host() { return dynamic ? dynamic->patches() : patches; }
};

Case builtIn() {
  scene::Scene s = scene::defaultScene();
  Case c;
  c.name = "built-in scene";
  c.patches = std::move(s.patches);
  c.occluders = std::move(s.occluders);
  c.up = s.up;
  c.viewDirection = s.viewDirection;
  c.validity = {true, "built-in scene: closed, outward cages"};
  return c;
}

Case bigGuy(vulkan::Context& context, bool animated);

// A held-out mesh: an OBJ cage at `level`, y up, its points scaled by `scale` and moved by
// `translate` on every axis (a mesh authored at another size or far from the origin).
Case meshFile(const std::string& file, uint32_t level, double scale, double translate) {
  bench::CullMesh m = bench::loadCullMesh(file, level);
  for (glm::dvec3& p : m.patches.points) p = scale * p + glm::dvec3(translate);
  // Recentred as osd-cull recentres a far mesh file at load (samples/osd-cull/mesh_patches.cpp),
  // so the planner sees what the program runs, not fp32 world coordinates that no form of
  // the program draws.
  const glm::dvec3 offset = scene::recentreFar(m.patches.points);
  Case c;
  c.name = std::filesystem::path(file).filename().string() + " level " + std::to_string(level);
  if (scale != 1.0 || translate != 0.0) {
    char t[64];
    std::snprintf(t, sizeof t, " (x%g, +%g%s)", scale, translate,
                  offset != glm::dvec3(0.0) ? ", recentred" : "");
    c.name += t;
  }
  c.up = {0, 1, 0};
  c.viewDirection = {0.3, 0.25, 1.0};
  c.validity = m.validity;
  c.patches = std::move(m.patches);
  return c;
}

// BigGuy level 2 with the procedural map (bench-displaced's scale: |D| up to 2% of its radius).
Case displacedBigGuy(vulkan::Context& context) {
  Case c = bigGuy(context, false);
  c.name = "BigGuy level 2, displaced";
  PatchOptions po;
  po.isolationLevel = 2;
  PatchExtraction ex =
      extractPatches(adapters::loadCage(bench::dataDir() / "characters" / "bigguy.obj"), po);
  if (ex.uvCorners.empty()) throw Error("displaced case: bigguy.obj has no texture coordinates");
  c.patches = std::move(ex.patches);
  c.uvCorners = std::move(ex.uvCorners);
  c.map = std::make_unique<bound::DisplacementMap>(
      "procedural", 256, 256, scene::proceduralDisplacementTexels(256), 0.64, 0.5);
  return c;
}

Case bigGuy(vulkan::Context& context, bool animated) {
  const auto file = bench::dataDir() / "characters" / "bigguy.obj";
  bench::CullMesh m = bench::loadCullMesh(file, 2);
  Case c;
  c.name = animated ? "BigGuy level 2, wave" : "BigGuy level 2";
  c.up = {0, 1, 0};
  c.viewDirection = {0.3, 0.25, 1.0};
  c.validity = m.validity;
  if (!animated) {
    c.patches = std::move(m.patches);
    return c;
  }
  const CageMesh cage = adapters::loadCage(file);
  PatchOptions po;
  po.isolationLevel = 2;
  c.dynamic = std::make_unique<frame::DynamicPatchMesh>(context, cage, po);
  scene::AnimationSource wave;
  wave.kind = scene::AnimationSource::Kind::Wave;
  wave.deformer.amount = 0.05;
  c.animation = scene::makeProceduralAnimation(wave, cage.positions);
  return c;
}

struct Row {
  std::vector<double> none, all, planned, predicted;
  std::map<std::string, int> choices;
  int changes = 0;  // plan changes after the first measured frame
};

// Levels of a case and how many met the two marks.
struct Tally {
  int levels = 0, within5 = 0, within25 = 0;
  void add(const Tally& t) {
    levels += t.levels;
    within5 += t.within5;
    within25 += t.within25;
  }
  std::string text() const {
    return "planned within 5% of the better of none and all at " + std::to_string(within5) +
           " of " + std::to_string(levels) + " levels; predicted within 25% of measured at " +
           std::to_string(within25) + " of " + std::to_string(levels);
  }
};

// The 1-minute load average (/proc/loadavg), "?" where there is none: printed next to the
// figures, since this machine is shared.
std::string loadAverage() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (!f) return "?";
  char text[64] = {};
  const bool ok = std::fscanf(f, "%63s", text) == 1;
  std::fclose(f);
  return ok ? text : "?";
}

// One table row (and CSV line) of a level: the medians of the three sides, the plan's
// choices, and whether it is within 5% of the better fixed choice and its prediction within 25%.
void reportLevel(const std::string& caseName, const std::string& label, const Row& row,
                 Tally& tally, FILE* csv) {
  const double none = median(row.none), allMs = median(row.all), plannedMs = median(row.planned),
               predicted = median(row.predicted);
  const double best = std::min(none, allMs);
  std::string choices;
  for (const auto& [choice, count] : row.choices)
    choices += (choices.empty() ? "" : "; ") + choice + " (" + std::to_string(count) + ")";
  choices += "; " + std::to_string(row.changes) + " plan changes";
  const bool within5 = plannedMs <= 1.05 * best,
             within25 = std::abs(predicted / plannedMs - 1.0) <= 0.25;
  ++tally.levels;
  tally.within5 += within5;
  tally.within25 += within25;
  std::printf("| %s | %.1f | %.1f | %.1f | %s | %.2f | %s | %.1f | %.2f | %s |\n", label.c_str(),
              none, allMs, plannedMs, choices.c_str(), plannedMs / best, within5 ? "yes" : "**no**",
              predicted, predicted / plannedMs, within25 ? "yes" : "**no**");
  std::fflush(stdout);
  if (csv) {
    std::fprintf(csv, "\"%s\",%s,%.4f,%.4f,%.4f,%.4f,\"%s\"\n", caseName.c_str(), label.c_str(),
                 none, allMs, plannedMs, predicted, choices.c_str());
    std::fflush(csv);
  }
}

// --per-frame: one measured frame's three times, the order they ran in, and the plan with
// its predictions and the planned frame's GPU stage times.
void printFrame(int f, const int* order, double none, double allMs,
                const session::SessionFrame& m) {
  const plan::Plan& p = *m.plan;
  std::fprintf(stderr,
               "  frame %d (order %d%d%d): none %.2f, all %.2f, planned %.2f ms (%s%s; "
               "predicted %.2f, unculled %.2f; GPU pass 1 %.2f, pyramid %.2f, cull %.2f, "
               "pass 2 %.2f)\n",
               f, order[0], order[1], order[2], none, allMs, m.stats.frameMs,
               p.stages.describe().c_str(), p.probe ? ", probe" : "",
               p.predicted.totalMs() - p.predicted.updateMs,
               p.predictedUnculled.totalMs() - p.predictedUnculled.updateMs, m.stats.gpu.pass1,
               m.stats.gpu.pyramid, m.stats.gpu.cull, m.stats.gpu.pass2);
}

Tally runCase(vulkan::Context& context, Case& c, plan::Planner& planner, const Options& o,
              FILE* csv) {
  Tally tally;
  std::printf("\n### %s, %ux%u\n\n", c.name.c_str(), o.width, o.height);
  const bool selfOccluding = plan::mayHideItself(c.host());
  std::printf("Self-occlusion (Hi-Z on the mesh alone): %s.\n\n",
              selfOccluding ? "offered, the surface is not convex" : "not offered, convex surface");
  std::printf(
      "| tess | none ms | all ms | planned ms | planned choice (frames) | planned / best | "
      "within 5%% | predicted ms | predicted / measured | within 25%% |\n");
  std::printf("|---:|---:|---:|---:|---|---:|---|---:|---:|---|\n");
  std::fflush(stdout);
  frame::Renderer renderer(context);
  frame::RenderTarget target(context, o.width, o.height);
  std::vector<frame::GpuTriangleMesh> meshes;
  for (const auto& m : c.occluders) meshes.emplace_back(context, m);
  std::vector<const frame::GpuTriangleMesh*> occluders;
  for (const auto& m : meshes) occluders.push_back(&m);
  frame::GpuPatchSet* gpu = nullptr;
  std::unique_ptr<frame::GpuPatchSet> staticGpu;
  if (c.dynamic)
    gpu = &c.dynamic->gpu();
  else
    gpu = (staticGpu = std::make_unique<frame::GpuPatchSet>(context, c.patches)).get();
  // A displaced mesh draws with its map on every side (the unculled frame too).
  std::unique_ptr<frame::GpuDisplacement> displacement;
  if (c.map) {
    displacement = std::make_unique<frame::GpuDisplacement>(context, *c.map, c.uvCorners,
                                                            c.host().patchCount());
    gpu->setDisplacement(displacement.get());
  }
  const frame::Bounds rest = frame::boundsOf(c.host().points);
  const frame::Camera framed =
      frame::frameBounds(rest, c.viewDirection, c.up, 40.0, o.width, o.height);
  const double d = glm::distance(framed.eye(), rest.center()), r = rest.radius();
  const frame::Camera start =
      frame::Camera::lookAt(framed.eye(), rest.center(), c.up, 40.0, o.width, o.height,
                            std::max(d - 1.5 * r, d * 1e-3), d + 1.5 * r);
  const std::string coneMethod = "tcone";
  auto cullData = [&](const std::string& method) -> const vulkan::Buffer* {
    if (!c.dynamic || method.empty()) return nullptr;
    return &c.dynamic->cullData(frame::cullMethod(method).reference);
  };
  uint64_t frameNumber = 0;
  const auto levels = bench::tessellationLevels(
      o.tess, o.adaptive, context.info().limits.maxTessellationGenerationLevel);
  for (const auto& [label, tessellation] : levels) {
    bench::progress(c.name + ": tess " + label);
    frame::CullFrameOptions base;
    base.render.tessellation = tessellation;
    base.render.cullBackFaces = c.validity.enabled;
    base.cull.backPatchValidity = c.validity;
    base.cull.displacementMap = c.map.get();
    base.cull.uvCorners = c.uvCorners;
    // All culling: the three stages in the two-pass frame; a displaced mesh: frustum and
    // occlusion on the displaced bound that culls most (Niessner & Loop Table 1: con-caf).
    frame::CullFrameOptions allOptions = base;
    allOptions.cull.frustum = true;
    allOptions.cull.backPatch = c.map ? "" : c.dynamic ? coneMethod : "tangent-plane";
    allOptions.cull.occlusion = c.map ? "con-caf" : "hiz";
    if (c.map) allOptions.cull.displacedKernel = *frame::cullMethod("con-caf").displaced;
    const frame::CullMesh allMesh[] = {
        {gpu, &c.host(), cullData(c.dynamic ? coneMethod : ""), glm::dmat4(1.0), c.validity}};
    frame::CullFrame all(context, renderer, target, allMesh, allOptions);
    // The planned side: the library's session (session/mesh_session.h), which keeps the
    // pass or frame of every choice with its visibility status.
    session::MeshSessionOptions so;
    so.name = c.name;
    so.view = "orbit/tess " + label;
    so.frame = base;
    so.occluders = !occluders.empty();
    so.deforming = c.dynamic != nullptr;
    so.cullData = cullData;
    session::MeshSession planned(context, renderer, target, *gpu, c.host(), occluders, so,
                                 &planner);
    Row row;
    const int first = -int(o.warmup);
    for (int f = first; f < int(o.frames); ++f, ++frameNumber) {
      const frame::Camera cam =
          frame::orbit(start, rest.center(), c.up,
                       (o.orbit > 0.0 ? o.orbit : 360.0 / o.frames) * (f - first) + 7.0);
      if (c.animation) {
        std::vector<glm::dvec3> cage(c.animation->vertexCount());
        c.animation->positions(double(frameNumber) / 24.0, cage);
        c.dynamic->setCagePositions(cage);
        c.dynamic->update();
      }
      const frame::PatchDraw draw{gpu, &c.host(), 0};
      // The three sides back to back.
      double none = 0.0, allMs = 0.0;
      session::SessionFrame m;
      const std::function<void()> sides[] = {
          [&] {
            none = renderer.render(target, cam, {&draw, 1}, occluders, base.render).wallMs;
          },
          [&] { allMs = all.render(cam, occluders).frameMs; }, [&] { m = planned.render(cam); }};
      // All six orders in turn: each side runs first, in the middle and last, and after
      // each other side, equally often over six frames (a frame after the heavy all-culling
      // frame runs slower on lavapipe, so a plain rotation, where one side follows it twice
      // as often as another, biases the comparison).
      static constexpr int kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                            {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
      for (int k : kOrders[(f - first) % 6]) sides[k]();
      const plan::Plan& p = *m.plan;
      if (f < 0) continue;
      row.none.push_back(none);
      row.all.push_back(allMs);
      row.planned.push_back(m.stats.frameMs);
      row.predicted.push_back(p.predicted.totalMs() - p.predicted.updateMs);
      ++row.choices[p.stages.describe() + (p.probe ? " [probe]" : "")];
      if (o.perFrame) printFrame(f, kOrders[(f - first) % 6], none, allMs, m);
      row.changes += m.planChanged && f > 0;
    }
    reportLevel(c.name, label, row, tally, csv);
  }
  std::printf("\n**%s:** %s (load average %s).\n", c.name.c_str(), tally.text().c_str(),
              loadAverage().c_str());
  return tally;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-plan", [&] {
    Options o;
    if (!commandLine(o).parse(argc, argv)) return 0;
    vulkan::Context context(bench::contextOptions(o.device));
    plan::Calibration calibration;
    try {
      calibration = measure::deviceCalibration(context, o.calibration);
    } catch (const Error& e) {
      if (!o.calibration.empty()) throw;
      bench::progress(std::string(e.what()) + "; measuring one (--quick)");
      measure::CalibrateOptions co;
      co.quick = true;
      calibration = measure::calibrate(context, co);
      plan::storeCalibration(calibration, plan::calibrationCacheFile(calibration.key));
    }
    plan::PlannerOptions po;
    po.holdFrames = 2;  // the bench plays few frames per level
    plan::Planner planner(calibration, po);
    std::printf("bench-plan: %s, calibration %s%s; load average %s at the start\n",
                context.info().name.c_str(), calibration.key.driver.c_str(),
                calibration.quick ? " (quick)" : "", loadAverage().c_str());
    std::printf(
        "\nMedians over %u frames per level after %u warm-up frames (the planner learns its "
        "rates there); none, all and planned interleaved per camera.\n",
        o.frames, o.warmup);
    const bench::CsvFile csv =
        bench::openCsv(o.csv, "case,tess,none_ms,all_ms,planned_ms,predicted_ms,choices");
    for (const std::string& name : o.cases)
      if (name != "builtin" && name != "bigguy" && name != "animated" && name != "displaced")
        throw Error("--cases: unknown case '" + name + "' (builtin, bigguy, animated, displaced)");
    Tally total;
    // --mesh without --cases: the held-out meshes only.
    if (!o.meshes.empty() && o.cases == Options{}.cases) o.cases.clear();
    for (const std::string& file : o.meshes) {
      Case c = meshFile(file, o.level, o.scale, o.translate);
      total.add(runCase(context, c, planner, o, csv.get()));
    }
    for (const std::string& name : o.cases) {
      Case c = name == "builtin"    ? builtIn()
               : name == "bigguy"   ? bigGuy(context, false)
               : name == "animated" ? bigGuy(context, true)
                                    : displacedBigGuy(context);
      total.add(runCase(context, c, planner, o, csv.get()));
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("\n**All cases:** %s (load average %s at the end; peak RSS %.1f MB).\n",
                total.text().c_str(), loadAverage().c_str(), usage.ru_maxrss / 1024.0);
    bench::progress("done");
    return 0;
  });
}
