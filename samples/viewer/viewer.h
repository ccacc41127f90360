#pragma once
/// \file viewer.h
/// \brief `osd-cull view`: an interactive window on a patch mesh or the built-in scene,
/// drawn with osd_cull's renderer and cull frame, presented through a Vulkan swapchain
/// (GLFW; lavapipe presents to X11, so it runs under Xvfb too), with a Dear ImGui HUD.
/// Scriptable for tests: --frames N --screenshot FILE --script "KEYS".
///
/// Everything it shows is a scene (scene/loaded_scene.h) played by session::ScenePlayer: a
/// scene file or the built-in scene with its animations (deforming meshes, moving
/// instances, camera paths), or a single mesh wrapped as a one-instance static scene.

#include "view_state.h"

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/patch/patch_set.h"
#include "osd_cull/plan/planner.h"
#include "osd_cull/scene/loaded_scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::viewer {

/// \brief What the viewer draws: a loaded scene (its first perspective view is the scene
/// camera of key `v`; the viewer drops the others) and the orbit camera's framing.
struct ViewerScene {
  scene::LoadedScene scene;
  glm::dvec3 up{0.0, 0.0, 1.0};
  glm::dvec3 viewDirection{0.55, -1.0, 0.45};  ///< from the scene center towards the eye
};

/// \brief A static one-instance scene of `patches` (object = world coordinates) and
/// `occluders`, whose back-patch culling runs as `backPatch` says; its scene camera looks
/// along -viewDirection at the patches.
ViewerScene staticScene(PatchSet patches, std::vector<frame::TriangleMesh> occluders,
                        const bound::BackPatchValidity& backPatch, const glm::dvec3& up,
                        const glm::dvec3& viewDirection);

/// \brief A loaded scene in the viewer: framed from its first perspective view.
/// \throws osd_cull::Error when it has no instances or no perspective view.
ViewerScene playedScene(scene::LoadedScene scene);

struct ViewerOptions {
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t frames = 0;                    ///< stop after this many frames; 0: until closed
  std::optional<std::string> screenshot;  ///< PNG of the window's last frame (HUD included)
  std::string script;                     ///< see parseScript()
  /// A timed diagnostic frame every this many frames gives the HUD its ms per pass
  /// (PassTiming); 0: never.
  uint32_t timePassesEvery = 30;
  std::string device;       ///< as vulkan::ContextOptions::device
  bool validate = false;    ///< validation layers; any message fails the run
  bool printFrames = true;  ///< one line of figures per frame on stdout
  ViewState initial;
  /// Makes the effect plan's planner for the viewer's device (null: no plan, e.g. no
  /// calibration); called once after the device is made. Unset: no plan.
  std::function<std::unique_ptr<plan::Planner>(vulkan::Context&)> makePlanner;
};

/// \brief Runs the viewer until the window closes, `q` is pressed or `frames` have been
/// drawn. Returns the process exit code (1 when validation reported messages).
/// \throws osd_cull::Error for a bad script, no display, or a device that cannot present.
int runViewer(ViewerScene& scene, const ViewerOptions& options);

}  // namespace osd_cull::viewer
