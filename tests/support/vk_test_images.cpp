#include "support/vk_test_images.h"

#include <algorithm>
#include <cmath>

namespace osd_cull::test {

std::map<uint32_t, uint32_t> itemHistogram(std::span<const uint32_t> items) {
  std::map<uint32_t, uint32_t> h;
  for (uint32_t v : items) ++h[v];
  return h;
}

uint32_t countCracks(std::span<const uint32_t> items, std::span<const float> depth,
                     std::span<const uint32_t> unculledItems, uint32_t width, uint32_t height,
                     float maxDepthSpread) {
  uint32_t gaps = 0;
  auto covered = [&](uint32_t x, uint32_t y) { return items[y * width + x] != 0; };
  auto d = [&](uint32_t x, uint32_t y) { return depth[y * width + x]; };
  for (uint32_t y = 1; y + 1 < height; ++y)
    for (uint32_t x = 1; x + 1 < width; ++x) {
      if (covered(x, y) || unculledItems[y * width + x] == 0) continue;
      const bool horizontal = covered(x - 1, y) && covered(x + 1, y) &&
                              std::abs(d(x - 1, y) - d(x + 1, y)) < maxDepthSpread;
      const bool vertical = covered(x, y - 1) && covered(x, y + 1) &&
                            std::abs(d(x, y - 1) - d(x, y + 1)) < maxDepthSpread;
      gaps += horizontal || vertical;
    }
  return gaps;
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
