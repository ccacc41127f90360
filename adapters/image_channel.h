#pragma once
/// \file image_channel.h
/// \brief One channel of an image file as floats (internal to adapters/): PNG (8/16-bit
/// gray, gray+alpha, RGB, RGBA, palette) through libpng and EXR (half, float or uint
/// channels) through OpenEXR.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace osd_cull::adapters::detail {

/// \brief A channel read from an image, rows flipped so that row 0 is the bottom row of
/// the picture (t = 0 in OBJ texture coordinates).
struct ImageChannel {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> texels;  ///< width * height, row-major
  /// True for unsigned integer images (PNG), whose values are normalised to [0, 1]; false
  /// for float images (EXR), read unchanged.
  bool normalized = true;
  int bitDepth = 8;  ///< bits per sample of the file (8, 16 for PNG; 16, 32 for EXR)
};

/// \brief Reads channel `channel` ('r', 'g', 'b' or 'a'; a gray image answers r with its
/// gray and refuses g and b, as an image without alpha refuses a) of a PNG file.
/// \throws osd_cull::Error naming the file and the problem (not a PNG, missing channel,
/// corrupt data).
ImageChannel readPngChannel(const std::filesystem::path& path, char channel);

/// \brief Reads channel `channel` of an EXR file: 'r' reads R (or Y of a luminance
/// image), 'g' G, 'b' B, 'a' A.
/// \throws osd_cull::Error naming the file and the problem.
ImageChannel readExrChannel(const std::filesystem::path& path, char channel);

/// \brief Writes one float channel as an EXR file with channel name `name` ("R", "Y", ...),
/// rows as ImageChannel holds them (row 0 becomes the bottom row). For tests and tools.
/// \throws osd_cull::Error naming the file when it cannot be written.
void writeExrChannel(const std::filesystem::path& path, const ImageChannel& image,
                     const char* name = "R");

}  // namespace osd_cull::adapters::detail
