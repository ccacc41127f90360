#pragma once
/// \file viewer.h
/// \brief `osd-cull view`: an interactive window on a patch mesh or the built-in scene,
/// drawn with osd_cull's renderer and cull frame, presented through a Vulkan swapchain
/// (GLFW; lavapipe presents to X11, so it runs under Xvfb too), with a Dear ImGui HUD.
/// Scriptable for tests: --frames N --screenshot FILE --script "KEYS".

#include "view_state.h"

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::viewer {

/// \brief What the viewer draws.
struct ViewerScene {
  PatchSet patches;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0.0, 0.0, 1.0};
  glm::dvec3 viewDirection{0.55, -1.0, 0.45};  ///< from the scene center towards the eye
  bound::BackPatchValidity backPatch;          ///< whether back-patch culling may run
};

struct ViewerOptions {
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t frames = 0;                    ///< stop after this many frames; 0: until closed
  std::optional<std::string> screenshot;  ///< PNG of the window's last frame (HUD included)
  std::string script;                     ///< see parseScript()
  std::string device;                     ///< as vulkan::ContextOptions::device
  bool validate = false;                  ///< validation layers; any message fails the run
  bool printFrames = true;                ///< one line of figures per frame on stdout
  ViewState initial;
};

/// \brief Runs the viewer until the window closes, `q` is pressed or `frames` have been
/// drawn. Returns the process exit code (1 when validation reported messages).
/// \throws osd_cull::Error for a bad script, no display, or a device that cannot present.
int runViewer(const ViewerScene& scene, const ViewerOptions& options);

}  // namespace osd_cull::viewer
