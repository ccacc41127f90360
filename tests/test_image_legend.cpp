// Legend strips under written images: each swatch has its documented colour and each
// label is drawn beside it.
#include "adapters/image_legend.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace osd_cull {
namespace {

using Rgb = std::array<uint8_t, 3>;

Rgb pixel(const adapters::PngImage& image, uint32_t x, uint32_t y) {
  const uint8_t* p = &image.samples8[4 * (size_t(y) * image.width + x)];
  return {p[0], p[1], p[2]};
}

adapters::PngImage blackImage(uint32_t w, uint32_t h) {
  return adapters::colorImage(w, h, std::vector<uint8_t>(size_t(4) * w * h, 0));
}

// Every pixel of every swatch has its entry's colour; the image above is untouched; the
// label beside each swatch has white pixels.
void expectSwatches(const adapters::PngImage& out, uint32_t imageHeight,
                    std::span<const adapters::LegendEntry> entries, const std::vector<Rgb>& rgb) {
  const auto swatches = adapters::legendLayout(out.width, entries);
  ASSERT_EQ(swatches.size(), rgb.size());
  for (size_t i = 0; i < swatches.size(); ++i) {
    const auto& s = swatches[i];
    for (uint32_t y = 0; y < s.size; ++y)
      for (uint32_t x = 0; x < s.size; ++x)
        ASSERT_EQ(pixel(out, s.x + x, imageHeight + s.y + y), rgb[i]) << entries[i].label;
    uint32_t white = 0;
    for (uint32_t y = 0; y < 7; ++y)
      for (uint32_t x = 0; x < 30; ++x)
        white += pixel(out, s.x + s.size + 4 + x, imageHeight + s.y + y) == Rgb{255, 255, 255};
    EXPECT_GT(white, 10u) << entries[i].label;
  }
  for (uint32_t y = 0; y < imageHeight; ++y)
    for (uint32_t x = 0; x < out.width; ++x) ASSERT_EQ(pixel(out, x, y), (Rgb{0, 0, 0}));
}

TEST(ImageLegend, StatusStripHasTheFiveDocumentedColoursUnderTheImage) {
  const adapters::PngImage out =
      adapters::withLegend(blackImage(640, 40), adapters::statusLegend());
  EXPECT_EQ(out.width, 640u);
  EXPECT_EQ(out.height, 40u + adapters::kLegendRowHeight);  // one row at 640 wide
  // patch.frag kStatusColors x 255: green drawn, yellow newly visible, blue frustum,
  // purple back-patch, red occlusion.
  expectSwatches(out, 40, adapters::statusLegend(),
                 {{89, 191, 89}, {242, 217, 64}, {89, 140, 242}, {179, 102, 230}, {242, 89, 77}});
}

TEST(ImageLegend, PatchTypeStripHasTheFourTypeColours) {
  const adapters::PngImage out =
      adapters::withLegend(blackImage(320, 20), adapters::patchTypeLegend());
  expectSwatches(out, 20, adapters::patchTypeLegend(),
                 {{204, 199, 184}, {102, 166, 242}, {242, 153, 64}, {217, 89, 166}});
}

TEST(ImageLegend, PatchIndexStripShowsTheHashColoursOfTheFirstPatches) {
  const adapters::PngImage out =
      adapters::withLegend(blackImage(400, 10), adapters::patchIndexLegend());
  std::vector<Rgb> rgb;
  for (const auto& e : adapters::patchIndexLegend()) rgb.push_back(e.rgb);
  expectSwatches(out, 10, adapters::patchIndexLegend(), rgb);
  EXPECT_NE(rgb[0], rgb[1]);
}

TEST(ImageLegend, ANarrowImageWrapsTheStripOntoMoreRows) {
  const adapters::PngImage out = adapters::withLegend(blackImage(96, 8), adapters::statusLegend());
  EXPECT_GT(out.height, 8u + 2 * adapters::kLegendRowHeight);
  expectSwatches(out, 8, adapters::statusLegend(),
                 {{89, 191, 89}, {242, 217, 64}, {89, 140, 242}, {179, 102, 230}, {242, 89, 77}});
}

}  // namespace
}  // namespace osd_cull
