#include "osd_cull/frame/draw/png_io.h"

#include "osd_cull/error.h"

#include <png.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>

namespace osd_cull::frame {

namespace {

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<FILE, FileCloser>;

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  auto* where = static_cast<std::string*>(png_get_error_ptr(png));
  *where = message;
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

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
      png_create_write_struct(PNG_LIBPNG_VER_STRING, message.get(), onPngError, onPngWarning);
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
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error("PNG " + path.string() + ": cannot open");
  // Heap-held: the error handler writes it and longjmps back (locals changed between
  // setjmp and longjmp would be indeterminate).
  auto message = std::make_unique<std::string>();
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, message.get(), onPngError, onPngWarning);
  if (!png) throw Error("PNG " + path.string() + ": libpng init failed");
  png_infop info = png_create_info_struct(png);
  PngImage image;
  std::vector<uint8_t> bytes;
  std::vector<png_bytep> rows;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw Error("PNG " + path.string() + ": " +
                (message->empty() ? std::string("read failed") : *message));
  }
  png_init_io(png, file.get());
  png_read_info(png, info);
  image.width = png_get_image_width(png, info);
  image.height = png_get_image_height(png, info);
  image.bitDepth = png_get_bit_depth(png, info);
  image.channels = png_get_channels(png, info);
  const size_t rowBytes = png_get_rowbytes(png, info);
  bytes.resize(rowBytes * image.height);
  rows.resize(image.height);
  for (uint32_t y = 0; y < image.height; ++y) rows[y] = bytes.data() + y * rowBytes;
  png_read_image(png, rows.data());
  png_destroy_read_struct(&png, &info, nullptr);
  if (image.bitDepth == 16) {
    image.samples16.resize(bytes.size() / 2);
    for (size_t i = 0; i < image.samples16.size(); ++i)
      image.samples16[i] = static_cast<uint16_t>((bytes[2 * i] << 8) | bytes[2 * i + 1]);
  } else {
    image.samples8 = std::move(bytes);
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

}  // namespace osd_cull::frame
