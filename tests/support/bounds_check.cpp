#include "support/bounds_check.h"

#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/bound/patch_eval.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace osd_cull::test {
namespace {

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The first sampled normal Bu x Bv (17 x 17 grid) more than gamma from `axis`, as a message
// (empty: none); `minN` gets the smallest sampled |N|.
std::string normalOutsideCone(std::span<const glm::dvec3> points, bool bezier,
                              const glm::dvec3& axis, double gamma, double& minN) {
  minN = std::numeric_limits<double>::infinity();
  std::string outside;
  for (int j = 0; j <= 16; ++j)
    for (int i = 0; i <= 16; ++i) {
      const double u = i / 16.0, v = j / 16.0;
      const bound::PatchSample s =
          bezier ? bound::evaluateBezier(points, u, v) : bound::evaluateGregory(points, u, v);
      const glm::dvec3 n = glm::cross(s.du, s.dv);
      const double len = glm::length(n);
      minN = std::min(minN, len);
      if (outside.empty() && len > 1e-300 && angleBetween(axis, n) > gamma + 1e-12) {
        std::ostringstream os;
        os << "normal at (" << u << ", " << v << ") " << angleBetween(axis, n)
           << " rad from the axis, half-angle " << gamma;
        outside = os.str();
      }
    }
  return outside;
}

// Whether a non-zero normal-patch coefficient of a Bézier patch lies more than gamma from
// `axis`.
bool coefficientOutsideCone(std::span<const glm::dvec3> points, const glm::dvec3& axis,
                            double gamma) {
  for (const glm::dvec3& n : bound::normalPatch(points))
    if (glm::length(n) != 0.0 && angleBetween(axis, n) > gamma + 1e-12) return true;
  return false;
}

void addViolation(BoundsCheck& r, uint32_t p, const std::string& what) {
  ++r.violations;
  if (r.firstViolations.size() < 8)
    r.firstViolations.push_back("patch " + std::to_string(p) + ": " + what);
}

// The statistics of a valid GPU cone (half-angle `angle`) against the reference's.
void compareWithReference(BoundsCheck& r, double angle, const glm::dvec3& axis,
                          const bound::ConeOfNormals& ref) {
  if (!ref.valid) return;
  ++r.bothValid;
  const double excess = angle - ref.angle;
  r.maxAngleExcess = r.bothValid == 1 ? excess : std::max(r.maxAngleExcess, excess);
  r.minAngleExcess = r.bothValid == 1 ? excess : std::min(r.minAngleExcess, excess);
  r.containsReference += angle >= ref.angle + angleBetween(axis, ref.axis);
}

}  // namespace

BoundsCheck checkDisplacedBounds(const PatchSet& set, bound::DisplacedExtension extension,
                                 std::span<const bound::DisplacementRange> ranges,
                                 std::span<const bound::DisplacedPatch> gpu) {
  BoundsCheck r;
  auto fail = [&](uint32_t p, const std::string& what) { addViolation(r, p, what); };
  for (uint32_t p = 0; p < set.patchCount(); ++p) {
    ++r.patches;
    const auto points = set.controlPoints(p);
    const bool bezier = set.type(p) == PatchType::Bezier;
    const bound::DisplacedPatch& g = gpu[p];
    const bound::DisplacementRange& range = ranges[p];
    // Dmin/Dmax: rounded outward to float, by at most one float step.
    const double step = 1.2e-7 * std::max(std::abs(range.dmin), std::abs(range.dmax)) + 1e-38;
    if (!(g.range.dmin <= range.dmin && g.range.dmin >= range.dmin - step))
      fail(p, "Dmin " + std::to_string(g.range.dmin) + " for " + std::to_string(range.dmin));
    if (!(g.range.dmax >= range.dmax && g.range.dmax <= range.dmax + step))
      fail(p, "Dmax " + std::to_string(g.range.dmax) + " for " + std::to_string(range.dmax));
    const bound::ConeOfNormals ref = bound::displacementCone(set, p, extension);
    if (!g.cone.valid) {
      r.lost += ref.valid;
      continue;
    }
    if (extension == bound::DisplacedExtension::Full) {
      fail(p, "a cone for the Full extension");
      continue;
    }
    if (!ref.valid && ref.reason == bound::BackPatchVerdict::NonFinite) {
      fail(p, "valid cone for non-finite points");
      continue;
    }
    // The kernel reads (cos α, sin α): both of one angle within its 1e-5 slack.
    const double gamma = std::asin(std::min(1.0, g.cone.sinAngle));
    if (!(std::abs(std::cos(g.cone.angle) - std::cos(gamma)) <= 1e-6))
      fail(p, "cos α and sin α disagree");
    double minN = 0.0;
    const std::string outside = normalOutsideCone(points, bezier, g.cone.axis, gamma, minN);
    if (!outside.empty()) fail(p, outside);
    if (bezier && extension == bound::DisplacedExtension::CoN &&
        coefficientOutsideCone(points, g.cone.axis, gamma))
      fail(p, "normal-patch coefficient outside the cone");
    compareWithReference(r, gamma, g.cone.axis, ref);
  }
  return r;
}

BoundsCheck checkBounds(const PatchSet& set, bound::BackPatchMethod method,
                        std::span<const frame::PatchBounds> gpu) {
  BoundsCheck r;
  const std::vector<bound::ConeOfNormals> reference = bound::buildPatchCones(set, method);
  auto fail = [&](uint32_t p, const std::string& what) { addViolation(r, p, what); };
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
    double minN = 0.0;
    const std::string outside = normalOutsideCone(points, bezier, g.axis, gamma, minN);
    if (!outside.empty()) fail(p, outside);
    if (!(g.minNormal <= minN * (1.0 + 1e-9) + 1e-300)) fail(p, "min |N| above a sampled |N|");
    if (bezier && method == bound::BackPatchMethod::NCone) {
      if (coefficientOutsideCone(points, g.axis, gamma))
        fail(p, "normal-patch coefficient outside the cone");
      for (const glm::dvec3& n : bound::normalPatch(points)) {
        if (glm::length(n) == 0.0) continue;
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
    compareWithReference(r, g.angle, g.axis, ref);
  }
  return r;
}

}  // namespace osd_cull::test
