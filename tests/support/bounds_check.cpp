#include "support/bounds_check.h"

#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/bound/patch_eval.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace osd_cull::test {
namespace {

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

BoundsCheck checkBounds(const PatchSet& set, bound::BackPatchMethod method,
                        std::span<const frame::PatchBounds> gpu) {
  BoundsCheck r;
  const std::vector<bound::ConeOfNormals> reference = bound::buildPatchCones(set, method);
  auto fail = [&](uint32_t p, const std::string& what) {
    ++r.violations;
    if (r.firstViolations.size() < 8)
      r.firstViolations.push_back("patch " + std::to_string(p) + ": " + what);
  };
  for (uint32_t p = 0; p < set.patchCount(); ++p) {
    ++r.patches;
    const auto points = set.controlPoints(p);
    const bool bezier = set.type(p) == PatchType::Bezier;
    const bound::ConeOfNormals& g = gpu[p].cone;
    const bound::ConeOfNormals& ref = reference[p];
    if (bezier) {
      const bound::DerivativeBounds d = bound::bezierDerivativeBounds(points);
      const bound::DerivativeBounds& gd = gpu[p].derivatives;
      if (!(gd.g >= d.g)) fail(p, "G " + std::to_string(gd.g) + " < " + std::to_string(d.g));
      if (!(gd.h >= d.h)) fail(p, "H " + std::to_string(gd.h) + " < " + std::to_string(d.h));
      if (!(gd.maxAbs >= d.maxAbs)) fail(p, "max |coordinate| below the reference");
    }
    if (!g.valid) {
      r.lost += ref.valid;
      continue;
    }
    if (!ref.valid && ref.reason == bound::BackPatchVerdict::NonFinite) {
      fail(p, "valid cone for non-finite points");
      continue;
    }
    const double gamma = std::asin(std::min(1.0, g.sinAngle));
    const double slack = 1e-12;
    if (!(g.angle >= gamma - slack)) fail(p, "half-angle below asin(sin)");
    // Normals on a grid.
    double minN = std::numeric_limits<double>::infinity();
    for (int j = 0; j <= 16; ++j)
      for (int i = 0; i <= 16; ++i) {
        const double u = i / 16.0, v = j / 16.0;
        const bound::PatchSample s =
            bezier ? bound::evaluateBezier(points, u, v) : bound::evaluateGregory(points, u, v);
        const glm::dvec3 n = glm::cross(s.du, s.dv);
        const double len = glm::length(n);
        minN = std::min(minN, len);
        if (len > 1e-300 && angleBetween(g.axis, n) > gamma + slack) {
          std::ostringstream os;
          os << "normal at (" << u << ", " << v << ") " << angleBetween(g.axis, n)
             << " rad from the axis, half-angle " << gamma;
          fail(p, os.str());
          i = j = 17;
        }
      }
    if (!(g.minNormal <= minN * (1.0 + 1e-9) + 1e-300)) fail(p, "min |N| above a sampled |N|");
    if (bezier && method == bound::BackPatchMethod::NCone) {
      const auto coeffs = bound::normalPatch(points);
      for (const glm::dvec3& n : coeffs) {
        if (glm::length(n) == 0.0) continue;
        if (angleBetween(g.axis, n) > gamma + slack) {
          fail(p, "normal-patch coefficient outside the cone");
          break;
        }
        if (!(g.minNormal <= glm::dot(n, glm::normalize(g.axis)) * (1.0 + 1e-9) + 1e-300)) {
          fail(p, "min |N| above a coefficient's component along the axis");
          break;
        }
      }
    }
    // Apex cone and radius.
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& q : points) centre += q;
    centre /= double(points.size());
    const glm::dvec3 a = glm::normalize(g.axis);
    double rho = 0.0;
    for (const glm::dvec3& q : points) {
      const glm::dvec3 d = q - g.apex;
      const double tol = 1e-12 * (glm::length(q) + glm::length(g.apex));
      if (!(glm::dot(d, a) >= glm::length(d) * g.sinAngle - tol)) {
        fail(p, "control point outside the apex cone");
        break;
      }
      const glm::dvec3 c = q - centre;
      rho = std::max(rho, glm::length(c - glm::dot(c, a) * a));
    }
    if (!(g.maxRadius >= rho * (1.0 - 1e-12))) fail(p, "max radius below the points'");
    if (ref.valid) {
      ++r.bothValid;
      const double excess = g.angle - ref.angle;
      r.maxAngleExcess = r.bothValid == 1 ? excess : std::max(r.maxAngleExcess, excess);
      r.minAngleExcess = r.bothValid == 1 ? excess : std::min(r.minAngleExcess, excess);
      r.containsReference += g.angle >= ref.angle + angleBetween(g.axis, ref.axis);
    }
  }
  return r;
}

}  // namespace osd_cull::test
