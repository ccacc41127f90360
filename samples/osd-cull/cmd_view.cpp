// osd-cull view: the interactive viewer (samples/viewer/), when built with GLFW and Dear
// ImGui (libglfw3-dev, libimgui-dev).
#include "command.h"
#include "device_options.h"
#include "mesh_patches.h"
#include "mesh_source.h"
#include "option_checks.h"
#include "plan_options.h"
#include "scene_source.h"

#include "osd_cull/error.h"
#include "osd_cull/scene/default_scene.h"

#if OSD_CULL_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace osd_cull::cli {
namespace {

const char* kDescription =
    R"(Opens a window on MESH drawn with the tessellation pipeline and culled as the keys say,
with a HUD of per-frame figures (patches drawn by pass, culled by stage, TES invocations,
ms per pass, the animation frame) and a live plot of cull rate and frame time. MESH may
also be a scene: a scene file (.json, docs/scene-format.md), an OBJ sequence pattern
(walk_###.obj) or built-in:scene; space plays its animations (deforming meshes, moving
instances, camera paths; v looks through its camera). Without MESH: the built-in static
scene. The ms per pass come from a timed diagnostic frame every --time-passes frames
(each pass submitted and waited for alone; the normal frame is one submission). Needs an
X11 display: on a machine without one, run under `xvfb-run -a`.)";

/// \brief The parsed options of `osd-cull view`.
struct ViewArgs {
  MeshSource source;
  PatchOptions patchOptions;
  std::optional<uint32_t> width;   ///< default 1280
  std::optional<uint32_t> height;  ///< default 720
  uint32_t tess = 4;
  std::string cull;  ///< empty: the plan (where calibrated)
  PlanArgs plan;
  uint32_t frames = 0;
  std::string screenshot;
  std::string script;
  bool noHud = false;
  uint32_t timePasses = 30;
  vulkan::ContextOptions device;
};

#if OSD_CULL_HAVE_VIEWER
int run(const ViewArgs& args) {
  viewer::ViewerOptions o;
  o.width = args.width.value_or(1280);
  o.height = args.height.value_or(720);
  o.initial.tessLevel = args.tess;
  o.initial.frustum = o.initial.backPatch = o.initial.occlusion = args.cull == "all";
  // The effect plan by default, as in `render` (docs/algorithms/plan.md); --cull or
  // --plan off fix the stages, said so.
  o.initial.plan = args.cull.empty() && args.plan.mode == "auto";
  o.makePlanner = [args](vulkan::Context& context) {
    return makePlanner(args.plan, context, !args.cull.empty(), "", std::cout);
  };
  o.frames = args.frames;
  if (!args.screenshot.empty()) o.screenshot = args.screenshot;
  o.script = args.script;
  o.timePassesEvery = args.timePasses;
  o.initial.showHud = !args.noHud;
  o.device = args.device.device;
  o.validate = args.device.validation;
  const PatchOptions& patchOptions = args.patchOptions;
  const MeshSource& source = args.source;
  if (o.screenshot && o.frames == 0) throw UsageError("--screenshot needs --frames N");
  if (o.screenshot) checkOutputFile(*o.screenshot, "--screenshot", {".png"});
  viewer::ViewerScene scene;
  if (!source.path) {
    scene::Scene demo = scene::defaultScene(patchOptions);
    scene =
        viewer::staticScene(std::move(demo.patches), std::move(demo.occluders),
                            {true, "built-in scene: closed cages, normals outward by construction"},
                            demo.up, demo.viewDirection);
  } else if (isSceneArgument(*source.path)) {
    scene = viewer::playedScene(loadSceneArgument(*source.path, 0));
    std::cout << "scene " << scene.scene.description.source << ": "
              << scene.scene.description.settings.frameCount << " frames at "
              << scene.scene.description.settings.framesPerSecond << " fps (space plays)\n";
  } else {
    if (!std::filesystem::exists(*source.path)) throw Error(*source.path + ": no such file");
    const LoadedMesh loaded = loadMeshSource(source);
    MeshPatches mesh = meshPatches(loaded, patchOptions);
    for (const std::string& note : mesh.notes) std::cout << "note: " << note << "\n";
    const glm::dvec3 up = loaded.bezier ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
    const glm::dvec3 direction =
        loaded.bezier ? glm::dvec3(0.6, -1.0, 0.5) : glm::dvec3(0.45, 0.35, 1.0);
    scene = viewer::staticScene(std::move(mesh.patches), {}, mesh.backPatch, up, direction);
  }
  return viewer::runViewer(scene, o);
}
#else
int run(const ViewArgs&) {
  throw Error(
      "this osd-cull was built without the viewer: install libglfw3-dev and "
      "libimgui-dev and rebuild");
}
#endif

Runner setup(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  addMeshOptions(app, args->source);
  addPatchOptions(app, args->patchOptions);
  addSizeOptions(app, args->width, args->height, 16, "1280 x 720");
  app.add_option("--tess", args->tess, "initial uniform tessellation level (default 4)")
      ->type_name("N")
      ->check(integerIn(1, 64));
  app.add_option("--cull", args->cull,
                 "initial culling by hand: all or none (default: the effect plan\n"
                 "chooses, key p; keys 1 2 3 c switch stages by hand)")
      ->type_name("MODE")
      ->check(oneOf({"all", "none"}));
  app.add_option("--frames", args->frames,
                 "stop after N frames (default: run until the window closes)")
      ->type_name("N")
      ->check(integerIn(1, 10000000));
  app.add_option("--screenshot", args->screenshot,
                 "with --frames: write the window's last frame (HUD included)")
      ->type_name("FILE.png");
  app.add_option("--script", args->script,
                 "keys to press, e.g. \"@2 c @4 s\": `@N` waits for frame N, a key\n"
                 "name presses it (as below; also plus, minus, space, esc),\n"
                 "orbit:YAW,PITCH, pan:RIGHT,UP and zoom:FACTOR move the camera, shot writes the\n"
                 "coming frame to FILE-frameN.png (FILE from --screenshot)")
      ->type_name("\"STEPS\"");
  app.add_flag("--no-hud", args->noHud, "start with the HUD hidden (key h)");
  app.add_option("--time-passes", args->timePasses,
                 "a timed diagnostic frame every N frames gives the HUD its ms per pass\n"
                 "(default 30; 0: never)")
      ->type_name("N")
      ->check(integerIn(0, 10000000));
  addDeviceOptions(app, args->device);
  addPlanOptions(app, args->plan);
  return [args] { return run(*args); };
}

std::string keys() {
#if OSD_CULL_HAVE_VIEWER
  return "Keys:\n" + viewer::keyHelp();
#else
  return {};
#endif
}

const Registration kRegistration({"view",
                                  "interactive viewer with a HUD (GLFW window, Vulkan swapchain)",
                                  kDescription, setup, keys()});

}  // namespace
}  // namespace osd_cull::cli
