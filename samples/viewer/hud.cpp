#include "hud.h"

#include "swapchain.h"
#include "window.h"

#include "adapters/image_legend.h"
#include "osd_cull/error.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <span>

namespace osd_cull::viewer {
namespace {

constexpr size_t kHistory = 240;

void checkImGuiVk(VkResult r) {
  if (r != VK_SUCCESS) throw Error("Dear ImGui's Vulkan backend: VkResult " + std::to_string(r));
}

vulkan::UniqueRenderPass createHudPass(VkDevice device, VkFormat format) {
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // draws over the blitted view
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  VkRenderPass pass = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateRenderPass(device, &info, nullptr, &pass));
  return vulkan::UniqueRenderPass(device, pass);
}

void push(std::deque<float>& history, float value) {
  history.push_back(value);
  while (history.size() > kHistory) history.pop_front();
}

void plot(const char* label, const std::deque<float>& history, float lo, float hi) {
  std::vector<float> values(history.begin(), history.end());
  char overlay[64];
  std::snprintf(overlay, sizeof(overlay), "%.1f", values.empty() ? 0.0f : values.back());
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay, lo, hi,
                   ImVec2(150, 28));
}

}  // namespace

Hud::Hud(vulkan::Context& context, Window& window, const Swapchain& swapchain) : context_(context) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window.handle(), true);

  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 4;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  OSD_CULL_VK(vkCreateDescriptorPool(context.device(), &poolInfo, nullptr, &pool));
  pool_ = vulkan::UniqueDescriptorPool(context.device(), pool);
  renderPass_ = createHudPass(context.device(), swapchain.format());

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context.instance();
  info.PhysicalDevice = context.physicalDevice();
  info.Device = context.device();
  info.QueueFamily = context.queueFamily();
  info.Queue = context.queue();
  info.DescriptorPool = pool_.get();
  info.MinImageCount = std::max(2u, swapchain.imageCount());
  info.ImageCount = std::max(2u, swapchain.imageCount());
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImGuiVk;
  if (!ImGui_ImplVulkan_Init(&info, renderPass_.get()))
    throw Error("Dear ImGui's Vulkan backend did not start");
  context.submit([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  attach(swapchain);
}

Hud::~Hud() {
  context_.waitIdle();
  framebuffers_.clear();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Hud::attach(const Swapchain& swapchain) {
  framebuffers_.clear();
  extent_ = swapchain.extent();
  for (uint32_t i = 0; i < swapchain.imageCount(); ++i) {
    VkImageView view = swapchain.view(i);
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = renderPass_.get();
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = extent_.width;
    info.height = extent_.height;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateFramebuffer(context_.device(), &info, nullptr, &fb));
    framebuffers_.emplace_back(context_.device(), fb);
  }
}

namespace {

// One swatch and label per colour of `entries` (the written images' legend strip), on a line.
void legendLine(std::span<const adapters::LegendEntry> entries) {
  for (size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i];
    const ImVec4 c(e.rgb[0] / 255.0f, e.rgb[1] / 255.0f, e.rgb[2] / 255.0f, 1.0f);
    if (i > 0) ImGui::SameLine();
    ImGui::ColorButton(e.label.c_str(), c,
                       ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoBorder,
                       ImVec2(10, 10));
    ImGui::SameLine(0, 3);
    ImGui::TextUnformatted(e.label.c_str());
  }
}

// Folded: where the figures come from and every note.
void details(const HudFigures& f) {
  if (!ImGui::CollapsingHeader("details")) return;
  ImGui::Text("%s", f.device.c_str());
  ImGui::Text("%s", f.scene.c_str());
  ImGui::Text("animation: %s   camera: %s", f.animation.c_str(), f.camera.c_str());
  ImGui::TextWrapped("per pass: %s", f.timing.c_str());
  for (const auto& note : f.notes) ImGui::TextWrapped("%s", note.c_str());
}

}  // namespace

void Hud::build(const HudFigures& f, const std::string& keys, bool show) {
  const uint32_t drawn = f.drawnPass1 + f.drawnPass2;
  push(cullRate_, f.patches
                      ? 100.0f * float(f.patches - std::min(drawn, f.patches)) / float(f.patches)
                      : 0.0f);
  push(frameMs_, float(f.frameMs));
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (show) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.6f);
    ImGui::Begin("osd_cull", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 420.0f);  // a compact window
    ImGui::Text("cull: %s   tess: %s   %s", f.cull.c_str(), f.tessellation.c_str(), f.mode.c_str());
    if (!f.plan.empty()) ImGui::TextWrapped("plan: %s", f.plan.c_str());
    ImGui::Text("drawn %u of %u (%u + %u); culled F %u B %u O %u; TES %llu", drawn, f.patches,
                f.drawnPass1, f.drawnPass2, f.culledFrustum, f.culledBackPatch, f.culledOcclusion,
                static_cast<unsigned long long>(f.tesInvocations));
    ImGui::Text("ms: frame %.1f; pass 1 %.2f, pyramid %.2f, cull %.2f, pass 2 %.2f", f.frameMs,
                f.pass1Ms, f.pyramidMs, f.cullMs, f.pass2Ms);
    plot("cull %", cullRate_, 0.0f, 100.0f);
    ImGui::SameLine();
    plot("ms", frameMs_, 0.0f,
         std::max(1.0f, *std::max_element(frameMs_.begin(), frameMs_.end()) * 1.1f));
    if (f.legend == HudFigures::Legend::Status) legendLine(adapters::statusLegend());
    if (f.legend == HudFigures::Legend::PatchType) legendLine(adapters::patchTypeLegend());
    details(f);
    if (ImGui::CollapsingHeader("keys", ImGuiTreeNodeFlags_DefaultOpen))
      ImGui::TextUnformatted(keys.c_str());
    ImGui::PopTextWrapPos();
    ImGui::End();
  }
  ImGui::Render();
}

void Hud::record(VkCommandBuffer cmd, uint32_t image) {
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = renderPass_.get();
  begin.framebuffer = framebuffers_.at(image).get();
  begin.renderArea = {{0, 0}, extent_};
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
}

bool Hud::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Hud::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace osd_cull::viewer
