#include "osd_cull/frame/verify/crack_count.h"

#include "osd_cull/frame/draw/render_target.h"
#include "osd_cull/vk/context.h"

#include <cmath>
#include <vector>

namespace osd_cull::frame {

uint32_t countCracks(std::span<const uint32_t> items, std::span<const float> depth,
                     std::span<const uint32_t> unculledItems, uint32_t width, uint32_t height,
                     float maxDepthSpread, uint32_t maxWidth) {
  uint32_t gaps = 0;
  auto covered = [&](int64_t x, int64_t y) {
    return x >= 0 && y >= 0 && x < int64_t{width} && y < int64_t{height} &&
           items[size_t(y) * width + size_t(x)] != 0;
  };
  auto d = [&](int64_t x, int64_t y) { return depth[size_t(y) * width + size_t(x)]; };
  // The nearest covered pixel from (x, y) in direction (dx, dy) within maxWidth steps.
  auto nearest = [&](int64_t x, int64_t y, int dx, int dy, int64_t& cx, int64_t& cy) {
    for (uint32_t k = 1; k <= maxWidth; ++k)
      if (covered(x + dx * int64_t{k}, y + dy * int64_t{k})) {
        cx = x + dx * int64_t{k};
        cy = y + dy * int64_t{k};
        return true;
      }
    return false;
  };
  auto across = [&](int64_t x, int64_t y, int dx, int dy) {
    int64_t ax = 0, ay = 0, bx = 0, by = 0;
    return nearest(x, y, -dx, -dy, ax, ay) && nearest(x, y, dx, dy, bx, by) &&
           std::abs(d(ax, ay) - d(bx, by)) < maxDepthSpread;
  };
  for (int64_t y = 0; y < int64_t{height}; ++y)
    for (int64_t x = 0; x < int64_t{width}; ++x) {
      if (covered(x, y) || unculledItems[size_t(y) * width + size_t(x)] == 0) continue;
      gaps += across(x, y, 1, 0) || across(x, y, 0, 1);
    }
  return gaps;
}

uint32_t countCracks(vulkan::Context& context, Renderer& renderer, RenderTarget& target,
                     const Camera& camera, const PatchDraw& draw, const RenderOptions& options,
                     uint32_t maxWidth) {
  RenderOptions culled = options;
  culled.cullBackFaces = true;
  renderer.render(target, camera, {&draw, 1}, {}, culled);
  const std::vector<uint32_t> items = target.readItems(context);
  const std::vector<float> depth = target.readDepth(context);
  RenderOptions unculled = options;
  unculled.cullBackFaces = false;
  renderer.render(target, camera, {&draw, 1}, {}, unculled);
  return countCracks(items, depth, target.readItems(context), target.width(), target.height(),
                     kCrackDepthSpread, maxWidth);
}

}  // namespace osd_cull::frame
