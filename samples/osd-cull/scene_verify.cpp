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

namespace {

/// \brief Adds to `methods` the displaced bound each displaced mesh is culled with (an
/// occlusion method; the other meshes skip it).
void addDisplacedKernels(std::vector<std::string>& methods, const scene::LoadedScene& loaded) {
  for (const scene::SceneMesh& mesh : loaded.meshes)
    if (const std::string kernel =
            bound::displacedKernelName(mesh.displacedExtension, mesh.displacedBox);
        mesh.displacementMap && std::find(methods.begin(), methods.end(), kernel) == methods.end())
      methods.push_back(kernel);
}

/// \brief The views of scene frame `f` (the player is at it): the scene's own, then
/// `views` random whole-scene views (seed + f).
std::vector<frame::Camera> frameCameras(const session::ScenePlayer& player, const VerifyArgs& args,
                                        uint32_t f) {
  const uint32_t views = args.views.value_or(4);
  std::vector<frame::Camera> cameras;
  for (size_t v = 0; v < player.viewCount(); ++v) cameras.push_back(player.camera(v));
  frame::ViewSetOptions vo;
  vo.set = frame::ViewSet::WholeObject;
  vo.count = views;
  vo.seed = args.seed + f;
  vo.width = args.width.value_or(128);
  vo.height = args.height.value_or(128);
  if (views > 0)
    for (const frame::Camera& c : frame::randomViews(player.bounds(), vo)) cameras.push_back(c);
  return cameras;
}

/// \brief A verifier of instance `i` at scene frame `f`: a deforming instance's tcone and
/// ncone (and displaced kernel) read the cones the player's GPU bounds pass computed for
/// this frame, as its frames are culled with (ScenePlayer); a displaced one gets its map.
std::unique_ptr<frame::CullVerifier> instanceVerifier(vulkan::Context& context,
                                                      session::ScenePlayer& player,
                                                      const scene::LoadedScene& loaded, size_t i,
                                                      const std::vector<std::string>& methods,
                                                      frame::VerifyOptions options, uint32_t f) {
  const scene::SceneDescription& d = loaded.description;
  const scene::SceneMesh& mesh = loaded.meshes[d.instances[i].mesh];
  if (frame::DynamicPatchMesh* dynamic = player.dynamicMesh(i); dynamic && mesh.validity.enabled)
    for (const std::string& m : methods)
      if (const bound::BackPatchMethod ref = frame::cullMethod(m).reference;
          ref == bound::BackPatchMethod::TCone || ref == bound::BackPatchMethod::NCone)
        options.cullData[ref] = &dynamic->cullData(ref);
  if (mesh.displacementMap) {
    options.displacementMap = &*mesh.displacementMap;
    options.uvCorners = mesh.extraction.uvCorners;
    // A deforming displaced instance: its displaced kernel reads the cones the player's
    // GPU bounds pass computed for this frame (as `render` culls it), the reference
    // gets them read back with the exact Dmin/Dmax.
    if (frame::DynamicPatchMesh* dynamic = player.dynamicMesh(i)) {
      options.displacedCullData[mesh.displacedExtension] = &dynamic->displacedCullData(
          *mesh.displacementMap, mesh.extraction.uvCorners, mesh.displacedExtension);
      if (f == d.settings.frameStart)
        std::printf("%s: %s reads the cones of the GPU bounds pass (deforming, displaced)\n",
                    d.instances[i].name.c_str(),
                    bound::displacedKernelName(mesh.displacedExtension, mesh.displacedBox).c_str());
    }
  }
  return std::make_unique<frame::CullVerifier>(context, player.patches(i), methods, mesh.validity,
                                               options);
}

/// \brief Adds a verifier's per-method totals into `totals`.
void addTotals(std::map<std::string, frame::MethodTotals>& totals,
               const frame::CullVerifier& verifier) {
  for (const frame::MethodTotals& t : verifier.totals()) {
    auto [it, added] = totals.emplace(t.name, t);
    if (!added) accumulate(it->second, t);
  }
}

/// \brief The totals over every instance and frame with what was skipped, and the number
/// of views checked per instance.
struct SceneTotals {
  std::map<std::string, frame::MethodTotals> byMethod;
  std::vector<std::pair<std::string, std::string>> skipped;
  uint64_t checkedViews = 0;
};

/// \brief Checks every instance from every view of each frame. A deforming instance is
/// checked on each frame's points by a fresh verifier (its passes build their cones from
/// them) whose totals are added at once; the others keep one verifier, added at the end.
SceneTotals verifyFrames(vulkan::Context& context, session::ScenePlayer& player,
                         const scene::LoadedScene& loaded, const VerifyArgs& args,
                         const std::vector<std::string>& methods,
                         const frame::VerifyOptions& options) {
  const scene::SceneDescription& d = loaded.description;
  const uint32_t frames = args.frames.value_or(2);
  SceneTotals totals;
  std::vector<std::unique_ptr<frame::CullVerifier>> verifiers(player.instanceCount());
  for (uint32_t f = d.settings.frameStart; f < d.settings.frameStart + frames; ++f) {
    player.seek(f);
    const std::vector<frame::Camera> cameras = frameCameras(player, args, f);
    for (size_t i = 0; i < player.instanceCount(); ++i) {
      const bool deforming = bool(loaded.meshes[d.instances[i].mesh].animation);
      if (!verifiers[i] || deforming) {
        verifiers[i] = instanceVerifier(context, player, loaded, i, methods, options, f);
        if (f == d.settings.frameStart)
          for (const auto& s : verifiers[i]->skipped())
            totals.skipped.emplace_back(s.first + " on " + d.instances[i].name, s.second);
      }
      for (const frame::Camera& c : cameras)
        verifiers[i]->verifyView(frame::instanceCamera(c, player.model(i)));
      if (deforming) addTotals(totals.byMethod, *verifiers[i]);
    }
    totals.checkedViews += cameras.size();
    std::fprintf(stderr, "verify: frame %u, %zu views\n", f, cameras.size());
  }
  for (size_t i = 0; i < verifiers.size(); ++i)
    if (!loaded.meshes[d.instances[i].mesh].animation) addTotals(totals.byMethod, *verifiers[i]);
  return totals;
}

/// \brief Writes the scene run's settings, the per-method totals, what was skipped and the
/// verdict to --json (the mesh form's fields plus "frames").
/// \throws osd_cull::Error when the file cannot be written.
void writeSceneVerifyJson(const VerifyArgs& args, const scene::SceneDescription& d,
                          const session::ScenePlayer& player, const vulkan::Context& context,
                          const SceneTotals& totals,
                          const std::vector<frame::MethodTotals>& ordered, uint32_t perInstance,
                          bool oracle, const VerifyVerdict& verdict) {
  nlohmann::ordered_json out;
  out["scene"] = d.source;
  out["instances"] = player.instanceCount();
  out["patches"] = player.patchCount();
  out["frames"] = args.frames.value_or(2);
  out["views"] = totals.checkedViews;
  out["random_views_per_frame"] = args.views.value_or(4);
  out["seed"] = args.seed;
  out["width"] = args.width.value_or(128);
  out["height"] = args.height.value_or(128);
  out["tess"] = args.tess;
  out["device"] = context.info().name;
  out["methods"] = nlohmann::ordered_json::array();
  for (const auto& t : ordered) out["methods"].push_back(methodJson(t, perInstance, oracle));
  finishVerifyJson(std::move(out), totals.skipped, verdict, args.json);
}

}  // namespace

int verifyScene(const VerifyArgs& args) {
  const uint32_t frames = args.frames.value_or(2);
  if (args.source.scheme) throw UsageError("--scheme does not apply to a scene");
  if (args.imageCheck && args.noOracle)
    throw UsageError("--image-check compares with the oracle's draw; drop --no-oracle");
  std::vector<std::string> methods = {"frustum", "tcone", "ncone", "tangent-plane"};
  if (!args.methods.empty()) methods = splitList(args.methods);
  if (!args.json.empty()) checkOutputFile(args.json, "--json", {".json"});

  scene::LoadedScene loaded = loadSceneArgument(*args.source.path, frames);
  addDisplacedKernels(methods, loaded);
  vulkan::Context context(args.device);
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = args.tess;
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.oracle = !args.noOracle;
  options.samplingGrid = args.sample;
  options.imageCheck = args.imageCheck;
  options.drawnTriangles = !args.surfaceExact;
  session::ScenePlayer player(context, loaded, {});
  const scene::SceneDescription& d = loaded.description;
  std::printf(
      "scene: %s, %zu instances, %u patches, %u frames from %u, %zu scene view(s) + %u "
      "random views per frame, tess %u, device %s\n",
      d.source.c_str(), player.instanceCount(), player.patchCount(), frames, d.settings.frameStart,
      d.views.size(), args.views.value_or(4), args.tess, context.info().name.c_str());

  const SceneTotals totals = verifyFrames(context, player, loaded, args, methods, options);
  printSkipped(totals.skipped);
  std::vector<frame::MethodTotals> ordered;
  for (const std::string& m : methods)
    if (totals.byMethod.count(m)) ordered.push_back(totals.byMethod.at(m));
  const uint32_t perInstance = player.patchCount() / uint32_t(player.instanceCount());
  const VerifyVerdict verdict = printVerifyTables(
      ordered, perInstance, options.oracle, args.surfaceExact, args.sample > 0 || args.imageCheck);
  if (!args.json.empty())
    writeSceneVerifyJson(args, d, player, context, totals, ordered, perInstance, options.oracle,
                         verdict);
  const vulkan::ValidationLog* log = context.validationLog();
  return finishVerify(verdict, log ? log->count() : 0);
}

}  // namespace osd_cull::cli
