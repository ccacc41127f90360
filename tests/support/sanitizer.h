#pragma once
/// \file sanitizer.h
/// \brief Smaller workloads for the longest verification tests in a sanitizer build
/// (cmake/OsdCullSanitizers.cmake defines OSD_CULL_SANITIZER_BUILD), so that the suite
/// passes under ASan + UBSan with the normal timeout.

#include <algorithm>
#include <cstdint>

namespace osd_cull::test {

#if defined(OSD_CULL_SANITIZER_BUILD)
inline constexpr bool kSanitizerBuild = true;
#else
inline constexpr bool kSanitizerBuild = false;
#endif

/// \brief `count`, or `count / divisor` (at least 1) in a sanitizer build.
constexpr uint32_t sanitizerScaled(uint32_t count, uint32_t divisor) {
  return kSanitizerBuild ? std::max(1u, count / divisor) : count;
}

}  // namespace osd_cull::test
