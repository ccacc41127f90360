// Drawing into the application's attachments: its color and depth formats (BGRA8, D16),
// its render passes or dynamic rendering, its depth as the source of the Hi-Z pyramid.
// Images equal those of osd_cull's own target; what is missing is named.
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/check.h"
#include "osd_cull/vk/context.h"
#include "support/app_device.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

// The application's side: images it created, and its render passes and framebuffer.
struct AppAttachments {
  vulkan::Image color, depth;
  vulkan::UniqueRenderPass clearPass, loadPass;
  vulkan::UniqueFramebuffer framebuffer;

  vulkan::UniqueRenderPass makePass(vulkan::Context& context, bool clear) {
    VkAttachmentDescription a[2]{};
    const VkFormat formats[2] = {color.format(), depth.format()};
    const VkImageLayout layouts[2] = {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                      VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    for (int i = 0; i < 2; ++i) {
      a[i].format = formats[i];
      a[i].samples = VK_SAMPLE_COUNT_1_BIT;
      a[i].loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
      a[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      a[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
      a[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
      a[i].initialLayout = clear ? VK_IMAGE_LAYOUT_UNDEFINED : layouts[i];
      a[i].finalLayout = layouts[i];
    }
    const VkAttachmentReference colorRef{0, layouts[0]}, depthRef{1, layouts[1]};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &colorRef;
    subpass.pDepthStencilAttachment = &depthRef;
    VkSubpassDependency deps[2]{};
    for (int i = 0; i < 2; ++i) {
      deps[i].srcSubpass = i == 0 ? VK_SUBPASS_EXTERNAL : 0;
      deps[i].dstSubpass = i == 0 ? 0 : VK_SUBPASS_EXTERNAL;
      deps[i].srcStageMask =
          i == 0 ? VK_PIPELINE_STAGE_ALL_COMMANDS_BIT : VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT;
      deps[i].dstStageMask =
          i == 0 ? VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT : VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
      deps[i].srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
      deps[i].dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    }
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 2;
    info.pAttachments = a;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = deps;
    VkRenderPass pass = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateRenderPass(context.device(), &info, nullptr, &pass));
    return vulkan::UniqueRenderPass(context.device(), pass);
  }

  AppAttachments(vulkan::Context& context, uint32_t w, uint32_t h, VkFormat colorFormat,
                 VkFormat depthFormat, bool renderPass)
      : color(context, {w, h, colorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT}),
        depth(context, {w, h, depthFormat,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT}) {
    if (!renderPass) return;
    clearPass = makePass(context, true);
    loadPass = makePass(context, false);
    const VkImageView views[2] = {color.view(), depth.view()};
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = clearPass.get();
    info.attachmentCount = 2;
    info.pAttachments = views;
    info.width = w;
    info.height = h;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    OSD_CULL_VK(vkCreateFramebuffer(context.device(), &info, nullptr, &fb));
    framebuffer = vulkan::UniqueFramebuffer(context.device(), fb);
  }

  // What the application hands osd_cull.
  frame::ExternalTarget lend() const {
    frame::ExternalTarget t;
    t.width = color.width();
    t.height = color.height();
    t.colorImage = color.handle();
    t.colorView = color.view();
    t.colorFormat = color.format();
    t.colorUsage = color.desc().usage;
    t.depthImage = depth.handle();
    t.depthView = depth.view();
    t.depthFormat = depth.format();
    t.depthUsage = depth.desc().usage;
    t.clearPass = clearPass.get();
    t.loadPass = loadPass.get();
    t.framebuffer = framebuffer.get();
    return t;
  }
};

// RGBA bytes of a BGRA image.
std::vector<uint8_t> bgraToRgba(std::vector<uint8_t> bytes) {
  for (size_t i = 0; i + 3 < bytes.size(); i += 4) std::swap(bytes[i], bytes[i + 2]);
  return bytes;
}

uint32_t differentPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  EXPECT_EQ(a.size(), b.size());
  uint32_t n = 0;
  for (size_t i = 0; i + 3 < std::min(a.size(), b.size()); i += 4)
    n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2] || a[i + 3] != b[i + 3];
  return n;
}

class ExternalTargetTest : public test::VkTest {
 protected:
  static constexpr uint32_t kW = 160, kH = 120;

  void SetUp() override {
    VkTest::SetUp();
    scene_ = scene::defaultScene();
    renderer_ = std::make_unique<frame::Renderer>(context());
    gpu_ = std::make_unique<frame::GpuPatchSet>(context(), scene_.patches);
    for (const auto& m : scene_.occluders) meshes_.emplace_back(context(), m);
    for (const auto& m : meshes_) occluders_.push_back(&m);
    options_.tessellation.uniformLevel = 3;
  }
  void TearDown() override {
    occluders_.clear();
    meshes_.clear();
    gpu_.reset();
    renderer_.reset();
    VkTest::TearDown();
  }

  frame::Camera camera(double degrees = 0.0) const {
    const frame::Bounds bounds = frame::boundsOf(scene_.patches.points);
    return frame::orbit(frame::frameBounds(bounds, scene_.viewDirection, scene_.up, 40.0, kW, kH),
                        bounds.center(), scene_.up, degrees);
  }

  std::vector<uint8_t> draw(frame::RenderTarget& target, double degrees = 0.0) {
    const frame::PatchDraw d{gpu_.get(), &scene_.patches, 0};
    renderer_->render(target, camera(degrees), {&d, 1}, occluders_, options_);
    return target.readColor(context());
  }

  // The image of osd_cull's own default target.
  std::vector<uint8_t> reference(double degrees = 0.0) {
    frame::RenderTarget own(context(), kW, kH);
    return draw(own, degrees);
  }

  scene::Scene scene_;
  std::unique_ptr<frame::Renderer> renderer_;
  std::unique_ptr<frame::GpuPatchSet> gpu_;
  std::vector<frame::GpuTriangleMesh> meshes_;
  std::vector<const frame::GpuTriangleMesh*> occluders_;
  frame::RenderOptions options_;
};

TEST_F(ExternalTargetTest, DynamicRenderingIntoTheApplicationsBgraImageDrawsLikeOurTarget) {
  ASSERT_TRUE(context().info().optional.dynamicRendering);
  AppAttachments app(context(), kW, kH, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D32_SFLOAT, false);
  frame::ExternalTarget lent = app.lend();
  lent.colorLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;  // any resting layout the app likes
  frame::RenderTarget target(context(), lent);
  EXPECT_TRUE(target.format().dynamicRendering);
  EXPECT_FALSE(target.hasItems());
  const std::vector<uint8_t> expected = reference();
  EXPECT_EQ(differentPixels(bgraToRgba(draw(target)), expected), 0u);
  EXPECT_THROW(target.items(), Error);
}

TEST_F(ExternalTargetTest, TheApplicationsRenderPassWithBgraAndD16DrawsLikeOurTarget) {
  AppAttachments app(context(), kW, kH, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D16_UNORM, true);
  frame::RenderTarget target(context(), app.lend());
  EXPECT_FALSE(target.format().dynamicRendering);
  EXPECT_EQ(target.format().renderPass, app.clearPass.get());
  const std::vector<uint8_t> expected = reference();
  const uint32_t differ = differentPixels(bgraToRgba(draw(target)), expected);
  // 16-bit depth resolves a few near-coincident surfaces (occluder contact lines) otherwise.
  EXPECT_LE(differ * 200u, kW * kH) << differ << " pixels differ";
}

TEST_F(ExternalTargetTest, OwnTargetWithDynamicRenderingEqualsOwnRenderPassTarget) {
  frame::OwnTargetOptions o;
  o.dynamicRendering = true;
  frame::RenderTarget dynamic(context(), kW, kH, o), passes(context(), kW, kH);
  EXPECT_EQ(differentPixels(draw(dynamic, 20.0), draw(passes, 20.0)), 0u);
  EXPECT_EQ(dynamic.readItems(context()), passes.readItems(context()));
}

// The two-pass frame drawn into the application's images: pass 1 through its clearing
// render pass, Hi-Z from its D16 depth, pass 2 through its loading pass.
TEST_F(ExternalTargetTest, CullFrameOnTheApplicationsTargetKeepsTheImageAndCullsByItsDepth) {
  AppAttachments app(context(), kW, kH, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D16_UNORM, true);
  AppAttachments unculled(context(), kW, kH, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D16_UNORM, true);
  frame::RenderTarget target(context(), app.lend()), reference(context(), unculled.lend());
  frame::CullFrameOptions o;
  o.render = options_;
  const frame::CullMesh meshes[] = {{gpu_.get(), &scene_.patches}};
  frame::CullFrame cull(context(), *renderer_, target, meshes, o);
  uint32_t occluded = 0;
  for (int f = 0; f < 3; ++f) {
    const frame::CullFrameStats s = cull.render(camera(5.0 * f), occluders_);
    occluded += s.culledOcclusion;
    const uint32_t differ = differentPixels(target.readColor(context()), draw(reference, 5.0 * f));
    EXPECT_LE(differ * 10000u, kW * kH) << differ << " pixels differ in frame " << f;
  }
  EXPECT_GT(occluded, 0u);
}

TEST_F(ExternalTargetTest, WhatIsMissingIsNamed) {
  try {
    frame::RenderTarget target(context(), frame::ExternalTarget{});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const char* name : {"colorImage", "colorView", "depthImage", "depthView", "colorFormat",
                             "depthFormat", "COLOR_ATTACHMENT usage"})
      EXPECT_NE(what.find(name), std::string::npos) << name << " in: " << what;
  }
  AppAttachments app(context(), kW, kH, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D16_UNORM, true);
  frame::ExternalTarget lent = app.lend();
  lent.loadPass = VK_NULL_HANDLE;
  EXPECT_THROW(frame::RenderTarget(context(), lent), Error);
}

TEST(ExternalTargetAdopted, DynamicRenderingTargetNeedsTheFeatureEnabled) {
  test::AppDeviceOptions options;
  options.dynamicRendering = false;
  test::AppDevice device(options);
  {
    vulkan::Context context(device.lend());
    AppAttachments app(context, 8, 8, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D32_SFLOAT, false);
    try {
      frame::RenderTarget target(context, app.lend());
      FAIL() << "expected an error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("dynamic rendering"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(device.log().count(), 0u) << device.log().summary();
}

}  // namespace
}  // namespace osd_cull
