#pragma once
/// \file coordinate_limit.h
/// \brief The largest coordinate a loaded mesh may have, and the check every reader uses.

#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <string>

namespace osd_cull::adapters {

/// \brief Largest coordinate magnitude a cage or patch file may have: 1e18.
///
/// Control points are drawn and culled in fp32, whose largest value is 3.4e38. The bound and
/// cull kernels square coordinate differences (distances, plane tests, box extents): with
/// |x| <= 1e18 a squared diagonal is at most 3 (2e18)^2 = 1.2e37, which still fits with
/// room for the products of the view-projection matrix. A 1e38 coordinate overflows at the
/// first square (the mesh silently draws nothing) and 1e308 does not even convert to fp32.
inline constexpr double kMaxCoordinate = 1e18;

/// \brief What is wrong with a coordinate beyond kMaxCoordinate ("1e+38 is beyond ±1e18,
/// the range fp32 drawing can represent ..."), or nullopt when it is in range.
std::optional<std::string> coordinateProblem(double value);

/// \brief Throws osd_cull::Error "FILE: vertex N has coordinate X, ..." for the first
/// position with a coordinate beyond kMaxCoordinate.
void checkCoordinateRange(std::span<const glm::dvec3> positions, const std::string& file);

}  // namespace osd_cull::adapters
