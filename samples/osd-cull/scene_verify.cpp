// osd-cull verify SCENE: the checks of `verify MESH` on every instance of every frame.
#include "scene_verify.h"

#include "scene_source.h"
#include "verify_report.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/scene/scene_player.h"
#include "osd_cull/vk/context.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace osd_cull::cli {

const char* const kSceneVerifyUsage = R"(
Scene form: osd-cull verify SCENE.json|SEQUENCE|built-in:scene --frames N --views V [options]
On each of N frames (animations and instance motion evaluated), checks every method on every
instance (culled in its own coordinates with view · model, each alone, as the mesh form)
from the scene's own views at that frame and V random whole-scene views. Totals are summed
over instances and frames; the JSON has the mesh form's fields plus "frames".
  --frames N      frames from the scene's frameStart (default 2)
  --views V       random views per frame (default 4); --seed, --width, --height (default 128)
  --methods, --tess, --sample, --image-check, --no-oracle, --surface-exact, --json,
  --device, --validate as above
)";

namespace {}  // namespace

int verifyScene(Args& args) {
  const uint32_t frames = static_cast<uint32_t>(args.integer("frames", 1, 100000).value_or(2));
  const uint32_t views = static_cast<uint32_t>(args.integer("views", 0, 1000000).value_or(4));
  const uint64_t seed = static_cast<uint64_t>(args.integer("seed", 0, 1L << 62).value_or(1));
  const auto methodsText = args.value("methods");
  const uint32_t tess = static_cast<uint32_t>(args.integer("tess", 1, 64).value_or(4));
  const uint32_t width = static_cast<uint32_t>(args.integer("width", 1, 16384).value_or(128));
  const uint32_t height = static_cast<uint32_t>(args.integer("height", 1, 16384).value_or(128));
  const int sample = static_cast<int>(args.integer("sample", 0, 256).value_or(0));
  const bool imageCheck = args.flag("image-check");
  const bool noOracle = args.flag("no-oracle");
  const bool surfaceExact = args.flag("surface-exact");
  const auto jsonPath = args.value("json");
  const auto device = args.value("device");
  const bool validate = args.flag("validate");
  const std::string argument = args.positional().at(0);
  if (args.positional().size() > 1)
    throw Error("expected one SCENE, got '" + args.positional()[1] + "' too");
  args.finish();
  if (imageCheck && noOracle)
    throw Error("--image-check compares with the oracle's draw; drop --no-oracle");
  std::vector<std::string> methods = {"frustum", "tcone", "ncone", "tangent-plane"};
  if (methodsText) methods = splitList(*methodsText);
  for (const auto& m : methods) frame::cullMethod(m);  // reject unknown names early

  scene::LoadedScene loaded = loadSceneArgument(argument, frames);
  vulkan::ContextOptions contextOptions;
  contextOptions.device = device.value_or("");
  contextOptions.validation = validate;
  vulkan::Context context(contextOptions);
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = tess;
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.oracle = !noOracle;
  options.samplingGrid = sample;
  options.imageCheck = imageCheck;
  options.drawnTriangles = !surfaceExact;
  scene::ScenePlayer player(context, loaded, {});
  const scene::SceneDescription& d = loaded.description;
  std::printf(
      "scene: %s, %zu instances, %u patches, %u frames from %u, %zu scene view(s) + %u "
      "random views per frame, tess %u, device %s\n",
      d.source.c_str(), player.instanceCount(), player.patchCount(), frames, d.settings.frameStart,
      d.views.size(), views, tess, context.info().name.c_str());

  std::vector<std::unique_ptr<frame::CullVerifier>> verifiers(player.instanceCount());
  std::map<std::string, frame::MethodTotals> totals;
  std::vector<std::pair<std::string, std::string>> skipped;
  uint64_t checkedViews = 0;
  for (uint32_t f = d.settings.frameStart; f < d.settings.frameStart + frames; ++f) {
    player.seek(f);
    std::vector<frame::Camera> cameras;
    for (size_t v = 0; v < player.viewCount(); ++v) cameras.push_back(player.camera(v));
    frame::ViewSetOptions vo;
    vo.set = frame::ViewSet::WholeObject;
    vo.count = views;
    vo.seed = seed + f;
    vo.width = width;
    vo.height = height;
    if (views > 0)
      for (const frame::Camera& c : frame::randomViews(player.bounds(), vo)) cameras.push_back(c);
    for (size_t i = 0; i < player.instanceCount(); ++i) {
      const scene::SceneMesh& mesh = loaded.meshes[d.instances[i].mesh];
      // A deforming instance is checked on this frame's points: a fresh verifier, whose
      // passes build their cones from those points.
      if (!verifiers[i] || mesh.animation) {
        verifiers[i] = std::make_unique<frame::CullVerifier>(context, player.patches(i), methods,
                                                             mesh.validity, options);
        if (f == d.settings.frameStart)
          for (const auto& s : verifiers[i]->skipped())
            skipped.emplace_back(s.first + " on " + d.instances[i].name, s.second);
      }
      for (const frame::Camera& c : cameras)
        verifiers[i]->verifyView(frame::instanceCamera(c, player.model(i)));
      if (mesh.animation) {
        for (const frame::MethodTotals& t : verifiers[i]->totals()) {
          auto [it, added] = totals.emplace(t.name, t);
          if (!added) accumulate(it->second, t);
        }
      }
    }
    checkedViews += cameras.size();
    std::fprintf(stderr, "verify: frame %u, %zu views\n", f, cameras.size());
  }
  for (size_t i = 0; i < verifiers.size(); ++i)
    if (!loaded.meshes[d.instances[i].mesh].animation)
      for (const frame::MethodTotals& t : verifiers[i]->totals()) {
        auto [it, added] = totals.emplace(t.name, t);
        if (!added) accumulate(it->second, t);
      }
  for (const auto& [name, why] : skipped)
    std::printf("skipped %s: %s\n", name.c_str(), why.c_str());
  std::vector<frame::MethodTotals> ordered;
  for (const std::string& m : methods)
    if (totals.count(m)) ordered.push_back(totals.at(m));
  const uint32_t perInstance = player.patchCount() / uint32_t(player.instanceCount());
  const VerifyVerdict verdict = printVerifyTables(ordered, perInstance, options.oracle,
                                                  surfaceExact, sample > 0 || imageCheck);
  if (jsonPath) {
    nlohmann::ordered_json out;
    out["scene"] = d.source;
    out["instances"] = player.instanceCount();
    out["patches"] = player.patchCount();
    out["frames"] = frames;
    out["views"] = checkedViews;
    out["random_views_per_frame"] = views;
    out["seed"] = seed;
    out["width"] = width;
    out["height"] = height;
    out["tess"] = tess;
    out["device"] = context.info().name;
    out["methods"] = nlohmann::ordered_json::array();
    for (const auto& t : ordered)
      out["methods"].push_back(methodJson(t, perInstance, options.oracle));
    out["skipped"] = nlohmann::ordered_json::array();
    for (const auto& [name, why] : skipped)
      out["skipped"].push_back({{"name", name}, {"reason", why}});
    out["ok"] = verdict.ok;
    out["ok_except_silhouette_chords"] = verdict.okButSilhouettes;
    std::ofstream file(*jsonPath);
    if (!(file << out.dump(2) << "\n")) throw Error("cannot write " + *jsonPath);
    std::printf("\nwrote %s\n", jsonPath->c_str());
  }
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  if (!verdict.okButSilhouettes) std::cerr << "verify: FAILED (see the tables)\n";
  return verdict.okButSilhouettes ? 0 : 1;
}

}  // namespace osd_cull::cli
