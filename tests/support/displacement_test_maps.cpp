#include "support/displacement_test_maps.h"

#include <glm/common.hpp>

namespace osd_cull::test {

std::vector<bound::DisplacementMap> extremeDisplacementMaps(double scale) {
  std::vector<float> spike(32 * 32, 0.5f), step(32 * 32, 0.0f);
  spike[17 * 32 + 9] = 1.0f;
  for (size_t i = 0; i < step.size(); ++i) step[i] = (i % 32) < 16 ? 0.0f : 1.0f;
  std::vector<bound::DisplacementMap> maps;
  maps.emplace_back("spike", 32, 32, spike, 2.0 * scale, 0.5);
  maps.emplace_back("step", 32, 32, step, scale, 0.5);
  maps.emplace_back("all-max", 8, 8, std::vector<float>(64, 1.0f), scale, 0.5);
  maps.emplace_back("all-min", 8, 8, std::vector<float>(64, 0.0f), scale, 0.5);
  maps.emplace_back("scale-0", 32, 32, step, 0.0, 0.5);
  return maps;
}

CageMesh withPlanarUVs(CageMesh cage) {
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const glm::dvec3& p : cage.positions) {
    lo = glm::min(lo, glm::dvec2(p));
    hi = glm::max(hi, glm::dvec2(p));
  }
  const glm::dvec2 size = glm::max(hi - lo, glm::dvec2(1e-300));
  cage.uvs.clear();
  for (const glm::dvec3& p : cage.positions) cage.uvs.push_back((glm::dvec2(p) - lo) / size);
  cage.faceUVs = cage.faceVertices;
  return cage;
}

}  // namespace osd_cull::test
