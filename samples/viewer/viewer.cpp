#include "viewer.h"

#include "hud.h"
#include "swapchain.h"
#include "window.h"

#include "adapters/image_png.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/session/scene_player.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

namespace osd_cull::viewer {
namespace {

using Clock = std::chrono::steady_clock;

/// A surface destroyed with the instance it was made for (before the Context).
struct Surface {
  VkInstance instance;
  VkSurfaceKHR handle;
  ~Surface() { vkDestroySurfaceKHR(instance, handle, nullptr); }
};

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                  VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

/// The orbit camera of the state around the scene's bounds.
frame::Camera viewCamera(const ViewState& s, const frame::Bounds& bounds, const ViewerScene& scene,
                         uint32_t width, uint32_t height) {
  const frame::Camera base =
      frame::frameBounds(bounds, scene.viewDirection, scene.up, 40.0, width, height);
  const glm::dvec3 pivot = bounds.center();
  glm::dvec3 offset = base.eye() - pivot;
  const glm::dvec3 up = glm::normalize(scene.up);
  glm::dvec3 right = glm::cross(offset, up);
  if (glm::length(right) < 1e-12 * glm::length(offset)) right = glm::dvec3(1, 0, 0);
  const glm::dmat4 yaw = glm::rotate(glm::dmat4(1.0), glm::radians(s.yawDegrees), up);
  const glm::dmat4 pitch =
      glm::rotate(glm::dmat4(1.0), glm::radians(s.pitchDegrees), glm::normalize(right));
  offset = glm::dvec3(yaw * pitch * glm::dvec4(offset, 0.0)) * s.zoom;
  const double d = glm::length(offset), r = bounds.radius();
  // Middle-drag pan: the pivot moves along the view's right and up axes (scaled by zoom,
  // so a drag moves the model about as far on screen at any distance).
  glm::dvec3 viewRight = glm::cross(-offset, up);
  viewRight = glm::length(viewRight) > 1e-12 * d ? glm::normalize(viewRight) : glm::dvec3(1, 0, 0);
  const glm::dvec3 viewUp = glm::cross(viewRight, -offset / d);
  const glm::dvec3 shift = (s.panX * viewRight + s.panY * viewUp) * r * s.zoom;
  const double far = std::sqrt(d * d + glm::dot(shift, shift)) + r;  // the box from the eye
  return frame::Camera::lookAt(pivot + shift + offset, pivot + shift, up, 40.0, width, height,
                               std::max(d - r, (d + r) * 1e-4), far);
}

frame::RenderOptions renderOptions(const ViewState& s, const vulkan::Context& context,
                                   bool backFaces) {
  frame::RenderOptions o;
  o.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  if (s.adaptive) {
    o.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
    o.tessellation.pixelsPerSegment = s.pixelsPerSegment;
  } else {
    o.tessellation.uniformLevel = std::min(s.tessLevel, o.tessellation.maxLevel);
  }
  o.patchTypeColors = s.typeColors;
  o.wireframe = s.wireframe;
  o.cullBackFaces = backFaces;
  return o;
}

}  // namespace

ViewerScene staticScene(PatchSet patches, std::vector<frame::TriangleMesh> occluders,
                        const bound::BackPatchValidity& backPatch, const glm::dvec3& up,
                        const glm::dvec3& viewDirection) {
  ViewerScene v;
  v.up = up;
  v.viewDirection = viewDirection;
  scene::SceneDescription& d = v.scene.description;
  d.source = patches.source;
  scene::MeshDescription md;
  md.name = patches.source;
  md.recentre = false;
  d.meshes.push_back(md);
  scene::InstanceDescription inst;
  inst.name = patches.source;
  d.instances.push_back(inst);
  frame::Bounds bounds = frame::boundsOf(patches.points);
  for (const auto& m : occluders) bounds = frame::unite(bounds, frame::boundsOf(m.positions));
  scene::ViewDescription view;
  view.name = "default";
  view.up = up;
  view.target = bounds.center();
  view.eye = bounds.center() + glm::normalize(viewDirection) * (3.0 * bounds.radius());
  d.views.push_back(view);
  scene::SceneMesh mesh;
  mesh.name = patches.source;
  mesh.validity = backPatch;
  mesh.restBounds = frame::boundsOf(patches.points);
  mesh.extraction.patches = std::move(patches);
  v.scene.meshes.push_back(std::move(mesh));
  v.scene.occluders = std::move(occluders);
  return v;
}

ViewerScene playedScene(scene::LoadedScene loaded) {
  scene::SceneDescription& d = loaded.description;
  if (d.instances.empty()) throw Error("scene " + d.source + ": no instances to view");
  auto view = std::find_if(d.views.begin(), d.views.end(), [](const scene::ViewDescription& v) {
    return v.kind == scene::ViewDescription::Kind::Perspective;
  });
  if (view == d.views.end())
    throw Error("scene " + d.source + ": no perspective view to start the viewer from");
  ViewerScene v;
  v.up = view->up;
  v.viewDirection = view->eye - view->target;
  if (!(glm::length(v.viewDirection) > 0.0)) v.viewDirection = {0.55, -1.0, 0.45};
  d.views = {*view};
  v.scene = std::move(loaded);
  return v;
}

namespace {

/// \brief The device, window, swapchain and HUD of the viewer, made in the order their
/// lifetimes need (the surface dies before the Context's instance).
struct Display {
  Window window;
  vulkan::Context context;
  Surface surface;
  Swapchain swapchain;
  Hud hud;

  Display(const ViewerOptions& options, const std::string& title)
      : window(options.width, options.height, title),
        context(contextOptions(options)),
        surface{context.instance(), window.createSurface(context.instance())},
        swapchain(context, surface.handle, framebufferExtent(window).width,
                  framebufferExtent(window).height),
        hud(context, window, swapchain) {}

  /// \brief The Vulkan context the viewer asks for: presentation extensions on top of the
  /// options' device and validation.
  static vulkan::ContextOptions contextOptions(const ViewerOptions& options) {
    vulkan::ContextOptions o;
    o.device = options.device;
    o.validation = options.validate;
    o.instanceExtensions = Window::requiredInstanceExtensions();
    o.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    return o;
  }

  /// \brief The window's framebuffer size now (0 x 0 while minimised).
  static VkExtent2D framebufferExtent(Window& window) {
    uint32_t w = 0, h = 0;
    window.framebufferSize(w, h);
    return {w, h};
  }
};

/// \brief The command buffer, semaphores and fence of the viewer's one frame in flight.
struct FrameSync {
  vulkan::UniqueCommandPool pool;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vulkan::UniqueSemaphore acquired;
  vulkan::UniqueSemaphore rendered;
  vulkan::UniqueFence fence;

  explicit FrameSync(const vulkan::Context& context) {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    VkCommandPool rawPool = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateCommandPool(context.device(), &poolInfo, nullptr, &rawPool));
    pool = vulkan::UniqueCommandPool(context.device(), rawPool);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    OSD_CULL_VK(vkAllocateCommandBuffers(context.device(), &alloc, &cmd));
    VkSemaphoreCreateInfo semInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore rawAcquired = VK_NULL_HANDLE, rawRendered = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateSemaphore(context.device(), &semInfo, nullptr, &rawAcquired));
    acquired = vulkan::UniqueSemaphore(context.device(), rawAcquired);
    OSD_CULL_VK(vkCreateSemaphore(context.device(), &semInfo, nullptr, &rawRendered));
    rendered = vulkan::UniqueSemaphore(context.device(), rawRendered);
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence rawFence = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateFence(context.device(), &fenceInfo, nullptr, &rawFence));
    fence = vulkan::UniqueFence(context.device(), rawFence);
  }
};

/// \brief The number of patches over every instance of the scene.
/// \throws osd_cull::Error when there are none.
uint32_t scenePatchTotal(const ViewerScene& scene) {
  uint32_t total = 0;
  for (const scene::InstanceDescription& i : scene.scene.description.instances)
    total += scene.scene.meshes.at(i.mesh).extraction.patches.patchCount();
  if (total == 0) throw Error(scene.scene.description.source + ": no patches to view");
  return total;
}

/// \brief One note per mesh whose back-patch culling is off, with the validity's reason.
std::vector<std::string> backPatchNotesOf(const ViewerScene& scene) {
  std::vector<std::string> notes;
  for (const scene::SceneMesh& m : scene.scene.meshes)
    if (!m.validity.enabled)
      notes.push_back("back-patch culling off for '" + m.name + "': " + m.validity.reason);
  return notes;
}

/// \brief The viewer's frame loop: each frame reads the input, (re)makes the scene player
/// when the window size or the cull stages change, draws the view (by the plan or by
/// hand), blits it under the HUD to the swapchain, presents, prints its figures and writes
/// the screenshots the options ask for.
class ViewerLoop {
 public:
  ViewerLoop(ViewerScene& scene, const ViewerOptions& options, ScriptPlayer& script)
      : scene_(scene),
        description_(scene.scene.description),
        options_(options),
        script_(script),
        patchTotal_(scenePatchTotal(scene)),
        display_(options, "osd-cull view: " + description_.source),
        context_(display_.context),
        frameCount_(std::max(1u, description_.settings.frameCount)),
        timing_(options.timePassesEvery),
        sync_(context_),
        keys_(keyHelp()),
        backPatchNotes_(backPatchNotesOf(scene)) {
    std::cout << "device: " << context_.info().name << " (" << context_.info().driver << ")\n";
    state_ = options.initial;
    state_.maxTessLevel = context_.info().limits.maxTessellationGenerationLevel;
    // The effect plan, as in `osd-cull render`: on by default where the device is calibrated.
    planner_ = options.makePlanner ? options.makePlanner(context_) : nullptr;
    figures_.device = context_.info().name;
    figures_.scene = description_.source + ": " + std::to_string(description_.instances.size()) +
                     " instance(s), " + std::to_string(patchTotal_) + " patches";
    figures_.patches = patchTotal_;
    std::cout << "keys:\n" << keys_;
    for (const std::string& note : backPatchNotes_) std::cout << "note: " << note << "\n";
  }

  /// \brief Runs the frames; returns the exit code (1 when validation reported messages).
  int run() {
    for (uint32_t f = 0; options_.frames == 0 || f < options_.frames; ++f) {
      if (!display_.window.poll()) break;
      const auto start = Clock::now();
      const bool shot = readInput(f);
      if (state_.quit) break;
      if (state_.turntable) orbitCamera(state_, 1.0, 0.0);
      advanceAnimation(state_, frameCount_);
      const VkExtent2D window = Display::framebufferExtent(display_.window);
      if (window.width == 0 || window.height == 0) continue;  // minimised
      const VkExtent2D extent = matchSwapchain(window);
      const frame::RenderTarget& shown = drawView(f, extent);
      uint32_t image = 0;
      VkResult r = vkAcquireNextImageKHR(context_.device(), display_.swapchain.handle(), UINT64_MAX,
                                         sync_.acquired.get(), VK_NULL_HANDLE, &image);
      if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        recreateSwapchain(window);
        continue;
      }
      if (r != VK_SUBOPTIMAL_KHR) OSD_CULL_VK(r);
      display_.hud.build(figures_, keyHelpCompact(), state_.showHud);
      display_.window.setUiCapture(display_.hud.wantsMouse(), display_.hud.wantsKeyboard());
      const bool last = options_.frames != 0 && f + 1 == options_.frames;
      const bool capture = (last || shot) && options_.screenshot.has_value();
      vulkan::Buffer readback;
      if (capture)
        readback = vulkan::Buffer(context_, VkDeviceSize{extent.width} * extent.height * 4,
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, vulkan::MemoryUse::Readback);
      recordPresentation(shown, image, extent, capture ? &readback : nullptr);
      r = submitAndPresent(image);
      if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR)
        recreateSwapchain(window);
      else
        OSD_CULL_VK(r);
      figures_.frameMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      if (options_.printFrames) printFrame(f);
      std::fflush(stdout);
      if (capture) writeScreenshots(readback, extent, f, shot, last);
    }
    context_.waitIdle();
    if (const vulkan::ValidationLog* log = context_.validationLog(); log && log->count() > 0) {
      std::cerr << "validation reported " << log->count() << " messages\n";
      return 1;
    }
    return 0;
  }

 private:
  /// \brief Applies the script's steps and the window's keys and mouse to the state for
  /// frame `f`; returns whether the script takes a shot of this frame.
  bool readInput(uint32_t f) {
    for (const std::string& line : script_.beforeFrame(f, state_))
      std::cout << "key: " << line << "\n";
    const bool shot = script_.takeShot();
    const WindowInput input = display_.window.takeInput();
    for (const std::string& k : input.keys)
      if (auto line = pressKey(state_, k)) std::cout << "key: " << *line << "\n";
    orbitCamera(state_, -0.3 * input.orbitX, -0.3 * input.orbitY);
    zoomCamera(state_, std::pow(1.01, input.zoomY) * std::pow(0.9, input.wheel));
    panCamera(state_, -0.005 * input.panX, 0.005 * input.panY);  // the model follows the mouse
    return shot;
  }

  /// \brief Makes the swapchain again at the window's size (the player with it).
  void recreateSwapchain(VkExtent2D window) {
    display_.swapchain.recreate(window.width, window.height);
    display_.hud.attach(display_.swapchain);
    dropPlayer();
  }

  /// \brief The swapchain's extent, after making it again if the window was resized.
  VkExtent2D matchSwapchain(VkExtent2D window) {
    const VkExtent2D now = display_.swapchain.extent();
    if (window.width != now.width || window.height != now.height) recreateSwapchain(window);
    return display_.swapchain.extent();
  }

  /// \brief Forgets the player and its status target (made again on the next frame).
  void dropPlayer() {
    player_.reset();
    statusTarget_.reset();
    builtCull_.clear();
  }

  /// \brief Draws this frame's view into the player's target (or the status target) and
  /// fills the HUD's figures; returns the target to show.
  const frame::RenderTarget& drawView(uint32_t f, VkExtent2D extent) {
    const bool backPatchAllowed =
        std::any_of(scene_.scene.meshes.begin(), scene_.scene.meshes.end(),
                    [](const auto& m) { return m.validity.enabled; });
    const frame::RenderOptions render =
        renderOptions(state_, context_, state_.backPatch && backPatchAllowed);
    if (state_.plan && !planner_) {
      state_.plan = false;
      std::cout << "note: no effect plan in this viewer (no calibration of this device, or "
                   "--cull given): the stages are chosen by hand\n";
    }
    makePlayerFor(render, extent, f);
    const uint32_t sceneFrame = description_.settings.frameStart + state_.sceneFrame;
    if (shownFrame_ != sceneFrame) {
      player_->seek(sceneFrame);
      shownFrame_ = sceneFrame;
    }
    if (!framing_) framing_ = player_->bounds();
    const frame::Camera camera =
        state_.sceneCamera ? player_->camera(0)
                           : viewCamera(state_, *framing_, scene_, extent.width, extent.height);
    describeView(render, sceneFrame);
    const frame::RenderTarget* shown =
        state_.plan ? drawPlanned(camera) : drawByHand(f, render, camera);
    if (state_.backPatch || state_.plan)
      for (const std::string& note : backPatchNotes_) figures_.notes.push_back(note);
    return *shown;
  }

  /// \brief Makes the player again when it is missing or the cull stages changed: they
  /// are fixed when a CullFrame is made (with none, it culls nothing and draws every patch).
  void makePlayerFor(const frame::RenderOptions& render, VkExtent2D extent, uint32_t f) {
    if (player_ && state_.cullLabel() == builtCull_) return;
    dropPlayer();
    scene::ViewDescription& view = description_.views.front();
    view.width = extent.width;
    view.height = extent.height;
    frame::CullFrameOptions fo;
    fo.render = render;
    fo.cull.frustum = state_.frustum;
    fo.cull.backPatch = state_.backPatch ? state_.backPatchMethod : "";
    fo.cull.occlusion = state_.occlusion ? "hiz" : "";
    player_ = std::make_unique<session::ScenePlayer>(context_, scene_.scene, fo,
                                                     frame::PointUpdatePath::Cpu,
                                                     state_.plan ? planner_.get() : nullptr);
    statusTarget_ = std::make_unique<frame::RenderTarget>(context_, extent.width, extent.height);
    builtCull_ = state_.cullLabel();
    shownFrame_.reset();
    timing_.forget(f);
  }

  /// \brief The HUD's lines that describe the view: stages, tessellation, animation and
  /// camera (the notes start empty).
  void describeView(const frame::RenderOptions& render, uint32_t sceneFrame) {
    figures_.cull = state_.cullLabel() + (state_.freezeCull ? " (cull camera frozen)" : "");
    figures_.tessellation =
        state_.adaptive ? "adaptive, " + std::to_string(state_.pixelsPerSegment) + " px/segment"
                        : "uniform " + std::to_string(render.tessellation.uniformLevel);
    figures_.animation =
        frameCount_ < 2 ? "no animation (one frame)"
                        : "frame " + std::to_string(sceneFrame) + " (frames " +
                              std::to_string(description_.settings.frameStart) + "-" +
                              std::to_string(description_.settings.frameStart + frameCount_ - 1) +
                              "), " + (state_.playing ? "playing" : "paused");
    figures_.camera = state_.sceneCamera
                          ? "scene camera '" + description_.views.front().name + "'"
                          : std::string("orbit") + (state_.turntable ? " (turntable)" : "");
    figures_.notes.clear();
    figures_.plan.clear();
    figures_.legend = state_.typeColors ? HudFigures::Legend::PatchType : HudFigures::Legend::None;
  }

  /// \brief The plan draws the frame (session::ScenePlayer with a planner): the stages it
  /// chose for each instance and why, per-stage GPU times from the frame's own timestamps.
  const frame::RenderTarget* drawPlanned(const frame::Camera& camera) {
    player_->setCamera(0, camera);
    const session::ViewFrame view = player_->renderCurrent(planFrame_++).front();
    const frame::CullFrameStats& s = view.stats;
    figures_.counts(s);
    const bool timed = s.gpu.measured();
    figures_.pass1Ms = timed ? s.gpu.pass1 : s.frameMs;
    figures_.pyramidMs = timed ? s.gpu.pyramid : 0.0;
    figures_.cullMs = timed ? s.gpu.cull : 0.0;
    figures_.pass2Ms = timed ? s.gpu.pass2 : 0.0;
    figures_.timing = timed ? "GPU timestamps of this frame" : "wall clock (drawn without culling)";
    figures_.cull = "plan";
    for (const plan::Plan& p : view.plans) addPlanNotes(p);
    figures_.plan = planLine(view.plans);
    figures_.mode = view.culled ? "culled draw (plan)" : "all patches (the plan culls nothing)";
    if (state_.statusColors || state_.freezeCull)
      figures_.notes.push_back(
          "status colors and the frozen cull camera need the stages by "
          "hand (1, 2, 3 or c)");
    return &player_->target(0);
  }

  /// \brief The HUD's line of the plan: the first instance's current choice and the reason
  /// of its back-patch and occlusion effects (first clause), and how many more instances.
  static std::string planLine(const std::vector<plan::Plan>& plans) {
    if (plans.empty()) return "";
    const plan::Plan& p = plans.front();
    std::string line = p.mesh + ": " + p.stages.describe() + (p.probe ? " [re-probe]" : "");
    for (const auto& [kind, e] : p.effects())
      if (kind == plan::EffectKind::BackPatch || kind == plan::EffectKind::Occlusion)
        line += std::string("; ") + plan::toString(kind) + (e->on ? " on: " : " off: ") +
                e->reason.substr(0, e->reason.find(';'));
    if (plans.size() > 1) line += " (+" + std::to_string(plans.size() - 1) + " instances: details)";
    return line;
  }

  /// \brief The HUD's notes for one instance's plan: its stages and predicted times, then
  /// the first clause of each cull effect's reason.
  void addPlanNotes(const plan::Plan& p) {
    char line[160];
    std::snprintf(line, sizeof line, "%s: %s%s, predicted %.1f ms (%.1f without culling)",
                  p.mesh.c_str(), p.stages.describe().c_str(), p.probe ? " [re-probe]" : "",
                  p.predicted.totalMs(), p.predictedUnculled.totalMs());
    figures_.notes.push_back(line);
    for (const auto& [kind, e] : p.effects())
      if (kind == plan::EffectKind::Frustum || kind == plan::EffectKind::BackPatch ||
          kind == plan::EffectKind::Occlusion)
        figures_.notes.push_back(std::string("  ") + plan::toString(kind) +
                                 (e->on ? " on: " : " off: ") +
                                 e->reason.substr(0, e->reason.find(';')));
  }

  /// \brief Draws the frame with the stages chosen by hand (a timed frame now and then
  /// gives the ms per pass, PassTiming), or the status view colored by what the (frozen)
  /// cull camera did; returns the target drawn.
  const frame::RenderTarget* drawByHand(uint32_t f, const frame::RenderOptions& render,
                                        const frame::Camera& camera) {
    frame::CullFrame& cullFrame = player_->cullFrame(0);
    frame::CullFrameOptions fo = cullFrame.options();
    fo.render = render;
    if (!state_.freezeCull || !state_.anyCull()) {
      // Most frames are one submission; a timed one splits the passes (PassTiming).
      const bool timed = timing_.due(f);
      fo.timePasses = timed;
      cullFrame.setOptions(fo);
      const frame::CullFrameStats s = cullFrame.render(camera, player_->occluders());
      if (timed) timing_.record(f, s.pass1Ms, s.pyramidMs, s.cullMs, s.pass2Ms);
      figures_.counts(s);
    } else {
      fo.timePasses = false;
      cullFrame.setOptions(fo);
    }
    figures_.pass1Ms = timing_.pass1Ms();
    figures_.pyramidMs = timing_.pyramidMs();
    figures_.cullMs = timing_.cullMs();
    figures_.pass2Ms = timing_.pass2Ms();
    figures_.timing = timing_.describe(f);
    if (state_.anyCull() && (state_.statusColors || state_.freezeCull)) {
      // Every patch from the current camera, colored by what the (frozen) cull camera did.
      cullFrame.renderStatusView(*statusTarget_, camera, player_->occluders());
      figures_.mode = "status colors";
      figures_.legend = HudFigures::Legend::Status;
      return statusTarget_.get();
    }
    figures_.mode = state_.anyCull() ? "culled draw" : "all patches";
    if (state_.statusColors)
      figures_.notes.push_back("status colors need a cull stage (1, 2, 3 or c)");
    return &player_->target(0);
  }

  /// \brief Records the blit of the drawn view to swapchain image `image`, the HUD over
  /// it and, with `readback`, the copy of the result for a screenshot.
  void recordPresentation(const frame::RenderTarget& shown, uint32_t image, VkExtent2D extent,
                          vulkan::Buffer* readback) {
    const VkCommandBuffer cmd = sync_.cmd;
    OSD_CULL_VK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    OSD_CULL_VK(vkBeginCommandBuffer(cmd, &begin));
    const VkImage target = display_.swapchain.image(image);
    const VkImage source = shown.color().handle();
    // The view was drawn and waited for; make its writes visible to the blit.
    imageBarrier(cmd, source, frame::RenderTarget::kColorLayout, frame::RenderTarget::kColorLayout,
                 VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(shown.width()), int32_t(shown.height()), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
    vkCmdBlitImage(cmd, source, frame::RenderTarget::kColorLayout, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    display_.hud.record(cmd, image);
    if (readback)
      recordReadback(target, extent, *readback);
    else
      imageBarrier(cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
    OSD_CULL_VK(vkEndCommandBuffer(cmd));
  }

  /// \brief Records the copy of swapchain image `target` (HUD drawn) into `readback` for
  /// the host, leaving the image ready to present.
  void recordReadback(VkImage target, VkExtent2D extent, vulkan::Buffer& readback) {
    const VkCommandBuffer cmd = sync_.cmd;
    imageBarrier(
        cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1,
                           &copy);
    VkBufferMemoryBarrier host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    host.buffer = readback.handle();
    host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &host, 0, nullptr);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
  }

  /// \brief Submits the recorded frame, presents swapchain image `image` and waits for the
  /// frame; returns vkQueuePresentKHR's result.
  VkResult submitAndPresent(uint32_t image) {
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSemaphore waitSem = sync_.acquired.get(), signalSem = sync_.rendered.get();
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &waitSem;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &sync_.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &signalSem;
    VkFence rawF = sync_.fence.get();
    OSD_CULL_VK(vkQueueSubmit(context_.queue(), 1, &submit, rawF));
    VkSwapchainKHR chain = display_.swapchain.handle();
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &signalSem;
    present.swapchainCount = 1;
    present.pSwapchains = &chain;
    present.pImageIndices = &image;
    const VkResult r = vkQueuePresentKHR(context_.queue(), &present);
    OSD_CULL_VK(vkWaitForFences(context_.device(), 1, &rawF, VK_TRUE, UINT64_MAX));
    OSD_CULL_VK(vkResetFences(context_.device(), 1, &rawF));
    return r;
  }

  /// \brief The one line of figures for frame `f` on stdout (--print-frames).
  void printFrame(uint32_t f) const {
    const std::string timedAt =
        timing_.lastTimed() ? "from frame " + std::to_string(*timing_.lastTimed()) : "none";
    std::printf(
        "frame %u: cull %s, drawn %u of %u patches (pass 1 %u, pass 2 %u), culled frustum %u "
        "back-patch %u occlusion %u, TES invocations %llu, %.1f ms, scene frame %u of %u %s, "
        "ms per pass %.3f %.3f %.3f %.3f %s\n",
        f, figures_.cull.c_str(), figures_.drawnPass1 + figures_.drawnPass2, figures_.patches,
        figures_.drawnPass1, figures_.drawnPass2, figures_.culledFrustum, figures_.culledBackPatch,
        figures_.culledOcclusion, static_cast<unsigned long long>(figures_.tesInvocations),
        figures_.frameMs, state_.sceneFrame, frameCount_, state_.playing ? "playing" : "paused",
        figures_.pass1Ms, figures_.pyramidMs, figures_.cullMs, figures_.pass2Ms, timedAt.c_str());
    if (!figures_.plan.empty()) std::printf("  plan: %s\n", figures_.plan.c_str());  // as the HUD
  }

  /// \brief Writes the read-back window image as the script's shot of frame `f` and/or
  /// the last frame's screenshot.
  void writeScreenshots(const vulkan::Buffer& readback, VkExtent2D extent, uint32_t f, bool shot,
                        bool last) const {
    std::span<const uint8_t> bytes = readback.mappedAs<const uint8_t>();
    std::vector<uint8_t> rgba(bytes.begin(), bytes.end());
    if (display_.swapchain.bgr())
      for (size_t i = 0; i + 3 < rgba.size(); i += 4) std::swap(rgba[i], rgba[i + 2]);
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
    const adapters::PngImage png = adapters::colorImage(extent.width, extent.height, rgba);
    for (const std::string& path :
         {shot ? screenshotPath(*options_.screenshot, f) : "", last ? *options_.screenshot : ""}) {
      if (path.empty()) continue;
      adapters::writePng(path, png);
      std::cout << "wrote " << path << "\n";
    }
  }

  ViewerScene& scene_;
  scene::SceneDescription& description_;
  const ViewerOptions& options_;
  ScriptPlayer& script_;
  const uint32_t patchTotal_;
  Display display_;
  vulkan::Context& context_;
  ViewState state_;
  std::unique_ptr<plan::Planner> planner_;
  uint64_t planFrame_ = 0;  // the plan's frame numbers (the scene frame may stand still)
  const uint32_t frameCount_;
  // The player (its CullFrame and target) is made for one window size and one set of cull
  // stages; it is made again when either changes. The status view has its own target.
  std::unique_ptr<session::ScenePlayer> player_;
  std::unique_ptr<frame::RenderTarget> statusTarget_;
  std::string builtCull_;                 // the stages the player was made with
  std::optional<uint32_t> shownFrame_;    // the animation frame the player was moved to
  std::optional<frame::Bounds> framing_;  // the orbit camera's, from the first frame
  PassTiming timing_;
  FrameSync sync_;
  HudFigures figures_;
  const std::string keys_;
  const std::vector<std::string> backPatchNotes_;
};

}  // namespace

int runViewer(ViewerScene& scene, const ViewerOptions& options) {
  const std::vector<ScriptStep> steps = parseScript(options.script);
  ScriptPlayer script(steps);
  if (script.hasShots() && !options.screenshot)
    throw ScriptError(
        "--script: 'shot' needs --screenshot FILE.png (the shots are named after it)");
  ViewerLoop loop(scene, options, script);
  return loop.run();
}

}  // namespace osd_cull::viewer
