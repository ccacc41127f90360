#pragma once
/// \file image_legend.h
/// \brief A legend strip under a written image: one coloured swatch and a short label per
/// colour the image uses (status views, patch-type colours, --debug-colors), drawn with a
/// built-in 5x7 bitmap font, so every picture explains its colours by itself.

#include "image_png.h"  // relative: also resolves where the headers are installed

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::adapters {

/// \brief One colour of a legend: its 8-bit RGB and a short label (letters, digits, space,
/// `-`, `=`, `/`, `.`; drawn in capitals).
struct LegendEntry {
  std::array<uint8_t, 3> rgb;
  std::string label;
};

/// \brief Where a swatch of a legend strip lies in the image `withLegend` returns: a
/// `size` x `size` square at (`x`, `y`), filled with its entry's colour.
struct LegendSwatch {
  uint32_t x = 0;
  uint32_t y = 0;
  uint32_t size = 0;
};

/// \brief Rows of the strip: 12 pixels each (a 5x7 glyph with its padding).
inline constexpr uint32_t kLegendRowHeight = 12;

/// \brief The status-view colours (shaders/patch/patch.frag kStatusColors, before
/// shading): green drawn, yellow newly visible, blue frustum-, purple back-patch-, red
/// occlusion-culled.
std::span<const LegendEntry> statusLegend();
/// \brief The patch-type colours (patch.frag kTypeColors): regular, boundary, corner, Gregory.
std::span<const LegendEntry> patchTypeLegend();
/// \brief --debug-colors: one colour per patch, a hash of its index (no fixed swatches;
/// the strip says so).
std::span<const LegendEntry> patchIndexLegend();

/// \brief The swatches of `entries` laid out in rows under an image `width` pixels wide,
/// `y` counted from the top of the strip.
std::vector<LegendSwatch> legendLayout(uint32_t width, std::span<const LegendEntry> entries);
/// \brief `image` (8-bit RGBA) with a legend strip of `entries` added below it: a dark
/// band, each entry's swatch and its label in white; width unchanged, taller by the rows.
/// \throws osd_cull::Error when the image is not 8-bit RGBA.
PngImage withLegend(const PngImage& image, std::span<const LegendEntry> entries);

}  // namespace osd_cull::adapters
