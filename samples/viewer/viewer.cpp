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
  return frame::Camera::lookAt(pivot + offset, pivot, up, 40.0, width, height,
                               std::max(d - r, (d + r) * 1e-4), d + r);
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

int runViewer(ViewerScene& scene, const ViewerOptions& options) {
  const std::vector<ScriptStep> steps = parseScript(options.script);
  ScriptPlayer script(steps);
  if (script.hasShots() && !options.screenshot)
    throw ScriptError(
        "--script: 'shot' needs --screenshot FILE.png (the shots are named after it)");
  scene::SceneDescription& description = scene.scene.description;
  uint32_t patchTotal = 0;
  for (const scene::InstanceDescription& i : description.instances)
    patchTotal += scene.scene.meshes.at(i.mesh).extraction.patches.patchCount();
  if (patchTotal == 0) throw Error(description.source + ": no patches to view");

  Window window(options.width, options.height, "osd-cull view: " + description.source);
  vulkan::ContextOptions contextOptions;
  contextOptions.device = options.device;
  contextOptions.validation = options.validate;
  contextOptions.instanceExtensions = Window::requiredInstanceExtensions();
  contextOptions.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  vulkan::Context context(contextOptions);
  std::cout << "device: " << context.info().name << " (" << context.info().driver << ")\n";
  Surface surface{context.instance(), window.createSurface(context.instance())};
  uint32_t fbWidth = 0, fbHeight = 0;
  window.framebufferSize(fbWidth, fbHeight);
  Swapchain swapchain(context, surface.handle, fbWidth, fbHeight);
  Hud hud(context, window, swapchain);

  ViewState state = options.initial;
  state.maxTessLevel = context.info().limits.maxTessellationGenerationLevel;
  // The effect plan, as in `osd-cull render`: on by default where the device is calibrated.
  const std::unique_ptr<plan::Planner> planner =
      options.makePlanner ? options.makePlanner(context) : nullptr;
  uint64_t planFrame = 0;  // the plan's frame numbers (the scene frame may stand still)
  const uint32_t frameCount = std::max(1u, description.settings.frameCount);
  // The player (its CullFrame and target) is made for one window size and one set of cull
  // stages; it is made again when either changes. The status view has its own target.
  std::unique_ptr<session::ScenePlayer> player;
  std::unique_ptr<frame::RenderTarget> statusTarget;
  std::string builtCull;                 // the stages the player was made with
  std::optional<uint32_t> shownFrame;    // the animation frame the player was moved to
  std::optional<frame::Bounds> framing;  // the orbit camera's, from the first frame
  PassTiming timing(options.timePassesEvery);
  auto dropPlayer = [&] {
    player.reset();
    statusTarget.reset();
    builtCull.clear();
  };

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context.queueFamily();
  VkCommandPool rawPool = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateCommandPool(context.device(), &poolInfo, nullptr, &rawPool));
  vulkan::UniqueCommandPool pool(context.device(), rawPool);
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool.get();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  OSD_CULL_VK(vkAllocateCommandBuffers(context.device(), &alloc, &cmd));
  VkSemaphoreCreateInfo semInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore rawAcquired = VK_NULL_HANDLE, rawRendered = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateSemaphore(context.device(), &semInfo, nullptr, &rawAcquired));
  vulkan::UniqueSemaphore acquired(context.device(), rawAcquired);
  OSD_CULL_VK(vkCreateSemaphore(context.device(), &semInfo, nullptr, &rawRendered));
  vulkan::UniqueSemaphore rendered(context.device(), rawRendered);
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence rawFence = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateFence(context.device(), &fenceInfo, nullptr, &rawFence));
  vulkan::UniqueFence fence(context.device(), rawFence);

  HudFigures figures;
  figures.device = context.info().name;
  figures.scene = description.source + ": " + std::to_string(description.instances.size()) +
                  " instance(s), " + std::to_string(patchTotal) + " patches";
  figures.patches = patchTotal;
  const std::string keys = keyHelp();
  std::cout << "keys:\n" << keys;
  std::vector<std::string> backPatchNotes;
  for (const scene::SceneMesh& m : scene.scene.meshes)
    if (!m.validity.enabled)
      backPatchNotes.push_back("back-patch culling off for '" + m.name + "': " + m.validity.reason);
  for (const std::string& note : backPatchNotes) std::cout << "note: " << note << "\n";

  for (uint32_t f = 0; options.frames == 0 || f < options.frames; ++f) {
    if (!window.poll()) break;
    const auto start = Clock::now();
    for (const std::string& line : script.beforeFrame(f, state))
      std::cout << "key: " << line << "\n";
    const bool shot = script.takeShot();
    const WindowInput input = window.takeInput();
    for (const std::string& k : input.keys)
      if (auto line = pressKey(state, k)) std::cout << "key: " << *line << "\n";
    orbitCamera(state, -0.3 * input.orbitX, -0.3 * input.orbitY);
    zoomCamera(state, std::pow(1.01, input.zoomY) * std::pow(0.9, input.wheel));
    if (state.quit) break;
    if (state.turntable) orbitCamera(state, 1.0, 0.0);
    advanceAnimation(state, frameCount);

    uint32_t w = 0, h = 0;
    window.framebufferSize(w, h);
    if (w == 0 || h == 0) continue;  // minimised
    if (w != swapchain.extent().width || h != swapchain.extent().height) {
      swapchain.recreate(w, h);
      hud.attach(swapchain);
      dropPlayer();
    }
    const VkExtent2D extent = swapchain.extent();
    const bool backPatchAllowed = std::any_of(scene.scene.meshes.begin(), scene.scene.meshes.end(),
                                              [](const auto& m) { return m.validity.enabled; });
    const frame::RenderOptions render =
        renderOptions(state, context, state.backPatch && backPatchAllowed);

    // The cull stages are fixed when a CullFrame is made: make the player again when they
    // change (with none, its CullFrame culls nothing and draws every patch).
    if (state.plan && !planner) {
      state.plan = false;
      std::cout << "note: no effect plan in this viewer (no calibration of this device, or "
                   "--cull given): the stages are chosen by hand\n";
    }
    if (!player || state.cullLabel() != builtCull) {
      dropPlayer();
      scene::ViewDescription& view = description.views.front();
      view.width = extent.width;
      view.height = extent.height;
      frame::CullFrameOptions fo;
      fo.render = render;
      fo.cull.frustum = state.frustum;
      fo.cull.backPatch = state.backPatch ? state.backPatchMethod : "";
      fo.cull.occlusion = state.occlusion ? "hiz" : "";
      player = std::make_unique<session::ScenePlayer>(context, scene.scene, fo,
                                                      frame::PointUpdatePath::Cpu,
                                                      state.plan ? planner.get() : nullptr);
      statusTarget = std::make_unique<frame::RenderTarget>(context, extent.width, extent.height);
      builtCull = state.cullLabel();
      shownFrame.reset();
      timing.forget();
    }
    const uint32_t sceneFrame = description.settings.frameStart + state.sceneFrame;
    if (shownFrame != sceneFrame) {
      player->seek(sceneFrame);
      shownFrame = sceneFrame;
    }
    if (!framing) framing = player->bounds();
    const frame::Camera camera =
        state.sceneCamera ? player->camera(0)
                          : viewCamera(state, *framing, scene, extent.width, extent.height);

    figures.cull = state.cullLabel() + (state.freezeCull ? " (cull camera frozen)" : "");
    figures.tessellation =
        state.adaptive ? "adaptive, " + std::to_string(state.pixelsPerSegment) + " px/segment"
                       : "uniform " + std::to_string(render.tessellation.uniformLevel);
    figures.animation = frameCount < 2
                            ? "no animation (one frame)"
                            : "frame " + std::to_string(sceneFrame) + " (frames " +
                                  std::to_string(description.settings.frameStart) + "-" +
                                  std::to_string(description.settings.frameStart + frameCount - 1) +
                                  "), " + (state.playing ? "playing" : "paused");
    figures.camera = state.sceneCamera
                         ? "scene camera '" + description.views.front().name + "'"
                         : std::string("orbit") + (state.turntable ? " (turntable)" : "");
    figures.notes.clear();
    frame::RenderTarget* shown = &player->target(0);
    if (state.plan) {
      // The plan draws the frame (session::ScenePlayer with a planner): the stages it chose
      // for each instance and why, per-stage GPU times from the frame's own timestamps.
      player->setCamera(0, camera);
      const session::ViewFrame view = player->renderCurrent(planFrame++).front();
      const frame::CullFrameStats& s = view.stats;
      figures.counts(s);
      const bool timed = s.gpu.measured();
      figures.pass1Ms = timed ? s.gpu.pass1 : s.frameMs;
      figures.pyramidMs = timed ? s.gpu.pyramid : 0.0;
      figures.cullMs = timed ? s.gpu.cull : 0.0;
      figures.pass2Ms = timed ? s.gpu.pass2 : 0.0;
      figures.timing =
          timed ? "GPU timestamps of this frame" : "wall clock (drawn without culling)";
      figures.cull = "plan";
      for (const plan::Plan& p : view.plans) {
        char line[160];
        std::snprintf(line, sizeof line, "%s: %s%s, predicted %.1f ms (%.1f without culling)",
                      p.mesh.c_str(), p.stages.describe().c_str(), p.probe ? " [re-probe]" : "",
                      p.predicted.totalMs(), p.predictedUnculled.totalMs());
        figures.notes.push_back(line);
        for (const auto& [kind, e] : p.effects())
          if (kind == plan::EffectKind::Frustum || kind == plan::EffectKind::BackPatch ||
              kind == plan::EffectKind::Occlusion)
            figures.notes.push_back(std::string("  ") + plan::toString(kind) +
                                    (e->on ? " on: " : " off: ") +
                                    e->reason.substr(0, e->reason.find(';')));
      }
      figures.mode = view.culled ? "culled draw (plan)" : "all patches (the plan culls nothing)";
      if (state.statusColors || state.freezeCull)
        figures.notes.push_back(
            "status colors and the frozen cull camera need the stages by "
            "hand (1, 2, 3 or c)");
    } else {
      frame::CullFrame& cullFrame = player->cullFrame(0);
      frame::CullFrameOptions fo = cullFrame.options();
      fo.render = render;
      if (!state.freezeCull || !state.anyCull()) {
        // Most frames are one submission; a timed one splits the passes (PassTiming).
        const bool timed = timing.due(f);
        fo.timePasses = timed;
        cullFrame.setOptions(fo);
        const frame::CullFrameStats s = cullFrame.render(camera, player->occluders());
        if (timed) timing.record(f, s.pass1Ms, s.pyramidMs, s.cullMs, s.pass2Ms);
        figures.counts(s);
      } else {
        fo.timePasses = false;
        cullFrame.setOptions(fo);
      }
      figures.pass1Ms = timing.pass1Ms();
      figures.pyramidMs = timing.pyramidMs();
      figures.cullMs = timing.cullMs();
      figures.pass2Ms = timing.pass2Ms();
      figures.timing = timing.describe(f);
      if (state.anyCull() && (state.statusColors || state.freezeCull)) {
        // Every patch from the current camera, colored by what the (frozen) cull camera did.
        cullFrame.renderStatusView(*statusTarget, camera, player->occluders());
        shown = statusTarget.get();
        figures.mode = "status colors";
      } else {
        figures.mode = state.anyCull() ? "culled draw" : "all patches";
        if (state.statusColors)
          figures.notes.push_back("status colors need a cull stage (1, 2, 3 or c)");
      }
    }
    if (state.backPatch || state.plan)
      for (const std::string& note : backPatchNotes) figures.notes.push_back(note);

    uint32_t image = 0;
    VkResult r = vkAcquireNextImageKHR(context.device(), swapchain.handle(), UINT64_MAX,
                                       acquired.get(), VK_NULL_HANDLE, &image);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
      swapchain.recreate(w, h);
      hud.attach(swapchain);
      dropPlayer();
      continue;
    }
    if (r != VK_SUBOPTIMAL_KHR) OSD_CULL_VK(r);
    hud.build(figures, keys, state.showHud);
    window.setUiCapture(hud.wantsMouse(), hud.wantsKeyboard());

    const bool last = options.frames != 0 && f + 1 == options.frames;
    const bool capture = (last || shot) && options.screenshot.has_value();
    vulkan::Buffer readback;
    if (capture)
      readback = vulkan::Buffer(context, VkDeviceSize{extent.width} * extent.height * 4,
                                VK_BUFFER_USAGE_TRANSFER_DST_BIT, vulkan::MemoryUse::Readback);
    OSD_CULL_VK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    OSD_CULL_VK(vkBeginCommandBuffer(cmd, &begin));
    const VkImage target = swapchain.image(image);
    const VkImage source = shown->color().handle();
    // The view was drawn and waited for; make its writes visible to the blit.
    imageBarrier(cmd, source, frame::RenderTarget::kColorLayout, frame::RenderTarget::kColorLayout,
                 VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(shown->width()), int32_t(shown->height()), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
    vkCmdBlitImage(cmd, source, frame::RenderTarget::kColorLayout, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    hud.record(cmd, image);
    if (capture) {
      imageBarrier(cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_TRANSFER_READ_BIT);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {extent.width, extent.height, 1};
      vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(),
                             1, &copy);
      VkBufferMemoryBarrier host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
      host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      host.buffer = readback.handle();
      host.size = VK_WHOLE_SIZE;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                           nullptr, 1, &host, 0, nullptr);
      imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                   VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
    } else {
      imageBarrier(cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
    }
    OSD_CULL_VK(vkEndCommandBuffer(cmd));
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSemaphore waitSem = acquired.get(), signalSem = rendered.get();
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &waitSem;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &signalSem;
    VkFence rawF = fence.get();
    OSD_CULL_VK(vkQueueSubmit(context.queue(), 1, &submit, rawF));
    VkSwapchainKHR chain = swapchain.handle();
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &signalSem;
    present.swapchainCount = 1;
    present.pSwapchains = &chain;
    present.pImageIndices = &image;
    r = vkQueuePresentKHR(context.queue(), &present);
    OSD_CULL_VK(vkWaitForFences(context.device(), 1, &rawF, VK_TRUE, UINT64_MAX));
    OSD_CULL_VK(vkResetFences(context.device(), 1, &rawF));
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
      swapchain.recreate(w, h);
      hud.attach(swapchain);
      dropPlayer();
    } else {
      OSD_CULL_VK(r);
    }
    figures.frameMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    if (options.printFrames) {
      const std::string timedAt =
          timing.lastTimed() ? "from frame " + std::to_string(*timing.lastTimed()) : "none";
      std::printf(
          "frame %u: cull %s, drawn %u of %u patches (pass 1 %u, pass 2 %u), culled frustum %u "
          "back-patch %u occlusion %u, TES invocations %llu, %.1f ms, scene frame %u of %u %s, "
          "ms per pass %.3f %.3f %.3f %.3f %s\n",
          f, figures.cull.c_str(), figures.drawnPass1 + figures.drawnPass2, figures.patches,
          figures.drawnPass1, figures.drawnPass2, figures.culledFrustum, figures.culledBackPatch,
          figures.culledOcclusion, static_cast<unsigned long long>(figures.tesInvocations),
          figures.frameMs, state.sceneFrame, frameCount, state.playing ? "playing" : "paused",
          figures.pass1Ms, figures.pyramidMs, figures.cullMs, figures.pass2Ms, timedAt.c_str());
    }
    std::fflush(stdout);
    if (capture) {
      std::span<const uint8_t> bytes = readback.mappedAs<const uint8_t>();
      std::vector<uint8_t> rgba(bytes.begin(), bytes.end());
      if (swapchain.bgr())
        for (size_t i = 0; i + 3 < rgba.size(); i += 4) std::swap(rgba[i], rgba[i + 2]);
      for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
      const adapters::PngImage png = adapters::colorImage(extent.width, extent.height, rgba);
      for (const std::string& path :
           {shot ? screenshotPath(*options.screenshot, f) : "", last ? *options.screenshot : ""}) {
        if (path.empty()) continue;
        adapters::writePng(path, png);
        std::cout << "wrote " << path << "\n";
      }
    }
  }
  context.waitIdle();
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  return 0;
}

}  // namespace osd_cull::viewer
