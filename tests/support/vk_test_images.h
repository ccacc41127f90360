#pragma once
/// \file vk_test_images.h
/// \brief Image checks for draw tests: item histograms, holes, cracks, pixel cameras.

#include "osd_cull/frame/camera.h"

#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace osd_cull::test {

/// \brief Pixels per item value (0 background, patch p -> p + 1, occluders 0xFFFFFFFF).
std::map<uint32_t, uint32_t> itemHistogram(std::span<const uint32_t> items);

/// \brief Background pixels with covered pixels somewhere to the left, right, above and
/// below: holes and cracks inside the silhouette of a convex object.
uint32_t countEnclosedBackground(std::span<const uint32_t> items, uint32_t width, uint32_t height);

/// \brief An orthographic camera at the origin looking down -z where world (x, -y) is
/// pixel position (x, y): the square [i, i+1] x [-(j+1), -j] covers exactly pixel (i, j)
/// (column i, row j from the top). Visible depths: z in [-zFar, -zNear].
frame::Camera pixelCamera(uint32_t width, uint32_t height, double zNear = 0.5, double zFar = 10.5);

}  // namespace osd_cull::test
