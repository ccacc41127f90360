#pragma once
/// \file animation_support.h
/// \brief What the animation sources (deformers.cpp, skinning.cpp, key_frames.cpp) share:
/// checks of their inputs and the extent of a rest cage.

#include <glm/vec3.hpp>

#include <span>
#include <string>

namespace osd_cull::scene::detail {

/// \brief The axis-aligned box of a rest cage.
struct Extent {
  glm::dvec3 lo{0.0};
  glm::dvec3 hi{0.0};
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
  glm::dvec3 size() const { return hi - lo; }
};

/// \brief The box of `rest`.
/// \throws osd_cull::Error naming `who` and the first vertex when the cage is empty or a
/// coordinate is NaN or Inf.
Extent checkedExtent(std::span<const glm::dvec3> rest, const std::string& who);

/// \brief Throws osd_cull::Error "<who>: <what> must be finite[ and > 0]" when it is not.
void requireFinite(double value, const std::string& who, const std::string& what);
void requirePositive(double value, const std::string& who, const std::string& what);

/// \brief Throws osd_cull::Error when `out` does not have `expected` entries.
void requireOutputSize(size_t size, size_t expected, const std::string& who);

}  // namespace osd_cull::scene::detail
