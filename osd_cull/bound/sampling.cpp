#include "osd_cull/bound/sampling.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <string>

namespace osd_cull::bound {

SurfaceSamples samplePatch(std::span<const glm::dvec3> points, int n) {
  if (n < 1) throw Error(std::string(__FILE__) + ": samplePatch needs n >= 1");
  if (points.size() != 16 && points.size() != 20)
    throw Error(std::string(__FILE__) +
                ": samplePatch takes 16 (Bézier) or 20 (Gregory) "
                "points, got " +
                std::to_string(points.size()));
  SurfaceSamples s;
  const size_t count = static_cast<size_t>(n + 1) * static_cast<size_t>(n + 1);
  s.position.reserve(count);
  s.normal.reserve(count);
  s.tangentScale.reserve(count);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      const PatchSample p =
          points.size() == 16 ? evaluateBezier(points, u, v) : evaluateGregory(points, u, v);
      s.position.push_back(p.position);
      s.normal.push_back(glm::cross(p.du, p.dv));
      s.tangentScale.push_back(glm::length(p.du) * glm::length(p.dv));
    }
  return s;
}

bool anyFrontFacing(const SurfaceSamples& samples, const glm::dvec3& eye, double tolerance) {
  for (size_t k = 0; k < samples.position.size(); ++k) {
    const glm::dvec3 toEye = eye - samples.position[k];
    const double facing = glm::dot(samples.normal[k], toEye);
    if (facing > tolerance * samples.tangentScale[k] * glm::length(toEye)) return true;
  }
  return false;
}

bool anyInsideClipVolume(const SurfaceSamples& samples, const glm::dmat4& viewProj,
                         double tolerance) {
  for (const glm::dvec3& p : samples.position) {
    const glm::dvec4 c = clipPoint(p, viewProj);
    const glm::dvec4 m = absClipPoint(p, viewProj);
    const double tx = tolerance * (m.x + m.w), ty = tolerance * (m.y + m.w);
    const double tz = tolerance * m.z, tw = tolerance * (m.z + m.w);
    if (c.x + c.w >= -tx && c.w - c.x >= -tx && c.y + c.w >= -ty && c.w - c.y >= -ty &&
        c.z >= -tz && c.w - c.z >= -tw)
      return true;
  }
  return false;
}

}  // namespace osd_cull::bound
