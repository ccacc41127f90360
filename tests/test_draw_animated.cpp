// Animated meshes: control points updated on the GPU (osd::GpuPointUpdate) are drawn
// straight from its buffer, and the image matches the one drawn from CPU-updated points.
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/osd/device_context.h"
#include "osd_cull/osd/gpu_point_update.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural.h"
#include "support/vk_test_context.h"
#include "support/vk_test_images.h"

#include <gtest/gtest.h>

#include <cmath>

namespace osd_cull {
namespace {

class AnimatedDrawTest : public test::VkTest {};

TEST_F(AnimatedDrawTest, GpuUpdatedPointsDrawLikeCpuUpdatedPoints) {
  const CageMesh cage = scene::defaultMesh();
  const PatchExtraction ex = extractPatches(cage);
  osd::DeviceContext device(context());
  osd::GpuPointUpdate update(device, ex.matrix, {4});
  frame::GpuPatchSet gpuDriven(context(), ex.patches);  // reads the update's buffer
  gpuDriven.readPointsFrom(context(), update.points(), 4);
  frame::GpuPatchSet cpuDriven(context(), ex.patches);  // uploaded from the CPU product
  frame::RenderTarget target(context(), 96, 96);
  frame::Renderer renderer(context());
  const auto camera =
      frame::Camera::lookAt({2.5, 2.0, 4.0}, {0, 0, 0}, {0, 1, 0}, 45.0, 96, 96, 0.5, 20);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 3;

  std::vector<glm::dvec3> moved(cage.positions.size()), points(ex.patches.points.size());
  for (int frame = 0; frame < 3; ++frame) {
    // Twist about y and stretch, more each frame.
    for (size_t i = 0; i < moved.size(); ++i) {
      const glm::dvec3 p = cage.positions[i];
      const double a = 0.3 * frame * p.y;
      moved[i] = {p.x * std::cos(a) - p.z * std::sin(a), p.y * (1.0 + 0.2 * frame),
                  p.x * std::sin(a) + p.z * std::cos(a)};
    }
    update.update(moved);
    renderer.render(target, camera, gpuDriven, nullptr, options);
    const auto fromGpu = target.readItems(context());
    ex.matrix.update(moved, points);
    cpuDriven.updatePoints(context(), points);
    renderer.render(target, camera, cpuDriven, nullptr, options);
    const auto fromCpu = target.readItems(context());
    size_t differ = 0, covered = 0;
    for (size_t i = 0; i < fromGpu.size(); ++i) {
      differ += fromGpu[i] != fromCpu[i];
      covered += fromCpu[i] != 0;
    }
    EXPECT_GT(covered, 1500u) << "frame " << frame;
    // Float sums in a different order: at most a few pixels on patch borders differ.
    EXPECT_LE(differ, covered / 200) << "frame " << frame;
  }
}

}  // namespace
}  // namespace osd_cull
