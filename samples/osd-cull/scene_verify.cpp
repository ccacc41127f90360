// osd-cull verify SCENE: the checks of `verify MESH` on every instance of every frame.
#include "scene_verify.h"

#include "option_checks.h"
#include "scene_source.h"
#include "verify_report.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/session/scene_player.h"
#include "osd_cull/vk/context.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace osd_cull::cli {

const char* const kSceneVerifyUsage =
    R"(Scene form: osd-cull verify SCENE.json|SEQUENCE|built-in:scene --frames N --views V
On each of N frames (animations and instance motion evaluated), checks every method on every
instance (culled in its own coordinates with view · model, each alone, as the mesh form)
from the scene's own views at that frame and V random whole-scene views. Totals are summed
over instances and frames; the JSON has the mesh form's fields plus "frames". A deforming
mesh's tcone and ncone use the cones the GPU bounds pass computed for the frame; a displaced
mesh is also checked with its displaced kernel (e.g. acon-caf), a deforming displaced one
with the displaced cones its GPU bounds pass computed for the frame, as render culls it.)";

int verifyScene(const VerifyArgs& args) {
  const uint32_t frames = args.frames.value_or(2);
  const uint32_t views = args.views.value_or(4);
  const uint64_t seed = args.seed;
  const uint32_t tess = args.tess;
  const uint32_t width = args.width.value_or(128);
  const uint32_t height = args.height.value_or(128);
  const int sample = args.sample;
  const bool imageCheck = args.imageCheck;
  const bool noOracle = args.noOracle;
  const bool surfaceExact = args.surfaceExact;
  const std::string& argument = *args.source.path;
  if (args.source.scheme) throw UsageError("--scheme does not apply to a scene");
  if (imageCheck && noOracle)
    throw UsageError("--image-check compares with the oracle's draw; drop --no-oracle");
  std::vector<std::string> methods = {"frustum", "tcone", "ncone", "tangent-plane"};
  if (!args.methods.empty()) methods = splitList(args.methods);
  if (!args.json.empty()) checkOutputFile(args.json, "--json", {".json"});

  scene::LoadedScene loaded = loadSceneArgument(argument, frames);
  // A displaced mesh is also checked with the displaced bound it is culled with (an
  // occlusion method; the other meshes skip it).
  for (const scene::SceneMesh& mesh : loaded.meshes)
    if (const std::string kernel =
            bound::displacedKernelName(mesh.displacedExtension, mesh.displacedBox);
        mesh.displacementMap && std::find(methods.begin(), methods.end(), kernel) == methods.end())
      methods.push_back(kernel);
  vulkan::Context context(args.device);
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = tess;
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.oracle = !noOracle;
  options.samplingGrid = sample;
  options.imageCheck = imageCheck;
  options.drawnTriangles = !surfaceExact;
  session::ScenePlayer player(context, loaded, {});
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
        frame::VerifyOptions instanceOptions = options;
        // A deforming instance's tcone and ncone read the cones the player's GPU bounds pass
        // computed for this frame, as its frames are culled with (ScenePlayer).
        if (frame::DynamicPatchMesh* dynamic = player.dynamicMesh(i);
            dynamic && mesh.validity.enabled)
          for (const std::string& m : methods)
            if (const bound::BackPatchMethod ref = frame::cullMethod(m).reference;
                ref == bound::BackPatchMethod::TCone || ref == bound::BackPatchMethod::NCone)
              instanceOptions.cullData[ref] = &dynamic->cullData(ref);
        if (mesh.displacementMap) {
          instanceOptions.displacementMap = &*mesh.displacementMap;
          instanceOptions.uvCorners = mesh.extraction.uvCorners;
          // A deforming displaced instance: its displaced kernel reads the cones the player's
          // GPU bounds pass computed for this frame (as `render` culls it), the reference
          // gets them read back with the exact Dmin/Dmax.
          if (frame::DynamicPatchMesh* dynamic = player.dynamicMesh(i)) {
            instanceOptions.displacedCullData[mesh.displacedExtension] =
                &dynamic->displacedCullData(*mesh.displacementMap, mesh.extraction.uvCorners,
                                            mesh.displacedExtension);
            if (f == d.settings.frameStart)
              std::printf(
                  "%s: %s reads the cones of the GPU bounds pass (deforming, displaced)\n",
                  d.instances[i].name.c_str(),
                  bound::displacedKernelName(mesh.displacedExtension, mesh.displacedBox).c_str());
          }
        }
        verifiers[i] = std::make_unique<frame::CullVerifier>(context, player.patches(i), methods,
                                                             mesh.validity, instanceOptions);
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
  if (!args.json.empty()) {
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
    std::ofstream file(args.json);
    if (!(file << out.dump(2) << "\n")) throw Error(args.json + ": cannot write");
    std::printf("\nwrote %s\n", args.json.c_str());
  }
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  if (!verdict.okButSilhouettes) std::cerr << "verify: FAILED (see the tables)\n";
  return verdict.okButSilhouettes ? 0 : 1;
}

}  // namespace osd_cull::cli
