#pragma once
/// \file item_comparison.h
/// \brief The same-image check of issue 10 ("0 pixels lost, < 0.01% differing"): a culled
/// frame's item image (RenderTarget::readItems) against the same frame drawn without
/// culling.

#include <cstdint>
#include <span>

namespace osd_cull::frame {

/// \brief Pixel counts of a culled item image against the unculled one.
struct ItemComparison {
  uint64_t pixels = 0;     ///< of the image
  uint64_t covered = 0;    ///< covered by a patch or occluder in the unculled image
  uint64_t lost = 0;       ///< covered unculled, background culled: must be 0
  uint64_t differing = 0;  ///< another item (depth ties between neighbours), or lost
  /// \brief differing / pixels (0 for an empty image).
  double differingShare() const { return pixels ? double(differing) / double(pixels) : 0.0; }
};

/// \brief Compares two item images pixel by pixel (item 0 = background).
/// \throws osd_cull::Error when their sizes differ.
ItemComparison compareItems(std::span<const uint32_t> culled, std::span<const uint32_t> unculled);

}  // namespace osd_cull::frame
