#include "support/vk_test_images.h"

#include <algorithm>
#include <cmath>

namespace osd_cull::test {

std::map<uint32_t, uint32_t> itemHistogram(std::span<const uint32_t> items) {
  std::map<uint32_t, uint32_t> h;
  for (uint32_t v : items) ++h[v];
  return h;
}

uint32_t countEnclosedBackground(std::span<const uint32_t> items, uint32_t width, uint32_t height) {
  std::vector<uint32_t> left(height, width), right(height, 0), top(width, height), bottom(width, 0);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      if (items[y * width + x] != 0) {
        left[y] = std::min(left[y], x);
        right[y] = std::max(right[y], x);
        top[x] = std::min(top[x], y);
        bottom[x] = std::max(bottom[x], y);
      }
  uint32_t enclosed = 0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      if (items[y * width + x] == 0 && left[y] < x && x < right[y] && top[x] < y && y < bottom[x])
        ++enclosed;
  return enclosed;
}

frame::Camera pixelCamera(uint32_t width, uint32_t height, double zNear, double zFar) {
  // Identity view (eye at the origin looking down -z, y up); the projection's top edge is
  // y = 0 and its bottom y = -height, so world (x, -y) is pixel position (x, y).
  return frame::Camera::orthographic(glm::dmat4(1.0), 0.0, double(width), -double(height), 0.0,
                                     zNear, zFar, width, height);
}

}  // namespace osd_cull::test
