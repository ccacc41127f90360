// osd-cull view: the interactive viewer (samples/viewer/), when built with GLFW and Dear
// ImGui (libglfw3-dev, libimgui-dev).
#include "command.h"
#include "mesh_patches.h"
#include "mesh_source.h"

#include "osd_cull/error.h"
#include "osd_cull/scene/default_scene.h"

#if OSD_CULL_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

#include <filesystem>
#include <iostream>

namespace osd_cull::cli {
namespace {

const char* kUsage = R"(Usage: osd-cull view [MESH] [options]

Opens a window on MESH (or the built-in scene) drawn with the tessellation pipeline and
culled as the keys say, with a HUD of per-frame figures (patches drawn by pass, culled by
stage, TES invocations, ms per pass) and a live plot of cull rate and frame time. Needs an
X11 display: on a machine without one, run under `xvfb-run -a`.

Options:
  --level N              adaptive isolation level, 0..10 (default 2)
  --endcap gregory|bspline  end caps of irregular patches (default gregory)
  --scheme catmark|loop|bilinear  override the scheme (default: file-name prefix)
  --width W --height H   window size (default 1280 x 720)
  --tess N               initial uniform tessellation level (default 4)
  --cull all|none        initial culling (default none; keys 1 2 3 c switch stages)
  --frames N             stop after N frames (default: run until the window closes)
  --screenshot FILE.png  with --frames: write the window's last frame (HUD included)
  --script "STEPS"       keys to press, e.g. "@2 c @4 s": `@N` waits for frame N, a key
                         name presses it (as below; also plus, minus, space, esc),
                         orbit:YAW,PITCH and zoom:FACTOR move the camera
  --no-hud               start with the HUD hidden (key h)
  --device X             Vulkan device: index or name substring
  --validate             enable the Vulkan validation layers (any message: exit 1)

Keys:
)";

#if OSD_CULL_HAVE_VIEWER
int run(Args& args) {
  viewer::ViewerOptions o;
  o.width = static_cast<uint32_t>(args.integer("width", 16, 16384).value_or(1280));
  o.height = static_cast<uint32_t>(args.integer("height", 16, 16384).value_or(720));
  o.initial.tessLevel = static_cast<uint32_t>(args.integer("tess", 1, 64).value_or(4));
  const std::string cull = args.value("cull").value_or("none");
  if (cull != "all" && cull != "none")
    throw Error("--cull: expected all or none, got '" + cull + "'");
  o.initial.frustum = o.initial.backPatch = o.initial.occlusion = cull == "all";
  o.frames = static_cast<uint32_t>(args.integer("frames", 1, 10000000).value_or(0));
  o.screenshot = args.value("screenshot");
  o.script = args.value("script").value_or("");
  o.initial.showHud = !args.flag("no-hud");
  o.device = args.value("device").value_or("");
  o.validate = args.flag("validate");
  const PatchOptions patchOptions = patchOptionsFromArgs(args);
  const MeshSource source = meshSourceFromArgs(args);
  args.finish();
  if (o.screenshot && o.frames == 0) throw Error("--screenshot needs --frames N");
  if (o.screenshot) {
    const std::filesystem::path dir = std::filesystem::path(*o.screenshot).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
      throw Error("--screenshot: directory " + dir.string() + " does not exist");
  }
  viewer::ViewerScene scene;
  if (!source.path) {
    scene::Scene demo = scene::defaultScene(patchOptions);
    scene.patches = std::move(demo.patches);
    scene.occluders = std::move(demo.occluders);
    scene.up = demo.up;
    scene.viewDirection = demo.viewDirection;
    scene.backPatch = {true, "built-in scene: closed cages, normals outward by construction"};
  } else {
    if (!std::filesystem::exists(*source.path)) throw Error(*source.path + ": no such file");
    const LoadedMesh loaded = loadMeshSource(source);
    MeshPatches mesh = meshPatches(loaded, patchOptions);
    scene.patches = std::move(mesh.patches);
    scene.backPatch = mesh.backPatch;
    scene.up = loaded.bezier ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
    scene.viewDirection = loaded.bezier ? glm::dvec3(0.6, -1.0, 0.5) : glm::dvec3(0.45, 0.35, 1.0);
  }
  return viewer::runViewer(scene, o);
}
#else
int run(Args&) {
  throw Error(
      "this osd-cull was built without the viewer: install libglfw3-dev and "
      "libimgui-dev and rebuild");
}
#endif

std::string usage() {
#if OSD_CULL_HAVE_VIEWER
  return std::string(kUsage) + viewer::keyHelp();
#else
  return kUsage;
#endif
}

const Registration kRegistration({"view",
                                  "interactive viewer with a HUD (GLFW window, Vulkan swapchain)",
                                  usage(),
                                  {"no-hud", "validate"},
                                  run});

}  // namespace
}  // namespace osd_cull::cli
