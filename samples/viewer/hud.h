#pragma once
/// \file hud.h
/// \brief The viewer's heads-up display (Dear ImGui): per-frame figures (patches drawn by
/// pass, culled by stage, TES invocations, ms per pass) and a live plot of cull rate and
/// frame time, drawn over the swapchain image after the view is blitted into it.

#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/vk/handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::viewer {

class Swapchain;
class Window;

/// \brief What the HUD shows for one frame.
struct HudFigures {
  std::string device, scene, cull, tessellation, mode;
  std::string animation;  ///< the animation frame and whether it plays
  std::string camera;     ///< orbit or the scene's
  std::string timing;     ///< where the ms per pass come from (PassTiming::describe)
  uint32_t patches = 0;
  uint32_t drawnPass1 = 0, drawnPass2 = 0;
  uint32_t culledFrustum = 0, culledBackPatch = 0, culledOcclusion = 0;
  uint64_t tesInvocations = 0;
  double pass1Ms = 0, pyramidMs = 0, cullMs = 0, pass2Ms = 0, frameMs = 0;
  std::string plan;  ///< the effect plan's current choice and its reason; empty without a plan
  enum class Legend { None, Status, PatchType } legend = Legend::None;  ///< colours shown
  std::vector<std::string> notes;
  /// \brief The patch counts of a frame: drawn per pass, culled per stage, TES invocations.
  void counts(const frame::CullFrameStats& s) {
    drawnPass1 = s.drawnPass1;
    drawnPass2 = s.drawnPass2;
    culledFrustum = s.culledFrustum;
    culledBackPatch = s.culledBackPatch;
    culledOcclusion = s.culledOcclusion;
    tesInvocations = s.pass1.tessEvaluationInvocations + s.pass2.tessEvaluationInvocations;
  }
};

class Hud {
 public:
  /// \brief Sets up Dear ImGui for `window` with a render pass on `swapchain`'s format.
  Hud(vulkan::Context& context, Window& window, const Swapchain& swapchain);
  ~Hud();
  Hud(const Hud&) = delete;
  Hud& operator=(const Hud&) = delete;

  /// \brief Framebuffers for the swapchain's current images (after a resize).
  void attach(const Swapchain& swapchain);
  /// \brief Builds this frame's interface from `figures`: a compact window (cull stages,
  /// the plan's choice, counts, ms, two small plots, the legend of the colours shown),
  /// details folded, and `keys` in a section open on first start; `show` false draws nothing.
  void build(const HudFigures& figures, const std::string& keys, bool show);
  /// \brief Records the interface into `cmd` over swapchain image `image`, which must be in
  /// COLOR_ATTACHMENT_OPTIMAL; it stays in that layout.
  void record(VkCommandBuffer cmd, uint32_t image);
  /// \brief True when the interface wants the mouse or the keyboard this frame.
  bool wantsMouse() const;
  bool wantsKeyboard() const;

 private:
  vulkan::Context& context_;
  VkExtent2D extent_{};
  vulkan::UniqueRenderPass renderPass_;
  vulkan::UniqueDescriptorPool pool_;
  std::vector<vulkan::UniqueFramebuffer> framebuffers_;
  std::deque<float> cullRate_, frameMs_;
};

}  // namespace osd_cull::viewer
