#include "osd_cull/frame/verify/item_comparison.h"

#include "osd_cull/error.h"

#include <string>

namespace osd_cull::frame {

ItemComparison compareItems(std::span<const uint32_t> culled, std::span<const uint32_t> unculled) {
  if (culled.size() != unculled.size())
    throw Error("compareItems: images of " + std::to_string(culled.size()) + " and " +
                std::to_string(unculled.size()) + " pixels");
  ItemComparison c;
  c.pixels = culled.size();
  for (size_t p = 0; p < culled.size(); ++p) {
    c.covered += unculled[p] != 0;
    c.lost += unculled[p] != 0 && culled[p] == 0;
    c.differing += culled[p] != unculled[p];
  }
  return c;
}

}  // namespace osd_cull::frame
