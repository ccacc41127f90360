// Drawing into the application's attachments: its color and depth formats (BGRA8, D16),
// its render passes or dynamic rendering, its depth as the source of the Hi-Z pyramid.
// Images equal those of osd_cull's own target; what is missing is named.
#include "app_vulkan.h"
#include "lend.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/context.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

// The application's side (the integration sample's): images with their own memory,
// render passes and framebuffer, or no passes for dynamic rendering.
struct AppAttachments : app::Target {
  AppAttachments(vulkan::Context& context, uint32_t w, uint32_t h, VkFormat colorFormat,
                 VkFormat depthFormat, bool renderPasses)
      : app::Target(context.physicalDevice(), context.device(), w, h, colorFormat, depthFormat,
                    renderPasses) {}
  frame::ExternalTarget lend() const { return app::lendTarget(*this); }
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
  EXPECT_EQ(target.format().renderPass, app.clearPass);
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
    EXPECT_EQ(differ, 0u) << differ << " pixels differ in frame " << f;
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
  app::Device device({.validation = true, .dynamicRendering = false});
  {
    vulkan::Context context(app::lendDevice(device));
    AppAttachments app(context, 8, 8, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D32_SFLOAT, false);
    try {
      frame::RenderTarget target(context, app.lend());
      FAIL() << "expected an error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("dynamic rendering"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(device.validationMessages.empty());
}

// A Vulkan 1.3 application without VK_KHR_dynamic_rendering: the core entry points are used.
TEST(ExternalTargetAdopted, DynamicRenderingOnACore13DeviceClearsTheApplicationsImage) {
  app::Device device({.validation = true});
  {
    vulkan::Context context(app::lendDevice(device));
    AppAttachments app(context, 8, 6, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D32_SFLOAT, false);
    frame::RenderTarget target(context, app.lend());
    frame::Renderer renderer(context);
    frame::RenderOptions options;
    options.background = {1.0f, 0.5f, 0.0f};
    const frame::Camera camera =
        frame::Camera::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 6, 0.1, 10.0);
    renderer.renderWith(
        target, camera, {}, options, [](VkCommandBuffer) {}, [](VkCommandBuffer) { return 0u; });
    const std::vector<uint8_t> bgra = target.readColor(context);
    ASSERT_EQ(bgra.size(), 8u * 6u * 4u);
    for (size_t p = 0; p < bgra.size(); p += 4) {
      EXPECT_EQ(bgra[p + 2], 255) << p;  // red
      EXPECT_NEAR(bgra[p + 1], 128, 1) << p;
      EXPECT_EQ(bgra[p], 0) << p;
    }
  }
  EXPECT_TRUE(device.validationMessages.empty());
}

}  // namespace
}  // namespace osd_cull
