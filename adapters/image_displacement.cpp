#include "adapters/image_displacement.h"

#include "adapters/image_channel.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/procedural_displacement.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace osd_cull::adapters {

char parseDisplacementChannel(std::string_view text) {
  if (text == "r" || text == "g" || text == "b" || text == "a") return text.front();
  throw Error("--displacement-channel: '" + std::string(text) + "' is not one of r, g, b, a");
}

bound::DisplacementMap loadDisplacementMap(const DisplacementOptions& options) {
  if (options.source.empty()) throw Error("displacement: no map given (a file or 'procedural')");
  detail::ImageChannel image;
  if (options.source == "procedural") {
    constexpr uint32_t kSize = 256;
    image.width = image.height = kSize;
    image.texels = scene::proceduralDisplacementTexels(kSize);
    image.normalized = true;
  } else {
    const std::filesystem::path path(options.source);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png")
      image = detail::readPngChannel(path, options.channel);
    else if (ext == ".exr")
      image = detail::readExrChannel(path, options.channel);
    else
      throw Error("displacement map " + options.source + ": unknown extension '" + ext +
                  "' (known: .png, .exr, or 'procedural')");
  }
  const double midlevel = options.midlevel.value_or(image.normalized ? 0.5 : 0.0);
  return bound::DisplacementMap(options.source, image.width, image.height, std::move(image.texels),
                                options.scale, midlevel, options.maxLod);
}

}  // namespace osd_cull::adapters
