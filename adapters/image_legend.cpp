#include "adapters/image_legend.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <cctype>
#include <string_view>

namespace osd_cull::adapters {
namespace {

constexpr uint32_t kSwatch = 8;        // swatch side, pixels
constexpr uint32_t kGlyphAdvance = 6;  // 5 columns and one of space
constexpr uint32_t kEntryGap = 10;     // between one label and the next swatch
constexpr std::array<uint8_t, 3> kBand{32, 32, 32};
constexpr std::array<uint8_t, 3> kText{255, 255, 255};

// 5x7 glyphs, one byte per row (bit 4 leftmost) of the characters in kGlyphChars.
constexpr std::string_view kGlyphChars = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-=/.";
constexpr uint8_t kGlyphs[][7] = {
    {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E},
    {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E},
    {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11},
    {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C},
    {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F},
    {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11},
    {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11},
    {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04},
    {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11},
    {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F},
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C},
    {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}, {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00},
    {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}, {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}};
static_assert(std::size(kGlyphs) == kGlyphChars.size());

// The 8-bit value of a shader colour component (patch.frag), rounded to nearest.
constexpr uint8_t byte(double c) { return static_cast<uint8_t>(c * 255.0 + 0.5); }
constexpr std::array<uint8_t, 3> rgb(double r, double g, double b) {
  return {byte(r), byte(g), byte(b)};
}

uint32_t entryWidth(const LegendEntry& e) {
  return kSwatch + 4 + kGlyphAdvance * static_cast<uint32_t>(e.label.size());
}

void fill(PngImage& image, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h,
          std::array<uint8_t, 3> c) {
  for (uint32_t y = y0; y < std::min(y0 + h, image.height); ++y)
    for (uint32_t x = x0; x < std::min(x0 + w, image.width); ++x) {
      uint8_t* p = &image.samples8[4 * (size_t(y) * image.width + x)];
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }
}

void drawText(PngImage& image, uint32_t x0, uint32_t y0, const std::string& text) {
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    const size_t g = kGlyphChars.find(c);
    if (g == std::string_view::npos) continue;  // space, or a character the font lacks
    const uint32_t x = x0 + kGlyphAdvance * static_cast<uint32_t>(i);
    for (uint32_t row = 0; row < 7; ++row)
      for (uint32_t col = 0; col < 5; ++col)
        if (kGlyphs[g][row] & (0x10u >> col)) fill(image, x + col, y0 + row, 1, 1, kText);
  }
}

}  // namespace

std::span<const LegendEntry> statusLegend() {
  static const LegendEntry entries[] = {{rgb(0.35, 0.75, 0.35), "drawn"},
                                        {rgb(0.95, 0.85, 0.25), "newly visible"},
                                        {rgb(0.35, 0.55, 0.95), "frustum"},
                                        {rgb(0.70, 0.40, 0.90), "back-patch"},
                                        {rgb(0.95, 0.35, 0.30), "occluded"}};
  return entries;
}

std::span<const LegendEntry> patchTypeLegend() {
  static const LegendEntry entries[] = {{rgb(0.80, 0.78, 0.72), "regular"},
                                        {rgb(0.40, 0.65, 0.95), "boundary"},
                                        {rgb(0.95, 0.60, 0.25), "corner"},
                                        {rgb(0.85, 0.35, 0.65), "Gregory"}};
  return entries;
}

// shaders/common/shading.glsl debugColor: a PCG hash of the patch index.
std::array<uint8_t, 3> debugColor(uint32_t index) {
  uint32_t h = index * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return rgb((h & 255u) / 255.0 * 0.7 + 0.3, ((h >> 8u) & 255u) / 255.0 * 0.7 + 0.3,
             ((h >> 16u) & 255u) / 255.0 * 0.7 + 0.3);
}

std::span<const LegendEntry> patchIndexLegend() {
  static const LegendEntry entries[] = {{debugColor(0), "patch 0"},
                                        {debugColor(1), "patch 1"},
                                        {debugColor(2), "patch 2 ... a colour per patch"}};
  return entries;
}

std::vector<LegendSwatch> legendLayout(uint32_t width, std::span<const LegendEntry> entries) {
  std::vector<LegendSwatch> swatches;
  uint32_t x = 4, row = 0;
  for (const LegendEntry& e : entries) {
    if (x > 4 && x + entryWidth(e) > width) x = 4, ++row;  // wrap onto a new row
    swatches.push_back({x, row * kLegendRowHeight + (kLegendRowHeight - kSwatch) / 2, kSwatch});
    x += entryWidth(e) + kEntryGap;
  }
  return swatches;
}

PngImage withLegend(const PngImage& image, std::span<const LegendEntry> entries) {
  if (image.bitDepth != 8 || image.channels != 4)
    throw Error("legend strip: the image is not 8-bit RGBA");
  const std::vector<LegendSwatch> swatches = legendLayout(image.width, entries);
  const uint32_t rows = swatches.empty() ? 0 : swatches.back().y / kLegendRowHeight + 1;
  PngImage out = image;
  out.height = image.height + rows * kLegendRowHeight;
  out.samples8.resize(size_t(4) * out.width * out.height);
  fill(out, 0, image.height, out.width, rows * kLegendRowHeight, kBand);
  for (size_t i = 0; i < swatches.size(); ++i) {
    const LegendSwatch& s = swatches[i];
    fill(out, s.x, image.height + s.y, s.size, s.size, entries[i].rgb);
    drawText(out, s.x + s.size + 4, image.height + s.y, entries[i].label);
  }
  return out;
}

}  // namespace osd_cull::adapters
