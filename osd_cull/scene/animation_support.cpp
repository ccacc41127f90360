#include "osd_cull/scene/animation_support.h"

#include "osd_cull/error.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace osd_cull::scene::detail {

Extent checkedExtent(std::span<const glm::dvec3> rest, const std::string& who) {
  if (rest.empty()) throw Error(who + ": the rest cage has no vertices");
  Extent e{rest[0], rest[0]};
  for (size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3& p = rest[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(who + ": rest vertex " + std::to_string(i) + " has a NaN or Inf coordinate");
    e.lo = glm::min(e.lo, p);
    e.hi = glm::max(e.hi, p);
  }
  return e;
}

void requireFinite(double value, const std::string& who, const std::string& what) {
  if (!std::isfinite(value)) throw Error(who + ": " + what + " must be finite");
}

void requirePositive(double value, const std::string& who, const std::string& what) {
  if (!(std::isfinite(value) && value > 0.0))
    throw Error(who + ": " + what + " must be finite and > 0");
}

void requireOutputSize(size_t size, size_t expected, const std::string& who) {
  if (size != expected)
    throw Error(who + ": positions() needs an output of " + std::to_string(expected) +
                " vertices, got " + std::to_string(size));
}

}  // namespace osd_cull::scene::detail
