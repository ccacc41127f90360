#include "osd_cull/frame/camera.h"

#include "osd_cull/error.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osd_cull::frame {

glm::dvec3 Camera::eye() const { return glm::dvec3(glm::inverse(view)[3]); }

glm::dmat4 perspectiveVk(double fovyRadians, double aspect, double zNear, double zFar) {
  if (!(fovyRadians > 0.0 && fovyRadians < glm::pi<double>()) || !(aspect > 0.0) ||
      !(zNear > 0.0) || !(zFar > zNear))
    throw Error("perspective camera: need 0 < fovy < 180 degrees, aspect > 0, 0 < near < far");
  glm::dmat4 p = glm::perspective(fovyRadians, aspect, zNear, zFar);
  p[1][1] = -p[1][1];
  return p;
}

glm::dmat4 orthographicVk(double left, double right, double bottom, double top, double zNear,
                          double zFar) {
  if (!(right > left) || !(top > bottom) || !(zFar > zNear))
    throw Error("orthographic camera: need left < right, bottom < top, near < far");
  glm::dmat4 p = glm::ortho(left, right, bottom, top, zNear, zFar);
  p[1][1] = -p[1][1];
  p[3][1] = -p[3][1];
  return p;
}

Camera Camera::lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                      double fovyDegrees, uint32_t width, uint32_t height, double zNear,
                      double zFar) {
  if (width == 0 || height == 0) throw Error("camera: image size must be positive");
  const glm::dvec3 dir = target - eye;
  if (glm::length(dir) == 0.0 || glm::length(glm::cross(dir, up)) == 0.0)
    throw Error("camera: eye equals target, or up is parallel to the view direction");
  Camera c;
  c.view = glm::lookAt(eye, target, up);
  c.projection =
      perspectiveVk(glm::radians(fovyDegrees), double(width) / double(height), zNear, zFar);
  c.width = width;
  c.height = height;
  return c;
}

Camera Camera::orthographic(const glm::dmat4& view, double left, double right, double bottom,
                            double top, double zNear, double zFar, uint32_t width,
                            uint32_t height) {
  if (width == 0 || height == 0) throw Error("camera: image size must be positive");
  Camera c;
  c.view = view;
  c.projection = orthographicVk(left, right, bottom, top, zNear, zFar);
  c.width = width;
  c.height = height;
  return c;
}

double Bounds::radius() const { return 0.5 * glm::length(hi - lo); }

std::array<glm::dvec3, 8> Bounds::corners() const {
  std::array<glm::dvec3, 8> c;
  for (int k = 0; k < 8; ++k)
    c[k] = {(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z};
  return c;
}

Bounds boundsOf(std::span<const glm::dvec3> points) {
  Bounds b;
  if (points.empty()) return b;
  b.lo = glm::dvec3(std::numeric_limits<double>::infinity());
  b.hi = -b.lo;
  for (const auto& p : points) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

Bounds unite(const Bounds& a, const Bounds& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

Camera frameBounds(const Bounds& bounds, const glm::dvec3& fromDirection, const glm::dvec3& up,
                   double fovyDegrees, uint32_t width, uint32_t height) {
  const double r = std::max(bounds.radius(), 1e-9);
  const double fovy = glm::radians(fovyDegrees);
  const double aspect = double(width) / double(std::max(height, 1u));
  const double fovx = 2.0 * std::atan(std::tan(fovy * 0.5) * aspect);
  const double half = 0.5 * std::min(fovy, fovx);
  const double distance = r / std::sin(half);
  const glm::dvec3 eye = bounds.center() + glm::normalize(fromDirection) * distance;
  return Camera::lookAt(eye, bounds.center(), up, fovyDegrees, width, height,
                        std::max(distance - r * 1.5, distance * 1e-3), distance + r * 1.5);
}

Camera frameTightly(const Camera& camera, std::span<const glm::dvec3> points, double fill) {
  if (camera.projection[3][3] != 0.0 || points.empty()) return camera;  // orthographic
  const double tanX = 1.0 / std::abs(camera.projection[0][0]);
  const double tanY = 1.0 / std::abs(camera.projection[1][1]);
  const glm::dmat3 rotation(camera.view);  // world to view: rows right, up, back
  const glm::dmat3 toWorld = glm::transpose(rotation);
  const Bounds bounds = boundsOf(points);
  const glm::dvec3 center = bounds.center();
  // Eye at center + d * back: a point at view-space offset o lies d - o.z in front and
  // fits where |o.x| <= fill * tanX * (d - o.z), likewise y.
  double d = bounds.radius() * 1e-6 + 1e-12;
  for (const glm::dvec3& p : points) {
    const glm::dvec3 o = rotation * (p - center);
    d = std::max({d, o.z + std::abs(o.x) / (fill * tanX), o.z + std::abs(o.y) / (fill * tanY)});
  }
  double nearest = d, farthest = d;
  for (const glm::dvec3& p : points) {
    const double depth = d - (rotation * (p - center)).z;
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  const double fovyDegrees = glm::degrees(2.0 * std::atan(tanY));
  return Camera::lookAt(center + toWorld[2] * d, center, toWorld[1], fovyDegrees, camera.width,
                        camera.height, std::max(nearest * 0.5, d * 1e-4), farthest * 1.5);
}

Camera instanceCamera(const Camera& camera, const glm::dmat4& model) {
  Camera c = camera;
  c.view = camera.view * model;
  return c;
}

bool isMirrored(const Camera& camera) { return glm::determinant(glm::dmat3(camera.view)) < 0.0; }

Camera orbit(const Camera& camera, const glm::dvec3& pivot, const glm::dvec3& axis,
             double degrees) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), pivot);
  m = glm::rotate(m, glm::radians(degrees), glm::normalize(axis));
  m = glm::translate(m, -pivot);
  Camera c = camera;
  c.view = camera.view * glm::inverse(m);
  return c;
}

}  // namespace osd_cull::frame
