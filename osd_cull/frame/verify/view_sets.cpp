#include "osd_cull/frame/verify/view_sets.h"

#include "osd_cull/error.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace osd_cull::frame {

const char* toString(ViewSet set) { return set == ViewSet::Sphere ? "sphere" : "whole-object"; }

ViewSet parseViewSet(std::string_view name) {
  if (name == "sphere") return ViewSet::Sphere;
  if (name == "whole-object") return ViewSet::WholeObject;
  throw Error("unknown view set '" + std::string(name) + "' (known: sphere, whole-object)");
}

namespace {

glm::dvec3 uniformDirection(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), phi(0.0, 2.0 * std::numbers::pi);
  const double z = u(rng), a = phi(rng), s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(a), s * std::sin(a), z};
}

// A unit vector perpendicular to `d`, uniformly distributed around it.
glm::dvec3 perpendicular(const glm::dvec3& d, std::mt19937_64& rng) {
  for (;;) {
    const glm::dvec3 r = uniformDirection(rng);
    const glm::dvec3 p = r - glm::dot(r, d) * d;
    if (glm::length(p) > 1e-3) return glm::normalize(p);
  }
}

}  // namespace

std::vector<Camera> randomViews(const Bounds& bounds, const ViewSetOptions& options) {
  if (options.width == 0 || options.height == 0)
    throw Error("randomViews: image size must be positive");
  if (!(options.fovyDegrees > 0.0 && options.fovyDegrees < 170.0))
    throw Error("randomViews: fovy must be in (0, 170) degrees");
  const double r = std::max(bounds.radius(), 1e-300);
  const double fovy = glm::radians(options.fovyDegrees);
  const double aspect = double(options.width) / double(options.height);
  const double fovx = 2.0 * std::atan(std::tan(fovy * 0.5) * aspect);
  const double half = 0.5 * std::min(fovy, fovx);
  const double fit = r / std::sin(half);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Camera> views;
  views.reserve(options.count);
  for (uint32_t i = 0; i < options.count; ++i) {
    const glm::dvec3 dir = uniformDirection(rng);
    const double distance = options.set == ViewSet::Sphere ? fit : fit * (1.0 + unit(rng));
    const glm::dvec3 eye = bounds.center() + distance * dir;
    glm::dvec3 forward = -dir;
    if (options.set == ViewSet::WholeObject) {
      // Turn the view away from the centre by at most the slack the fit leaves.
      const double slack = std::max(0.0, half - std::asin(std::min(1.0, r / distance)));
      const double angle = slack * std::sqrt(unit(rng));
      forward = std::cos(angle) * forward + std::sin(angle) * perpendicular(forward, rng);
    }
    const glm::dvec3 up = perpendicular(forward, rng);
    views.push_back(Camera::lookAt(eye, eye + forward * distance, up, options.fovyDegrees,
                                   options.width, options.height, 0.5 * (distance - r),
                                   distance + 1.5 * r));
  }
  return views;
}

}  // namespace osd_cull::frame
