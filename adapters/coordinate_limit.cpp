#include "adapters/coordinate_limit.h"

#include "adapters/text_input.h"

#include <glm/common.hpp>

#include <cmath>
#include <sstream>

namespace osd_cull::adapters {

std::optional<std::string> coordinateProblem(double value) {
  if (std::abs(value) <= kMaxCoordinate) return std::nullopt;
  std::ostringstream s;
  s << value << " is beyond ±1e18, the range fp32 drawing and culling can represent "
    << "(squared distances must stay below 3.4e38); scale the mesh down";
  return s.str();
}

void checkCoordinateRange(std::span<const glm::dvec3> positions, const std::string& file) {
  for (size_t v = 0; v < positions.size(); ++v)
    for (int i = 0; i < 3; ++i)
      if (auto problem = coordinateProblem(positions[v][i]))
        detail::fail(file, 0, "vertex " + std::to_string(v + 1) + " has coordinate " + *problem);
}

std::optional<std::string> extentProblem(std::span<const glm::dvec3> points, const char* what) {
  if (points.empty()) return std::nullopt;
  glm::dvec3 lo = points.front(), hi = points.front();
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 d = hi - lo;
  const double diagonal = std::hypot(d.x, d.y, d.z);  // no underflow of 1e-300 squared
  if (diagonal >= kMinExtent) return std::nullopt;
  std::ostringstream s;
  if (lo == hi)
    s << "degenerate extent: all " << points.size() << " " << what << " coincide at (" << lo.x
      << ", " << lo.y << ", " << lo.z << ")";
  else
    s << "degenerate extent " << diagonal << " (the bounding-box diagonal of " << points.size()
      << " " << what << "), below 1e-18, the smallest size fp32 drawing and culling can resolve "
      << "(squared distances must stay above 1.2e-38)";
  return s.str();
}

void checkExtent(std::span<const glm::dvec3> positions, const std::string& file) {
  if (auto problem = extentProblem(positions, "vertices"))
    detail::fail(file, 0, *problem + ": scale the mesh up");
}

}  // namespace osd_cull::adapters
