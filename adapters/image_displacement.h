#pragma once
/// \file image_displacement.h
/// \brief Displacement maps from files (PNG 8/16-bit gray or RGBA with a chosen channel,
/// float EXR) or generated in code ("procedural"), as a bound::DisplacementMap with its
/// mip chain and min/max pyramid.

#include "osd_cull/bound/displaced_map.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace osd_cull::adapters {

/// \brief What displaces a mesh: P + N * scale * (D(s, t) - midlevel).
struct DisplacementOptions {
  /// A file (.png or .exr, by extension, case-insensitive) or "procedural"
  /// (scene::proceduralDisplacementTexels, 256 x 256, 4 octaves).
  std::string source;
  double scale = 1.0;
  /// Unset: 0.5 for unsigned images (PNG, procedural; values in [0, 1], as the DirectX SDK
  /// subdivision samples use a * 2 - 1), 0 for float images (EXR).
  std::optional<double> midlevel;
  char channel = 'r';   ///< 'r', 'g', 'b' or 'a'
  uint32_t maxLod = 0;  ///< coarsest mip level the draw samples (bound::DisplacementMap)
};

/// \brief Parses "r", "g", "b" or "a".
/// \throws osd_cull::Error naming the option for anything else.
char parseDisplacementChannel(std::string_view text);

/// \brief Reads or generates the map of `options`.
/// \throws osd_cull::Error naming the file and the problem (unknown extension, unreadable
/// file, missing channel, bad scale or midlevel).
bound::DisplacementMap loadDisplacementMap(const DisplacementOptions& options);

}  // namespace osd_cull::adapters
