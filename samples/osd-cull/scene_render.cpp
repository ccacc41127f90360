// osd-cull render SCENE.json|SEQUENCE: plays a scene frame by frame (scene::ScenePlayer),
// every view culled by its own two-pass frame, and keeps each frame's image.
#include "scene_render.h"

#include "cull_options.h"
#include "cull_report.h"
#include "scene_source.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/draw/png_io.h"
#include "osd_cull/scene/scene_player.h"
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

// Creates `dir` and proves a file can be written there, before any frame is rendered.
void checkWritable(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path probe = dir / ".osd-cull-write-test";
  std::ofstream out(probe);
  if (ec || !out) throw Error("--out-dir " + dir.string() + ": cannot write there");
  out.close();
  fs::remove(probe, ec);
}

std::string frameFile(const std::string& view, const char* kind, uint32_t frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "_%s%04u.png", kind, frame);
  return view + name;
}

}  // namespace

const char* const kSceneRenderUsage = R"(
Scene form: osd-cull render SCENE.json|SEQUENCE|built-in:scene [options]
Plays a scene file (docs/scene-format.md), an OBJ sequence (walk/frame_####.obj or
name[0-58].obj) or the built-in scene; every view of every frame runs the two-pass culled
frame (Niessner & Loop) over the shared meshes, each instance with its own status.
  --frames N             frames to play (default: the scene's frameCount)
  --out-dir D            write D/<view>_NNNN.png for every frame and view (checked writable
                         before rendering)
  --out FILE.png         the last frame of the first view
  --cull MODE            as above; default all (frustum + back-patch + occlusion)
  --tess N               uniform tessellation level (default 4)
  --width W --height H   image size of views that do not give their own
  --compare              also draw every frame without culling (same tessellation, back-face
                         culling, image size) and print what culling saved
  --status-view          also write D/<view>_status_NNNN.png: every patch colored by its
                         status, seen from 120 degrees around the scene
  --stats FILE.json      per-frame, per-view figures as JSON
  --device X, --validate as above
)";

int renderScene(Args& args) {
  const auto frames = args.integer("frames", 1, 1000000);
  const auto outDir = args.value("out-dir");
  const auto out = args.value("out");
  const uint32_t tess = static_cast<uint32_t>(args.integer("tess", 1, 64).value_or(4));
  const bool compare = args.flag("compare");
  const bool statusView = args.flag("status-view");
  const auto statsPath = args.value("stats");
  const auto width = args.integer("width", 1, 16384);
  const auto height = args.integer("height", 1, 16384);
  const auto device = args.value("device");
  const bool validate = args.flag("validate");
  const bool cullGiven = args.value("cull").has_value();
  CullChoice cull = cullChoiceFromArgs(args);
  if (!cullGiven) cull.mode = "all";
  const std::string argument = args.positional().at(0);
  if (args.positional().size() > 1)
    throw Error("expected one SCENE, got '" + args.positional()[1] + "' too");
  args.finish();
  if (statusView && !outDir) throw Error("--status-view writes into --out-dir; give one");
  if (outDir) checkWritable(*outDir);

  scene::LoadedScene loaded = loadSceneArgument(argument, frames.value_or(0));
  if (width) loaded.description.settings.width = uint32_t(*width);
  if (height) loaded.description.settings.height = uint32_t(*height);
  const scene::SceneSettings& settings = loaded.description.settings;
  const uint32_t frameCount = frames ? uint32_t(*frames) : settings.frameCount;

  vulkan::ContextOptions contextOptions;
  contextOptions.device = device.value_or("");
  contextOptions.validation = validate;
  vulkan::Context context(contextOptions);
  frame::CullFrameOptions options = cull.frame;
  options.render.tessellation.uniformLevel = tess;
  options.render.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.cull = cullSettings(cull, {false, "set per mesh"});
  // Back faces are culled in the draws exactly when back-patch culling may run: like for
  // like, the unculled comparison draws the same way.
  options.render.cullBackFaces = !options.cull.backPatch.empty();
  scene::ScenePlayer player(context, loaded, options);
  std::cout << "device: " << context.info().name << "\n";
  std::cout << "scene: " << loaded.description.source << ", " << player.instanceCount()
            << " instances, " << player.patchCount() << " patches, " << loaded.occluders.size()
            << " occluders, " << player.viewCount() << " view(s), " << frameCount << " frames at "
            << settings.framesPerSecond << " fps, cull " << cull.mode << "\n";
  for (const std::string& line : player.describe()) std::cout << "  " << line << "\n";
  for (size_t i = 0; i < player.instanceCount(); ++i)
    if (const frame::CullPass* pass = player.cullFrame(0).cullPass(i);
        pass && !pass->backPatchNote().empty())
      std::cout << "  note: " << pass->backPatchNote() << "\n";

  std::unique_ptr<frame::RenderTarget> baseline;
  nlohmann::json jsonFrames = nlohmann::json::array();
  for (uint32_t f = settings.frameStart; f < settings.frameStart + frameCount; ++f) {
    const std::vector<scene::ViewFrame> views = player.render(f);
    for (size_t v = 0; v < views.size(); ++v) {
      const scene::ViewFrame& vf = views[v];
      std::printf("view %s %s\n", vf.view.c_str(), cullFrameLine(f, vf.stats).c_str());
      nlohmann::json j = cullFrameJson(f, vf.stats);
      j["view"] = vf.view;
      frame::RenderTarget& target = player.target(v);
      if (outDir)
        frame::writePng(
            fs::path(*outDir) / frameFile(vf.view, "", f),
            frame::colorImage(target.width(), target.height(), target.readColor(context)));
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
        frame::writePng(
            fs::path(*outDir) / frameFile(vf.view, "status_", f),
            frame::colorImage(target.width(), target.height(), statusTarget.readColor(context)));
      }
      jsonFrames.push_back(std::move(j));
    }
    std::fflush(stdout);
  }
  if (outDir)
    std::cout << "wrote " << frameCount * player.viewCount() << " frames to " << *outDir << "\n";
  if (out) {
    frame::RenderTarget& target = player.target(0);
    frame::writePng(*out,
                    frame::colorImage(target.width(), target.height(), target.readColor(context)));
    std::cout << "wrote " << *out << "\n";
  }
  if (statsPath) {
    nlohmann::json doc{{"device", context.info().name},
                       {"scene", loaded.description.source},
                       {"cull", cull.mode},
                       {"frameCount", frameCount},
                       {"frames", jsonFrames}};
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
