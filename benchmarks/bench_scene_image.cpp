// The same-image benchmark of issue 10 (docs/results/animation.md, section "Same image over
// 300 frames"): the built-in scene (a skinned character swinging its limbs among static and
// moving objects, the camera on its path, a sun view) played frame after frame with culling
// (frustum, the back-patch method, Hi-Z occlusion: Niessner & Loop §3's two-pass frame),
// and every frame of every view drawn again without culling, like for like (same
// tessellation, back-face culling, image size). The item images must agree: no pixel lost
// (covered unculled, background culled), fewer than 0.01% differing (depth ties between
// neighbouring patches).
//
// With --plan (issue 12, docs/results/plan.md "Scenes") a second player of the same scene
// runs the effect plan (every instance in every view planned each frame from the device's
// calibration, or --calibration FILE), and each frame times three cases interleaved: the
// planned frame, the frame with all stages, and the unculled draw (the planned and the
// all-stages frame alternate which runs first); it prints their medians, the planned frame
// against the better of the other two, its predicted time against the measured one, and
// the planned frame's own image check against its unculled draw.
// --scene character plays a displaced, skinned BigGuy beside a twisting cube among static
// meshes behind a wall (triangle occluder) instead of the built-in scene.
//
// Usage: bench-scene-image [--frames N] [--width W] [--height H] [--tess L]
//                          [--back-patch METHOD] [--gpu-points] [--every K]
//                          [--scene built-in|character] [--plan] [--calibration FILE]
//   prints every K-th frame (default 10) and the frames with a lost pixel or over 0.01%
//   differing, then the worst figures and medians over all frames and views; exits 1 when
//   a pixel was lost or a frame differed by 0.01% or more.
#include "adapters/scene_assets.h"
#include "adapters/scene_file.h"
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/measure/calibrate.h"
#include "osd_cull/plan/planner.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/session/scene_player.h"
#include "osd_cull/vk/context.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

struct Args {
  uint32_t frames = 300;
  uint32_t width = 160;
  uint32_t height = 120;
  uint32_t tess = 4;
  std::string backPatch = "ncone";
  bool gpuPoints = false;
  uint32_t every = 10;
  std::string scene = "built-in";
  bool plan = false;
  std::string calibration;
};

// A skinned, displaced BigGuy and a twisting cube among static meshes, a wall in front.
std::string characterScene(uint32_t frames) {
  return R"({"version": 1,
  "settings": {"frameCount": )" +
         std::to_string(frames) + R"(, "framesPerSecond": 24},
  "meshes": [
    {"name": "guy", "file": "characters/bigguy.obj", "level": 2,
     "animation": {"deformer": "skin", "rig": "limbs", "joints": 4, "swingDegrees": 25},
     "displacement": {"map": "procedural", "scale": 0.4}},
    {"name": "twister", "builtIn": "creased-cube", "level": 2,
     "animation": {"deformer": "twist", "axis": 2, "amount": 0.4}},
    {"name": "torus", "builtIn": "torus", "level": 2},
    {"name": "pawn", "file": "shapes/catmark_pawn.obj", "level": 2}],
  "instances": [
    {"name": "guy", "mesh": "guy", "transform": {"scale": 0.05}},
    {"name": "twister", "mesh": "twister", "transform": {"translate": [3, 1, 0.5]}},
    {"name": "torus", "mesh": "torus", "transform": {"translate": [-3, 2, 0.5]}},
    {"name": "pawn", "mesh": "pawn", "transform": {"translate": [0, 6, 0], "scale": 1.5}},
    {"name": "far torus", "mesh": "torus", "transform": {"translate": [20, 60, 3]}}],
  "occluders": [{"box": {"min": [-1.5, -4, -1], "max": [1.5, -3.8, 0.6]}}],
  "views": [{"name": "main", "camera": {"eye": [2, -12, 4], "target": [0, 0, 1]},
             "path": {"orbit": {"degreesPerSecond": 10}}}]})";
}

// Per view (and per view and instance): what each frame measured.
struct Worst {
  uint64_t lost = 0;
  double differing = 0.0;  // share of the image
  uint32_t frame = 0;
};
struct Series {
  Series(size_t views, size_t instances)
      : culledShare(views),
        tesRatio(views),
        culledMs(views),
        plainMs(views),
        plannedMs(views),
        predictedMs(views),
        plannedLost(views, 0),
        choices(views, std::vector<std::map<std::string, uint32_t>>(instances)),
        worst(views) {}
  std::vector<std::vector<double>> culledShare, tesRatio, culledMs, plainMs, plannedMs, predictedMs;
  std::vector<uint64_t> plannedLost;
  // Per view and instance: how many frames each stage choice ran.
  std::vector<std::vector<std::map<std::string, uint32_t>>> choices;
  std::vector<Worst> worst;
};

// --scene: the built-in scene (with a sun view) or the character scene, at the image size.
scene::LoadedScene loadBenchScene(const Args& a) {
  if (a.scene != "built-in" && a.scene != "character")
    throw Error("--scene: '" + a.scene + "' is neither built-in nor character");
  scene::LoadedScene s = a.scene == "built-in"
                             ? scene::builtInScene(a.frames)
                             : adapters::loadScene(adapters::parseScene(
                                   characterScene(a.frames), "character scene", bench::dataDir()));
  s.description.settings.width = a.width;
  s.description.settings.height = a.height;
  if (a.scene == "built-in") {
    scene::ViewDescription sun;
    sun.name = "sun";
    sun.kind = scene::ViewDescription::Kind::Shadow;
    sun.lightDirection = {-0.4, 0.5, -1.0};
    sun.width = sun.height = a.height;
    s.description.views.push_back(sun);
  }
  return s;
}

// The per-view summary over all frames.
void printSummary(const scene::LoadedScene& s, const session::ScenePlayer& player,
                  const Series& series, uint32_t frames) {
  std::printf("\nsummary over %u frames (worst: largest over all frames; medians per frame)\n",
              frames);
  std::printf("%-5s %10s %15s %11s %14s %15s %12s\n", "view", "worst lost", "worst differing",
              "at frame", "median culled", "median TES/plain", "median ms c/p");
  for (size_t v = 0; v < player.viewCount(); ++v)
    std::printf("%-5s %10llu %14.4f%% %11u %13.1f%% %15.3f %6.2f/%.2f\n",
                s.description.views[v].name.c_str(),
                static_cast<unsigned long long>(series.worst[v].lost),
                100.0 * series.worst[v].differing, series.worst[v].frame,
                100.0 * bench::median(series.culledShare[v]), bench::median(series.tesRatio[v]),
                bench::median(series.culledMs[v]), bench::median(series.plainMs[v]));
}

// --plan: the planned frame against all stages and unculled, and what the plan chose.
void printPlanSummary(const scene::LoadedScene& s, const session::ScenePlayer& player,
                      const session::ScenePlayer& planned, const Series& series) {
  std::printf(
      "\nplan (medians per frame, ms; planned, all stages and unculled interleaved in each "
      "frame)\n%-5s %9s %9s %9s %16s %14s %12s\n",
      "view", "planned", "all", "unculled", "planned/better", "predicted/meas", "lost pixels");
  for (size_t v = 0; v < player.viewCount(); ++v) {
    const double p = bench::median(series.plannedMs[v]), all = bench::median(series.culledMs[v]),
                 none = bench::median(series.plainMs[v]);
    std::printf("%-5s %9.2f %9.2f %9.2f %16.3f %14.3f %12llu\n",
                s.description.views[v].name.c_str(), p, all, none, p / std::min(all, none),
                bench::median(series.predictedMs[v]) / p,
                static_cast<unsigned long long>(series.plannedLost[v]));
  }
  for (size_t v = 0; v < player.viewCount(); ++v)
    for (size_t i = 0; i < player.instanceCount(); ++i) {
      std::string line;
      for (const auto& [choice, n] : series.choices[v][i])
        line += (line.empty() ? "" : ", ") + choice + " (" + std::to_string(n) + ")";
      std::printf("planned %s / %s: %s\n", s.description.views[v].name.c_str(),
                  s.description.instances[i].name.c_str(), line.c_str());
    }
  for (const session::MeshWork& w : planned.work())
    std::printf("planned mesh '%s': %s, %llu point updates, %llu bounds dispatches\n",
                w.mesh.c_str(), w.deforms ? "deforms" : "static",
                static_cast<unsigned long long>(w.pointUpdates),
                static_cast<unsigned long long>(w.boundsDispatches));
  for (size_t v = 0; v < player.viewCount(); ++v)
    std::printf("view %s: %zu CullFrame(s) built for the plan's choices\n",
                s.description.views[v].name.c_str(), planned.cullFrameCount(v));
}

int run(const Args& a) {
  scene::LoadedScene s = loadBenchScene(a);

  vulkan::Context context;
  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = a.tess;
  options.render.cullBackFaces = true;
  options.cull.backPatch = a.backPatch;
  session::ScenePlayer player(
      context, s, options, a.gpuPoints ? frame::PointUpdatePath::Gpu : frame::PointUpdatePath::Cpu);
  std::printf(
      "scene: %s, %zu instances, %u patches, %zu views, %u frames, tess %u, %s, %s "
      "point update, device %s\n",
      s.description.source.c_str(), player.instanceCount(), player.patchCount(), player.viewCount(),
      a.frames, a.tess, a.backPatch.c_str(), a.gpuPoints ? "GPU" : "CPU",
      context.info().name.c_str());
  for (const std::string& line : player.describe()) std::printf("  %s\n", line.c_str());
  // --plan: the same scene played by a planned player, like for like.
  std::unique_ptr<plan::Planner> planner;
  std::unique_ptr<session::ScenePlayer> planned;
  if (a.plan) {
    const plan::Calibration calibration = measure::deviceCalibration(context, a.calibration);
    std::printf("plan: calibration of %s%s\n", calibration.key.device.c_str(),
                calibration.quick ? " (quick)" : "");
    planner = std::make_unique<plan::Planner>(calibration);
    planned = std::make_unique<session::ScenePlayer>(
        context, s, options,
        a.gpuPoints ? frame::PointUpdatePath::Gpu : frame::PointUpdatePath::Cpu, planner.get());
  }
  Series series(player.viewCount(), player.instanceCount());
  auto& [culledShare, tesRatio, culledMs, plainMs, plannedMs, predictedMs, plannedLost, choices,
         worst] = series;
  std::vector<std::unique_ptr<frame::RenderTarget>> plannedPlain;
  if (planned)
    for (size_t v = 0; v < player.viewCount(); ++v)
      plannedPlain.push_back(std::make_unique<frame::RenderTarget>(
          context, player.target(v).width(), player.target(v).height()));

  std::vector<std::unique_ptr<frame::RenderTarget>> plain;
  for (size_t v = 0; v < player.viewCount(); ++v)
    plain.push_back(std::make_unique<frame::RenderTarget>(context, player.target(v).width(),
                                                          player.target(v).height()));
  uint32_t failedFrames = 0;
  std::printf("\n%6s %-5s %9s %8s %6s %11s %10s %9s %9s\n", "frame", "view", "culled", "covered",
              "lost", "differing", "TES ratio", "culled ms", "plain ms");
  for (uint32_t f = 0; f < a.frames; ++f) {
    // The planned and the all-stages frame alternate which runs first.
    std::vector<session::ViewFrame> plannedViews;
    if (planned && f % 2 == 0) plannedViews = planned->render(f);
    const std::vector<session::ViewFrame> views = player.render(f);
    if (planned && f % 2 == 1) plannedViews = planned->render(f);
    bool failed = false;
    for (size_t v = 0; v < plannedViews.size(); ++v) {
      plannedMs[v].push_back(plannedViews[v].stats.totalMs());
      double predicted = 0.0;
      for (const plan::Plan& p : plannedViews[v].plans)
        predicted += p.predicted.totalMs() - p.predicted.updateMs;
      predictedMs[v].push_back(predicted);
      for (size_t i = 0; i < plannedViews[v].plans.size(); ++i)
        ++choices[v][i][plannedViews[v].plans[i].stages.describe()];
      const frame::ItemComparison c = planned->compareWithUnculled(v, *plannedPlain[v]).items;
      plannedLost[v] += c.lost;
      failed |= c.lost > 0 || c.differingShare() >= 1e-4;
    }
    for (size_t v = 0; v < views.size(); ++v) {
      // Each culled frame is followed by its unculled draw: the two are interleaved.
      const session::UnculledComparison u = player.compareWithUnculled(v, *plain[v]);
      const frame::ItemComparison& c = u.items;
      const frame::CullFrameStats& st = views[v].stats;
      const double differing = c.differingShare();
      const uint64_t culledTes =
                         st.pass1.tessEvaluationInvocations + st.pass2.tessEvaluationInvocations,
                     plainTes = u.unculled.statistics.tessEvaluationInvocations;
      const double ratio = plainTes ? double(culledTes) / double(plainTes) : 1.0;
      culledShare[v].push_back(double(st.culled()) / double(st.patchesTotal));
      tesRatio[v].push_back(ratio);
      culledMs[v].push_back(st.totalMs());
      plainMs[v].push_back(u.unculled.wallMs);
      if (c.lost > worst[v].lost || differing > worst[v].differing)
        worst[v] = {std::max(worst[v].lost, c.lost), std::max(worst[v].differing, differing), f};
      const bool bad = c.lost > 0 || differing >= 1e-4;
      failed |= bad;
      if (bad || f % a.every == 0 || f + 1 == a.frames)
        std::printf("%6u %-5s %8.1f%% %8llu %6llu %10.4f%% %10.3f %9.2f %9.2f%s\n", f,
                    views[v].view.c_str(), 100.0 * culledShare[v].back(),
                    static_cast<unsigned long long>(c.covered),
                    static_cast<unsigned long long>(c.lost), 100.0 * differing, ratio, st.totalMs(),
                    u.unculled.wallMs, bad ? "  <-- FAILS" : "");
    }
    failedFrames += failed;
  }

  printSummary(s, player, series, a.frames);
  if (planned) printPlanSummary(s, player, *planned, series);
  for (const session::MeshWork& w : player.work())
    std::printf("mesh '%s': %s, %llu point updates, %llu bounds dispatches\n", w.mesh.c_str(),
                w.deforms ? "deforms" : "static", static_cast<unsigned long long>(w.pointUpdates),
                static_cast<unsigned long long>(w.boundsDispatches));
  std::printf("frames failing (a pixel lost or >= 0.01%% differing): %u of %u\n", failedFrames,
              a.frames);
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::fprintf(stderr, "validation reported %llu messages\n",
                 static_cast<unsigned long long>(log->count()));
    return 1;
  }
  return failedFrames == 0 ? 0 : 1;
}

}  // namespace
}  // namespace osd_cull

int main(int argc, char** argv) {
  return osd_cull::bench::run("bench-scene-image", [&] {
    osd_cull::Args a;
    const bool go = osd_cull::bench::CommandLine("bench-scene-image", "bench_scene_image.cpp")
                        .number("--frames", a.frames, 1)
                        .number("--width", a.width, 1)
                        .number("--height", a.height, 1)
                        .number("--tess", a.tess, 1)
                        .text("--back-patch", a.backPatch)
                        .flag("--gpu-points", a.gpuPoints)
                        .number("--every", a.every, 1)
                        .text("--scene", a.scene)
                        .flag("--plan", a.plan)
                        .text("--calibration", a.calibration)
                        .parse(argc, argv);
    return go ? osd_cull::run(a) : 0;
  });
}
