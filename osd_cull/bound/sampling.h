#pragma once
/// \file sampling.h
/// \brief Dense sampling of a patch in double: the ground truth that cull decisions are
/// checked against (tests, `osd-cull verify`). A culled patch must have no sample that is
/// front-facing (back-patch tests) or inside the clip volume (frustum test).

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace osd_cull::bound {

/// \brief Surface points and their normals N = Bu x Bv (not normalized), with the tangent
/// lengths |Bu| |Bv| used to make the front-facing tolerance scale-free.
struct SurfaceSamples {
  std::vector<glm::dvec3> position;
  std::vector<glm::dvec3> normal;
  std::vector<double> tangentScale;  ///< |Bu| * |Bv|
};

/// \brief Samples a 16-point Bézier or 20-point Gregory patch on the (n+1) x (n+1) grid
/// u, v in {0, 1/n, ..., 1} (edges and corners included); Gregory normals use the true
/// derivatives. \throws osd_cull::Error for another point count or n < 1.
SurfaceSamples samplePatch(std::span<const glm::dvec3> points, int n);

/// \brief True if some sample is front-facing from `eye`:
/// dot(N, eye - B) > tolerance * |Bu| |Bv| |eye - B|, i.e. the view ray makes an angle of
/// more than about `tolerance` radians with the tangent plane (a ray closer to edge-on is
/// within the rounding of the sampling itself).
bool anyFrontFacing(const SurfaceSamples& samples, const glm::dvec3& eye, double tolerance = 1e-9);

/// \brief True if some sample lies in the clip volume -w <= x, y <= w, 0 <= z <= w, each
/// bound widened by tolerance times the magnitudes the clip coordinates are summed from.
bool anyInsideClipVolume(const SurfaceSamples& samples, const glm::dmat4& viewProj,
                         double tolerance = 1e-9);

}  // namespace osd_cull::bound
