// PNG files: writing the renderer's images, reading any PNG libpng decodes (expanded to 8
// or 16 bits per sample: palette to RGB, low bit depths to 8, tRNS to alpha), and one
// channel of it for displacement maps.
#include "adapters/image_png.h"

#include "adapters/image_channel.h"
#include "osd_cull/error.h"

#include <png.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

namespace osd_cull::adapters {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void onError(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message ? message : "libpng error";
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

int colorType(int channels) {
  switch (channels) {
    case 1:
      return PNG_COLOR_TYPE_GRAY;
    case 2:
      return PNG_COLOR_TYPE_GRAY_ALPHA;
    case 3:
      return PNG_COLOR_TYPE_RGB;
    case 4:
      return PNG_COLOR_TYPE_RGBA;
    default:
      throw Error("PNG: channels must be 1 to 4, got " + std::to_string(channels));
  }
}

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

void writePng(const std::filesystem::path& path, const PngImage& image) {
  const size_t samples = size_t{image.width} * image.height * image.channels;
  const bool wide = image.bitDepth == 16;
  if (image.bitDepth != 8 && image.bitDepth != 16)
    throw Error("PNG " + path.string() + ": bit depth must be 8 or 16");
  if ((wide ? image.samples16.size() : image.samples8.size()) != samples || samples == 0)
    throw Error("PNG " + path.string() + ": sample count does not match " +
                std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                std::to_string(image.channels));
  const int type = colorType(image.channels);
  // Big-endian rows for 16-bit samples.
  const size_t rowBytes = size_t{image.width} * image.channels * (wide ? 2 : 1);
  std::vector<uint8_t> bytes(rowBytes * image.height);
  if (wide) {
    for (size_t i = 0; i < samples; ++i) {
      bytes[2 * i] = static_cast<uint8_t>(image.samples16[i] >> 8);
      bytes[2 * i + 1] = static_cast<uint8_t>(image.samples16[i] & 0xFF);
    }
  } else {
    std::copy(image.samples8.begin(), image.samples8.end(), bytes.begin());
  }
  std::vector<png_bytep> rows(image.height);
  for (uint32_t y = 0; y < image.height; ++y) rows[y] = bytes.data() + y * rowBytes;

  File file(std::fopen(path.c_str(), "wb"));
  if (!file) throw Error("PNG " + path.string() + ": cannot open for writing");
  // Heap-held: the error handler writes it and longjmps back (locals changed between
  // setjmp and longjmp would be indeterminate).
  auto message = std::make_unique<std::string>();
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, message.get(), onError, onWarning);
  if (!png) throw Error("PNG " + path.string() + ": libpng init failed");
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw Error("PNG " + path.string() + ": " +
                (message->empty() ? std::string("write failed") : *message));
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, image.width, image.height, image.bitDepth, type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

PngImage readPng(const std::filesystem::path& path) {
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
  PngImage image;
  const bool ok = info && decode(png, info, file.get(), bytes, &rows, image.width, image.height,
                                 image.channels, image.bitDepth, image.hasAlpha);
  png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  if (!ok) throw Error(where + ": " + (message.empty() ? "cannot decode" : message));
  if (image.bitDepth == 16) {
    // decode() asked libpng for host-order 16-bit samples.
    image.samples16.resize(bytes.size() / 2);
    std::memcpy(image.samples16.data(), bytes.data(), image.samples16.size() * 2);
  } else if (image.bitDepth == 8) {
    image.samples8 = std::move(bytes);
  } else {
    throw Error(where + ": " + std::to_string(image.bitDepth) + "-bit samples are not supported");
  }
  return image;
}

PngImage colorImage(uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
  PngImage image{width, height, 4, 8, {rgba.begin(), rgba.end()}, {}};
  return image;
}

PngImage depthImage(uint32_t width, uint32_t height, std::span<const float> depth) {
  float lo = std::numeric_limits<float>::max(), hi = 0.0f;
  for (float d : depth)
    if (d < 1.0f) {
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  PngImage image{width, height, 1, 16, {}, std::vector<uint16_t>(depth.size())};
  const float range = hi > lo ? hi - lo : 1.0f;
  for (size_t i = 0; i < depth.size(); ++i)
    image.samples16[i] =
        depth[i] >= 1.0f
            ? 65535
            : static_cast<uint16_t>(std::clamp((depth[i] - lo) / range, 0.0f, 1.0f) * 65534.0f);
  return image;
}

PngImage itemImage(uint32_t width, uint32_t height, std::span<const uint32_t> items) {
  PngImage image{width, height, 3, 8, std::vector<uint8_t>(items.size() * 3), {}};
  for (size_t i = 0; i < items.size(); ++i) {
    image.samples8[3 * i + 0] = static_cast<uint8_t>(items[i] & 0xFF);
    image.samples8[3 * i + 1] = static_cast<uint8_t>((items[i] >> 8) & 0xFF);
    image.samples8[3 * i + 2] = static_cast<uint8_t>((items[i] >> 16) & 0xFF);
  }
  return image;
}

namespace detail {

ImageChannel readPngChannel(const std::filesystem::path& path, char channel) {
  const std::string where = "PNG " + path.string();
  const PngImage image = readPng(path);
  const uint32_t width = image.width, height = image.height;
  const int channels = image.channels, depth = image.bitDepth;
  const bool hasAlpha = image.hasAlpha;

  // Sample index of the channel within a pixel.
  const bool gray = channels <= 2;
  int index = -1;
  switch (channel) {
    case 'r':
      index = 0;
      break;
    case 'g':  // a gray image has no green or blue: refused, as 'a' without alpha is
      index = gray ? -1 : 1;
      break;
    case 'b':
      index = gray ? -1 : 2;
      break;
    case 'a':
      index = hasAlpha ? channels - 1 : -1;
      break;
    default:
      break;
  }
  if (index < 0)
    throw Error(where + ": " +
                (channel == 'a' ? std::string("has no alpha channel")
                 : gray && (channel == 'g' || channel == 'b')
                     ? "has no channel '" + std::string(1, channel) + "': a gray image has one " +
                           "color channel, read as r"
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
      const double v = (depth == 16 ? image.samples16[sample] : image.samples8[sample]) * unit;
      out.texels[static_cast<size_t>(height - 1 - y) * width + x] = static_cast<float>(v);
    }
  return out;
}

}  // namespace detail
}  // namespace osd_cull::adapters
