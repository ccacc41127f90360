// PNG reading for displacement maps: any PNG libpng reads, expanded to 8 or 16 bits per
// sample (palette to RGB, low bit depths to 8, tRNS to alpha).
#include "adapters/image_channel.h"

#include "osd_cull/error.h"

#include <png.h>

#include <bit>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace osd_cull::adapters::detail {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

[[noreturn]] void onError(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message ? message : "libpng error";
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

// Reads the decoded samples. The setjmp lives in a function that owns no object with a
// destructor (the caller owns the buffers), so libpng's longjmp skips none.
bool decode(png_structp png, png_infop info, std::FILE* file, std::vector<uint8_t>& bytes,
            std::vector<png_bytep>* rows, uint32_t& width, uint32_t& height, int& channels,
            int& depth, bool& hasAlpha) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_user_limits(png, 1u << 16, 1u << 16);
  png_read_info(png, info);
  const int type = png_get_color_type(png, info);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8)
    png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (png_get_bit_depth(png, info) == 16 && std::endian::native == std::endian::little)
    png_set_swap(png);
  png_read_update_info(png, info);
  width = png_get_image_width(png, info);
  height = png_get_image_height(png, info);
  channels = png_get_channels(png, info);
  depth = png_get_bit_depth(png, info);
  const int outType = png_get_color_type(png, info);
  hasAlpha = (outType & PNG_COLOR_MASK_ALPHA) != 0;
  const size_t rowBytes = png_get_rowbytes(png, info);
  bytes.resize(rowBytes * height);
  rows->resize(height);
  for (uint32_t y = 0; y < height; ++y) (*rows)[y] = bytes.data() + y * rowBytes;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

ImageChannel readPngChannel(const std::filesystem::path& path, char channel) {
  const std::string where = "PNG " + path.string();
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error(where + ": cannot open");
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
    throw Error(where + ": not a PNG file (bad signature)");
  std::string message;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &message, onError, onWarning);
  if (!png) throw Error(where + ": libpng init failed");
  png_infop info = png_create_info_struct(png);
  png_set_sig_bytes(png, 8);
  std::vector<uint8_t> bytes;
  std::vector<png_bytep> rows;
  uint32_t width = 0, height = 0;
  int channels = 0, depth = 0;
  bool hasAlpha = false;
  const bool ok =
      info && decode(png, info, file.get(), bytes, &rows, width, height, channels, depth, hasAlpha);
  png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  if (!ok) throw Error(where + ": " + (message.empty() ? "cannot decode" : message));
  if (depth != 8 && depth != 16)
    throw Error(where + ": " + std::to_string(depth) + "-bit samples are not supported");

  // Sample index of the channel within a pixel.
  const bool gray = channels <= 2;
  int index = -1;
  switch (channel) {
    case 'r':
      index = 0;
      break;
    case 'g':
      index = gray ? 0 : 1;
      break;
    case 'b':
      index = gray ? 0 : 2;
      break;
    case 'a':
      index = hasAlpha ? channels - 1 : -1;
      break;
    default:
      break;
  }
  if (index < 0)
    throw Error(where + ": " +
                (channel == 'a'
                     ? std::string("has no alpha channel")
                     : "channel '" + std::string(1, channel) + "' is not one of r, g, b, a"));
  ImageChannel out;
  out.width = width;
  out.height = height;
  out.bitDepth = depth;
  out.normalized = true;
  out.texels.resize(static_cast<size_t>(width) * height);
  const double unit = depth == 16 ? 1.0 / 65535.0 : 1.0 / 255.0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t sample = (static_cast<size_t>(y) * width + x) * channels + index;
      double v = 0.0;
      if (depth == 16) {
        uint16_t s;
        std::memcpy(&s, bytes.data() + 2 * sample, 2);
        v = s * unit;
      } else {
        v = bytes[sample] * unit;
      }
      out.texels[static_cast<size_t>(height - 1 - y) * width + x] = static_cast<float>(v);
    }
  return out;
}

}  // namespace osd_cull::adapters::detail
