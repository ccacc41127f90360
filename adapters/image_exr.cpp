// EXR reading for displacement maps through OpenEXR: one channel as 32-bit floats.
#include "adapters/image_channel.h"

#include "osd_cull/error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <exception>
#include <string>

namespace osd_cull::adapters::detail {

ImageChannel readExrChannel(const std::filesystem::path& path, char channel) {
  const std::string where = "EXR " + path.string();
  if (!std::filesystem::exists(path)) throw Error(where + ": cannot open (no such file)");
  std::string name;
  switch (channel) {
    case 'r':
      name = "R";
      break;
    case 'g':
      name = "G";
      break;
    case 'b':
      name = "B";
      break;
    case 'a':
      name = "A";
      break;
    default:
      throw Error(where + ": channel '" + std::string(1, channel) + "' is not one of r, g, b, a");
  }
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imf::ChannelList& channels = header.channels();
    if (!channels.findChannel(name) && channel != 'a' && channels.findChannel("Y")) name = "Y";
    const Imf::Channel* found = channels.findChannel(name);
    if (!found) {
      std::string known;
      for (auto it = channels.begin(); it != channels.end(); ++it)
        known += (known.empty() ? "" : ", ") + std::string(it.name());
      throw Error(where + ": has no channel " + name + " (channels: " + known + ")");
    }
    if (found->xSampling != 1 || found->ySampling != 1)
      throw Error(where + ": channel " + name + " is subsampled; not supported");
    const Imath::Box2i window = header.dataWindow();
    const int64_t w = int64_t(window.max.x) - window.min.x + 1;
    const int64_t h = int64_t(window.max.y) - window.min.y + 1;
    if (w <= 0 || h <= 0 || w > 65536 || h > 65536)
      throw Error(where + ": data window of " + std::to_string(w) + " x " + std::to_string(h) +
                  " pixels is empty or larger than 65536 on a side");
    std::vector<float> rows(static_cast<size_t>(w * h));
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(rows.data()) -
                 (int64_t(window.min.x) + int64_t(window.min.y) * w) * int64_t(sizeof(float));
    frame.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * w));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);

    ImageChannel out;
    out.width = static_cast<uint32_t>(w);
    out.height = static_cast<uint32_t>(h);
    out.normalized = false;
    out.bitDepth = found->type == Imf::HALF ? 16 : 32;
    out.texels.resize(rows.size());
    for (int64_t y = 0; y < h; ++y)  // EXR rows run top to bottom; row 0 becomes t = 0
      std::copy_n(rows.begin() + y * w, w, out.texels.begin() + (h - 1 - y) * w);
    return out;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(where + ": " + e.what());
  }
}

void writeExrChannel(const std::filesystem::path& path, const ImageChannel& image,
                     const char* name) {
  const std::string where = "EXR " + path.string();
  const auto w = static_cast<int64_t>(image.width), h = static_cast<int64_t>(image.height);
  if (w <= 0 || h <= 0 || image.texels.size() != static_cast<size_t>(w * h))
    throw Error(where + ": " + std::to_string(image.texels.size()) + " texels for " +
                std::to_string(w) + " x " + std::to_string(h));
  std::vector<float> rows(image.texels.size());
  for (int64_t y = 0; y < h; ++y)
    std::copy_n(image.texels.begin() + (h - 1 - y) * w, w, rows.begin() + y * w);
  try {
    Imf::Header header(static_cast<int>(w), static_cast<int>(h));
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rows.data()), sizeof(float),
                                  sizeof(float) * static_cast<size_t>(w)));
    file.setFrameBuffer(frame);
    file.writePixels(static_cast<int>(h));
  } catch (const std::exception& e) {
    throw Error(where + ": " + e.what());
  }
}

}  // namespace osd_cull::adapters::detail
