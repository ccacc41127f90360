#include "adapters/coordinate_limit.h"

#include "adapters/text_input.h"

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

}  // namespace osd_cull::adapters
