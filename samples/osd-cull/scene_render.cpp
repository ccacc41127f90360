// osd-cull render SCENE.json|SEQUENCE: plays a scene frame by frame (session::ScenePlayer),
// every view culled by its own two-pass frame, and keeps each frame's image.
#include "scene_render.h"

#include "cull_options.h"
#include "cull_report.h"
#include "option_checks.h"
#include "plan_options.h"
#include "scene_source.h"

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
void printScenePlans(const session::ViewFrame& vf, std::vector<plan::Plan>& printed) {
  printed.resize(vf.plans.size());
  for (size_t i = 0; i < vf.plans.size(); ++i) {
    const plan::Plan& p = vf.plans[i];
    plan::Plan& last = printed[i];
    const bool first = last.mesh.empty();
    if (!first && p.stages == last.stages && plan::planChange(last, p).empty()) continue;
    const std::string who =
        "instance " + std::to_string(i) + " '" + p.mesh + "' in view '" + p.view + "'";
    printPlanChange(first ? nullptr : &last, p, std::cout, who);
    last = p;
  }
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
  const std::optional<uint32_t> frames = args.frames;
  const std::optional<std::string> outDir =
      args.outDir.empty() ? std::nullopt : std::optional(args.outDir);
  const std::optional<std::string> out = args.out.empty() ? std::nullopt : std::optional(args.out);
  const uint32_t tess = args.tess;
  const bool compare = args.compare;
  const bool statusView = args.statusView;
  const std::optional<std::string> statsPath =
      args.stats.empty() ? std::nullopt : std::optional(args.stats);
  const std::optional<uint32_t> width = args.width, height = args.height;
  CullChoice cull = cullChoice(args.cull);
  if (args.cull.mode.empty()) cull.mode = "all";
  const std::string& argument = *args.source.path;
  if (args.source.scheme) throw UsageError("--scheme does not apply to a scene");
  if (args.adaptive > 0.0 || !args.camera.empty() || args.orbitDegrees != 0.0 || args.ids ||
      args.debugColors || !args.occluders.empty() || !args.pyramidDir.empty())
    throw UsageError(
        "--adaptive, --camera, --orbit, --ids, --debug-colors, --occluders and --pyramid-dir "
        "apply to the mesh form, not to a scene");
  if (statusView && !outDir) throw UsageError("--status-view writes into --out-dir; give one");
  if (out) checkOutputFile(*out, "--out", {".png"});
  if (statsPath) checkOutputFile(*statsPath, "--stats", {".json"});
  if (outDir) prepareOutputDirectory(*outDir, "--out-dir");

  scene::LoadedScene loaded = loadSceneArgument(argument, frames.value_or(0));
  if (width) loaded.description.settings.width = uint32_t(*width);
  if (height) loaded.description.settings.height = uint32_t(*height);
  const scene::SceneSettings& settings = loaded.description.settings;
  const uint32_t frameCount = frames ? uint32_t(*frames) : settings.frameCount;

  vulkan::Context context(args.device);
  // The effect plan (docs/algorithms/plan.md, "Scenes"): without --cull, every instance in
  // every view is planned each frame; without a calibration the scene plays with --cull all.
  std::unique_ptr<plan::Planner> planner;
  const bool wantPlan = args.plan.mode == "auto" && args.cull.mode.empty();
  if (const std::string missing = wantPlan ? missingCalibration(args.plan, context) : "";
      !missing.empty())
    std::cout << "plan: off, playing with --cull all (" << missing << ")\n";
  else
    planner = makePlanner(args.plan, context, !args.cull.mode.empty(),
                          cull.backPatchMethodGiven ? cull.backPatchMethod : "", std::cout);
  frame::CullFrameOptions options = cull.frame;
  options.render.tessellation.uniformLevel = tess;
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
  std::cout << "device: " << context.info().name << "\n";
  std::cout << "scene: " << loaded.description.source << ", " << player.instanceCount()
            << " instances, " << player.patchCount() << " patches, " << loaded.occluders.size()
            << " occluders, " << player.viewCount() << " view(s), " << frameCount << " frames at "
            << settings.framesPerSecond << " fps, cull " << (planner ? "planned" : cull.mode)
            << "\n";
  for (const std::string& line : player.describe()) std::cout << "  " << line << "\n";
  if (!planner)
    for (size_t i = 0; i < player.instanceCount(); ++i)
      if (const frame::CullPass* pass = player.cullFrame(0).cullPass(i);
          pass && !pass->backPatchNote().empty())
        std::cout << "  note: " << pass->backPatchNote() << "\n";
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
      printScenePlans(vf, printed[v]);
      {
        std::optional<double> predicted;
        std::vector<plan::StageChoice> stages;
        for (const plan::Plan& p : vf.plans) {
          predicted = predicted.value_or(0.0) + p.predicted.totalMs() - p.predicted.updateMs;
          stages.push_back(p.stages);
        }
        summaries[v].add(vf.stats, predicted, !stages.empty() && stages != lastStages[v]);
        lastStages[v] = std::move(stages);
      }
      std::printf("view %s %s\n", vf.view.c_str(), cullFrameLine(f, vf.stats).c_str());
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
      frame::RenderTarget& target = player.target(v);
      if (outDir)
        adapters::writePng(
            fs::path(*outDir) / frameFile(vf.view, "", f),
            adapters::colorImage(target.width(), target.height(), target.readColor(context)));
      if (compare) {
        if (!baseline || baseline->width() != target.width() ||
            baseline->height() != target.height())
          baseline =
              std::make_unique<frame::RenderTarget>(context, target.width(), target.height());
        const frame::FrameStats plain = player.renderUnculled(v, *baseline);
        const uint64_t culledTes = tes(vf.stats),
                       plainTes = plain.statistics.tessEvaluationInvocations;
        const double saved = plainTes ? 100.0 * (1.0 - double(culledTes) / double(plainTes)) : 0.0;
        std::printf(
            "  vs unculled: patches drawn %u -> %u, TES invocations %llu -> %llu (%.1f%% saved), "
            "wall %.2f ms -> %.2f ms\n",
            plain.patchesDrawn, vf.stats.drawnPass1 + vf.stats.drawnPass2, u64(plainTes),
            u64(culledTes), saved, plain.wallMs, vf.stats.totalMs());
        j["unculled"] = plainFrameJson(f, plain);
      }
      if (statusView) {
        frame::RenderTarget statusTarget(context, target.width(), target.height());
        // Seen from 120 degrees around the scene, so that culled patches (back-facing,
        // behind the wall, outside the view) show in their colors.
        const frame::Camera side = frame::orbit(vf.camera, player.bounds().center(),
                                                loaded.description.views[v].up, 120.0);
        player.cullFrame(v).renderStatusView(statusTarget, side, player.occluders());
        adapters::writePng(
            fs::path(*outDir) / frameFile(vf.view, "status_", f),
            adapters::colorImage(target.width(), target.height(), statusTarget.readColor(context)));
      }
      jsonFrames.push_back(std::move(j));
    }
    std::fflush(stdout);
  }
  for (size_t v = 0; v < summaries.size(); ++v) {
    std::string text = summaries[v].summary().text();
    for (size_t at = 0; (at = text.find("summary:", at)) != std::string::npos; at += 8)
      text.replace(at, 8, "summary of view " + loaded.description.views[v].name + ":");
    std::cout << text << "\n";
  }
  if (outDir)
    std::cout << "wrote " << frameCount * player.viewCount() << " frames to " << *outDir << "\n";
  if (out) {
    frame::RenderTarget& target = player.target(0);
    adapters::writePng(
        *out, adapters::colorImage(target.width(), target.height(), target.readColor(context)));
    std::cout << "wrote " << *out << "\n";
  }
  if (statsPath) {
    nlohmann::json doc{{"device", context.info().name},
                       {"scene", loaded.description.source},
                       {"cull", planner ? std::string("plan") : cull.mode},
                       {"frameCount", frameCount},
                       {"frames", jsonFrames}};
    doc["summary"] = nlohmann::json::object();
    for (size_t v = 0; v < summaries.size(); ++v)
      doc["summary"][loaded.description.views[v].name] = summaryJson(summaries[v].summary());
    std::ofstream file(*statsPath);
    if (!(file << doc.dump(2) << "\n")) throw Error(*statsPath + ": cannot write");
    std::cout << "wrote " << *statsPath << "\n";
  }
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  return 0;
}

}  // namespace osd_cull::cli
