#pragma once
/// \file image_png.h
/// \brief PNG files: the renderer's images written (and read back), and any PNG libpng
/// reads decoded to 8 or 16 bits per sample (displacement maps read one channel of it,
/// image_displacement.h). The one PNG module: the library proper does no file I/O.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace osd_cull::adapters {

/// \brief An 8- or 16-bit image with 1 to 4 channels; 16-bit samples are stored as
/// uint16_t in host order in `samples16`, 8-bit ones in `samples8`.
struct PngImage {
  uint32_t width = 0;
  uint32_t height = 0;
  int channels = 0;
  int bitDepth = 8;
  std::vector<uint8_t> samples8;
  std::vector<uint16_t> samples16;
  bool hasAlpha = false;  ///< readPng: the last channel is alpha (2 or 4 channels)
};

/// \brief Writes an image; rows top to bottom.
/// \throws osd_cull::Error naming the file when it cannot be written or the sizes disagree.
void writePng(const std::filesystem::path& path, const PngImage& image);
/// \brief Reads any PNG libpng decodes, expanded to 8 or 16 bits per sample (palette to RGB,
/// gray below 8 bits to 8, tRNS to alpha); `hasAlpha` tells whether the last channel is alpha.
/// \throws osd_cull::Error naming the file when it is missing, not a PNG or corrupt.
PngImage readPng(const std::filesystem::path& path);

/// \brief RGBA8 color as read from RenderTarget::readColor.
PngImage colorImage(uint32_t width, uint32_t height, std::span<const uint8_t> rgba);
/// \brief Depth as 16-bit gray: drawn pixels spread over [0, 65534] from their nearest to
/// their farthest depth (near is dark), background (depth 1) is 65535.
PngImage depthImage(uint32_t width, uint32_t height, std::span<const float> depth);
/// \brief Item buffer as 8-bit RGB holding the item value's low 24 bits (R lowest): the
/// file decodes back to patch IDs (value - 1; 0 is background, white is an occluder).
PngImage itemImage(uint32_t width, uint32_t height, std::span<const uint32_t> items);

}  // namespace osd_cull::adapters
