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

/// \brief Smallest extent (bounding-box diagonal) a mesh may have: 1e-18, kMaxCoordinate's
/// mirror. The cull kernels square coordinate differences in fp32: with extents of at least
/// 1e-18 the squares stay above fp32's smallest normal number, 1.2e-38. A mesh whose
/// vertices all coincide, or whose coordinates are 1e-320 (subnormal doubles, zero in
/// fp32), has no size to frame, draw or cull.
inline constexpr double kMinExtent = 1e-18;

/// \brief What is wrong with the extent of `points` (their bounding-box diagonal), e.g.
/// "degenerate extent: all 8 vertices coincide at (1, 2, 3)" or "degenerate extent 1e-300
/// (the bounding-box diagonal of 3 vertices), below 1e-18 ..."; nullopt when it is at least
/// kMinExtent. `what` names the points in the message ("vertices", "control points").
std::optional<std::string> extentProblem(std::span<const glm::dvec3> points, const char* what);

/// \brief Throws osd_cull::Error "FILE: degenerate extent: ..." (extentProblem()) for a
/// mesh file whose positions have no size.
void checkExtent(std::span<const glm::dvec3> positions, const std::string& file);

/// \brief What is wrong with a coordinate beyond kMaxCoordinate ("1e+38 is beyond ±1e18,
/// the range fp32 drawing can represent ..."), or nullopt when it is in range.
std::optional<std::string> coordinateProblem(double value);

/// \brief Throws osd_cull::Error "FILE: vertex N has coordinate X, ..." for the first
/// position with a coordinate beyond kMaxCoordinate.
void checkCoordinateRange(std::span<const glm::dvec3> positions, const std::string& file);

}  // namespace osd_cull::adapters
