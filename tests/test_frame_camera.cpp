// frame::frameTightly: a camera that fits an object's box, not its bounding sphere.
#include "osd_cull/frame/camera.h"

#include <gtest/gtest.h>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace osd_cull {
namespace {

// The largest |x| and |y| in normalized device coordinates of the box's 8 corners.
glm::dvec2 projectedExtent(const frame::Camera& c, const frame::Bounds& b) {
  glm::dvec2 extent(0.0);
  for (const glm::dvec3& corner : b.corners()) {
    const glm::dvec4 p = c.viewProjection() * glm::dvec4(corner, 1.0);
    EXPECT_GT(p.w, 0.0);
    EXPECT_GE(p.z / p.w, 0.0);
    EXPECT_LE(p.z / p.w, 1.0);
    extent = glm::max(extent, glm::abs(glm::dvec2(p.x, p.y) / p.w));
  }
  return extent;
}

TEST(FrameTightly, NoPointsOrAnOrthographicCameraLeaveTheCameraAsItIs) {
  const frame::Camera c =
      frame::frameBounds({{-1, -1, -1}, {1, 1, 1}}, {0, 0, 1}, {0, 1, 0}, 40.0, 64, 64);
  EXPECT_EQ(frame::frameTightly(c, {}).view, c.view);
}

TEST(FrameTightly, AFlatSlabFillsTheImageWhereTheBoundingSphereLeavesAThird) {
  const frame::Bounds slab{{-10.0, -0.5, -6.0}, {10.0, 0.5, 6.0}};
  const glm::dvec3 from(0.3, 0.6, 1.0), up(0.0, 1.0, 0.0);
  const frame::Camera sphere = frame::frameBounds(slab, from, up, 40.0, 640, 360);
  const glm::dvec2 before = projectedExtent(sphere, slab);
  EXPECT_LT(std::max(before.x, before.y), 0.7);
  const frame::Camera tight = frame::frameTightly(sphere, slab.corners());
  const glm::dvec2 after = projectedExtent(tight, slab);
  EXPECT_NEAR(std::max(after.x, after.y), 0.92, 0.005);  // one side just fits
  EXPECT_LE(after.x, 0.9201);
  EXPECT_LE(after.y, 0.9201);
  // Same direction and image size.
  const glm::dvec3 dirBefore = glm::normalize(sphere.eye() - slab.center());
  const glm::dvec3 dirAfter = glm::normalize(tight.eye() - slab.center());
  EXPECT_NEAR(glm::dot(dirBefore, dirAfter), 1.0, 1e-9);
  EXPECT_EQ(tight.width, 640u);
  EXPECT_EQ(tight.height, 360u);
}

}  // namespace
}  // namespace osd_cull
