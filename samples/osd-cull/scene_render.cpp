// osd-cull render SCENE.json|SEQUENCE: plays a scene frame by frame (session::ScenePlayer),
// every view culled by its own two-pass frame, and keeps each frame's image.
#include "scene_render.h"

#include "cull_options.h"
#include "cull_report.h"
#include "option_checks.h"
#include "plan_options.h"
#include "scene_source.h"

#include "adapters/image_legend.h"
#include "adapters/image_png.h"
#include "osd_cull/error.h"
#include "osd_cull/session/scene_player.h"
#include "osd_cull/vk/context.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace osd_cull::cli {
namespace {

namespace fs = std::filesystem;

unsigned long long u64(uint64_t v) { return static_cast<unsigned long long>(v); }

uint64_t tes(const frame::CullFrameStats& s) {
  return s.pass1.tessEvaluationInvocations + s.pass2.tessEvaluationInvocations;
}

std::string frameFile(const std::string& view, const char* kind, uint32_t frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "_%s%04u.png", kind, frame);
  return view + name;
}

// Prints each instance's plan of this frame that differs from the one printed last (all
// of them at the first frame), naming instance and view.
void printScenePlans(const session::ViewFrame& vf, std::vector<plan::Plan>& printed, bool verbose) {
  printed.resize(vf.plans.size());
  for (size_t i = 0; i < vf.plans.size(); ++i) {
    const plan::Plan& p = vf.plans[i];
    plan::Plan& last = printed[i];
    const bool first = last.mesh.empty();
    if (!first && p.stages == last.stages && plan::planChange(last, p).empty()) continue;
    const std::string who =
        "instance " + std::to_string(i) + " '" + p.mesh + "' in view '" + p.view + "'";
    printPlanChange(first ? nullptr : &last, p, std::cout, who, verbose);
    last = p;
  }
}

/// \brief The scene form's usage checks and output preparation: no mesh-form options,
/// --status-view with --out-dir, the output files' names.
/// \throws UsageError naming the option.
void checkSceneRenderArgs(const RenderArgs& args) {
  if (args.source.scheme) throw UsageError("--scheme does not apply to a scene");
  if (args.adaptive > 0.0 || !args.camera.empty() || args.orbitDegrees != 0.0 || args.ids ||
      args.debugColors || !args.occluders.empty() || !args.pyramidDir.empty())
    throw UsageError(
        "--adaptive, --camera, --orbit, --ids, --debug-colors, --occluders and --pyramid-dir "
        "apply to the mesh form, not to a scene");
  if (args.statusView && args.outDir.empty())
    throw UsageError("--status-view writes into --out-dir; give one");
  if (!args.out.empty()) checkOutputFile(args.out, "--out", {".png"});
  if (!args.stats.empty()) checkOutputFile(args.stats, "--stats", {".json"});
  if (!args.outDir.empty()) prepareOutputDirectory(args.outDir, "--out-dir");
}

/// \brief The effect plan (docs/algorithms/plan.md, "Scenes"): without --cull, every
/// instance in every view is planned each frame; without a calibration (null, said on
/// stdout) the scene plays with --cull all.
std::unique_ptr<plan::Planner> scenePlanner(const RenderArgs& args, vulkan::Context& context,
                                            const CullChoice& cull) {
  const bool wantPlan = args.plan.mode == "auto" && args.cull.mode.empty();
  if (const std::string missing = wantPlan ? missingCalibration(args.plan, context) : "";
      !missing.empty()) {
    std::cout << "plan: off, playing with --cull all (" << missing << ")\n";
    return nullptr;
  }
  return makePlanner(args.plan, context, !args.cull.mode.empty(),
                     cull.backPatchMethodGiven ? cull.backPatchMethod : "", std::cout);
}

/// \brief The device and scene lines, the player's description and, without a plan, the
/// back-patch notes of the instances' cull passes.
void printSceneHeader(const vulkan::Context& context, const scene::LoadedScene& loaded,
                      session::ScenePlayer& player, uint32_t frameCount, bool planned,
                      const std::string& cullMode) {
  std::cout << "device: " << context.info().name << "\n";
  std::cout << "scene: " << loaded.description.source << ", " << player.instanceCount()
            << " instances, " << player.patchCount() << " patches, " << loaded.occluders.size()
            << " occluders, " << player.viewCount() << " view(s), " << frameCount << " frames at "
            << loaded.description.settings.framesPerSecond << " fps, cull "
            << (planned ? "planned" : cullMode) << "\n";
  for (const std::string& line : player.describe()) std::cout << "  " << line << "\n";
  if (!planned)
    for (size_t i = 0; i < player.instanceCount(); ++i)
      if (const frame::CullPass* pass = player.cullFrame(0).cullPass(i);
          pass && !pass->backPatchNote().empty())
        std::cout << "  note: " << pass->backPatchNote() << "\n";
}

/// \brief Adds a view's frame to its summary: the predicted time of its plans (none
/// unplanned) and whether the plans' stages changed since `lastStages`.
void addToSummary(session::SummaryAccumulator& summary, std::vector<plan::StageChoice>& lastStages,
                  const session::ViewFrame& vf) {
  std::optional<double> predicted;
  std::vector<plan::StageChoice> stages;
  for (const plan::Plan& p : vf.plans) {
    predicted = predicted.value_or(0.0) + p.predicted.totalMs() - p.predicted.updateMs;
    stages.push_back(p.stages);
  }
  summary.add(vf.stats, predicted, !stages.empty() && stages != lastStages);
  lastStages = std::move(stages);
}

/// \brief A view's frame in --stats: the cull frame's figures, the view and its plans.
nlohmann::json viewFrameJson(uint32_t f, const session::ViewFrame& vf) {
  nlohmann::json j = cullFrameJson(f, vf.stats);
  j["view"] = vf.view;
  if (!vf.plans.empty()) {
    j["plans"] = nlohmann::json::array();
    for (const plan::Plan& p : vf.plans)
      j["plans"].push_back({{"instance", p.mesh},
                            {"stages", p.stages.describe()},
                            {"probe", p.probe},
                            {"update", p.update.on},
                            {"bounds", p.bounds.on},
                            {"predictedMs", p.predicted.totalMs()}});
  }
  return j;
}

/// \brief --compare: draws view `v` unculled into `baseline` (made at the view's size),
/// prints the line against the culled frame and returns its figures for --stats.
nlohmann::json compareUnculled(vulkan::Context& context, session::ScenePlayer& player, size_t v,
                               const session::ViewFrame& vf, uint32_t f,
                               std::unique_ptr<frame::RenderTarget>& baseline) {
  const frame::RenderTarget& target = player.target(v);
  if (!baseline || baseline->width() != target.width() || baseline->height() != target.height())
    baseline = std::make_unique<frame::RenderTarget>(context, target.width(), target.height());
  const frame::FrameStats plain = player.renderUnculled(v, *baseline);
  const uint64_t culledTes = tes(vf.stats), plainTes = plain.statistics.tessEvaluationInvocations;
  const double saved = plainTes ? 100.0 * (1.0 - double(culledTes) / double(plainTes)) : 0.0;
  std::printf(
      "  vs unculled: patches drawn %u -> %u, TES invocations %llu -> %llu (%.1f%% saved), "
      "wall %.2f ms -> %.2f ms\n",
      plain.patchesDrawn, vf.stats.drawnPass1 + vf.stats.drawnPass2, u64(plainTes), u64(culledTes),
      saved, plain.wallMs, vf.stats.totalMs());
  return plainFrameJson(f, plain);
}

/// \brief --status-view: view `v`'s status colors seen from 120 degrees around the scene
/// (so that culled patches, back-facing, behind the wall or outside the view, show in
/// their colors), written into `outDir`.
void writeStatusView(vulkan::Context& context, session::ScenePlayer& player,
                     const scene::LoadedScene& loaded, size_t v, const session::ViewFrame& vf,
                     uint32_t f, const std::string& outDir) {
  const frame::RenderTarget& target = player.target(v);
  frame::RenderTarget statusTarget(context, target.width(), target.height());
  const frame::Camera side =
      frame::orbit(vf.camera, player.bounds().center(), loaded.description.views[v].up, 120.0);
  player.cullFrame(v).renderStatusView(statusTarget, side, player.occluders());
  adapters::writePng(fs::path(outDir) / frameFile(vf.view, "status_", f),
                     adapters::withLegend(adapters::colorImage(target.width(), target.height(),
                                                               statusTarget.readColor(context)),
                                          adapters::statusLegend()));
}

/// \brief The end-of-run summary of each view, named after it.
void printSummaries(const std::vector<session::SummaryAccumulator>& summaries,
                    const scene::LoadedScene& loaded) {
  for (size_t v = 0; v < summaries.size(); ++v) {
    std::string text = summaries[v].summary().text();
    for (size_t at = 0; (at = text.find("summary:", at)) != std::string::npos; at += 8)
      text.replace(at, 8, "summary of view " + loaded.description.views[v].name + ":");
    std::cout << text << "\n";
  }
}

/// \brief Writes --stats: the device, scene, cull, every view's frames and each view's
/// summary.
/// \throws osd_cull::Error when the file cannot be written.
void writeSceneStats(const std::string& path, const vulkan::Context& context,
                     const scene::LoadedScene& loaded, const std::string& cull, uint32_t frameCount,
                     nlohmann::json jsonFrames,
                     const std::vector<session::SummaryAccumulator>& summaries) {
  nlohmann::json doc{{"device", context.info().name},
                     {"scene", loaded.description.source},
                     {"cull", cull},
                     {"frameCount", frameCount},
                     {"frames", std::move(jsonFrames)}};
  doc["summary"] = nlohmann::json::object();
  for (size_t v = 0; v < summaries.size(); ++v)
    doc["summary"][loaded.description.views[v].name] = summaryJson(summaries[v].summary());
  std::ofstream file(path);
  if (!(file << doc.dump(2) << "\n")) throw Error(path + ": cannot write");
  std::cout << "wrote " << path << "\n";
}

}  // namespace

const char* const kSceneRenderUsage =
    R"(Scene form: osd-cull render SCENE.json|SEQUENCE|built-in:scene [options]
Plays a scene file (docs/scene-format.md), an OBJ sequence (walk/frame_####.obj or
name[0-58].obj) or the built-in scene; every view of every frame runs the two-pass culled
frame (Niessner & Loop) over the shared meshes, each instance with its own status. It
takes --frames, --out-dir (DIR/<view>_NNNN.png per frame and view), --out (last frame of
the first view), --plan (auto, the default: every instance in every view gets the effect
plan each frame, printed when it changes; off: --cull all), --plan-calibration, --cull (a
fixed choice for all instances), --tess, --width/--height (views without their
own), --compare, --status-view (DIR/<view>_status_NNNN.png, seen from 120 degrees around
the scene), --stats, --device and --validate.)";

int renderScene(const RenderArgs& args) {
  CullChoice cull = cullChoice(args.cull);
  if (args.cull.mode.empty()) cull.mode = "all";
  checkSceneRenderArgs(args);
  scene::LoadedScene loaded = loadSceneArgument(*args.source.path, args.frames.value_or(0));
  if (args.width) loaded.description.settings.width = uint32_t(*args.width);
  if (args.height) loaded.description.settings.height = uint32_t(*args.height);
  const scene::SceneSettings& settings = loaded.description.settings;
  const uint32_t frameCount = args.frames ? uint32_t(*args.frames) : settings.frameCount;

  vulkan::Context context(args.device);
  const std::unique_ptr<plan::Planner> planner = scenePlanner(args, context, cull);
  frame::CullFrameOptions options = cull.frame;
  options.render.tessellation.uniformLevel = args.tess;
  options.render.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.cull = cullSettings(cull, {false, "set per mesh"});
  // Back faces are culled in the draws per mesh, from the mesh's own validity, in every
  // mode, --cull none included (session::ScenePlayer sets CullMesh::cullBackFaces and the
  // unculled comparison's PatchDraw::cullBackFaces): like for like.
  // The plan's point update: on the path the calibration measured cheaper.
  const plan::Calibration* calibration = planner ? &planner->calibration() : nullptr;
  const frame::PointUpdatePath pointUpdate =
      calibration && calibration->pointUpdateGpuMsPerPatch < calibration->pointUpdateCpuMsPerPatch
          ? frame::PointUpdatePath::Gpu
          : frame::PointUpdatePath::Cpu;
  session::ScenePlayer player(context, loaded, options, pointUpdate, planner.get());
  printSceneHeader(context, loaded, player, frameCount, planner != nullptr, cull.mode);
  // The last plan printed per (view, instance).
  std::vector<std::vector<plan::Plan>> printed(player.viewCount());

  std::unique_ptr<frame::RenderTarget> baseline;
  nlohmann::json jsonFrames = nlohmann::json::array();
  // The end-of-run summary of each view (session::SummaryAccumulator).
  std::vector<session::SummaryAccumulator> summaries(player.viewCount());
  std::vector<std::vector<plan::StageChoice>> lastStages(player.viewCount());
  for (uint32_t f = settings.frameStart; f < settings.frameStart + frameCount; ++f) {
    const std::vector<session::ViewFrame> views = player.render(f);
    for (size_t v = 0; v < views.size(); ++v) {
      const session::ViewFrame& vf = views[v];
      printScenePlans(vf, printed[v], args.verbose);
      addToSummary(summaries[v], lastStages[v], vf);
      std::printf("view %s %s\n", vf.view.c_str(), cullFrameLine(f, vf.stats).c_str());
      nlohmann::json j = viewFrameJson(f, vf);
      frame::RenderTarget& target = player.target(v);
      if (!args.outDir.empty())
        adapters::writePng(
            fs::path(args.outDir) / frameFile(vf.view, "", f),
            adapters::colorImage(target.width(), target.height(), target.readColor(context)));
      if (args.compare) j["unculled"] = compareUnculled(context, player, v, vf, f, baseline);
      if (args.statusView) writeStatusView(context, player, loaded, v, vf, f, args.outDir);
      jsonFrames.push_back(std::move(j));
    }
    std::fflush(stdout);
  }
  printSummaries(summaries, loaded);
  if (!args.outDir.empty())
    std::cout << "wrote " << frameCount * player.viewCount() << " frames to " << args.outDir
              << "\n";
  if (!args.out.empty()) {
    frame::RenderTarget& target = player.target(0);
    adapters::writePng(
        args.out, adapters::colorImage(target.width(), target.height(), target.readColor(context)));
    std::cout << "wrote " << args.out << "\n";
  }
  if (!args.stats.empty())
    writeSceneStats(args.stats, context, loaded, planner ? std::string("plan") : cull.mode,
                    frameCount, std::move(jsonFrames), summaries);
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  return 0;
}

}  // namespace osd_cull::cli
