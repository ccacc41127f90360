#pragma once
/// \file camera.h
/// \brief A view: view and projection matrices (double, on the host) and a viewport.
///
/// Conventions: right-handed world, camera looks down -z in view space; projections map
/// to Vulkan clip space (x right, y down, depth 0 near .. 1 far; GLM_FORCE_DEPTH_ZERO_TO_ONE)
/// so that world "up" is up in the image.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>

namespace osd_cull::frame {

/// \brief View, projection and image size of one view.
struct Camera {
  glm::dmat4 view{1.0};
  glm::dmat4 projection{1.0};
  uint32_t width = 0;
  uint32_t height = 0;

  /// \brief projection * view.
  glm::dmat4 viewProjection() const { return projection * view; }
  /// \brief The camera position in world space.
  glm::dvec3 eye() const;

  /// \brief A perspective camera at `eye` looking at `target`; fovy in degrees.
  static Camera lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                       double fovyDegrees, uint32_t width, uint32_t height, double zNear,
                       double zFar);
  /// \brief An orthographic camera: the view volume [left, right] x [bottom, top] x
  /// [-zNear, -zFar] in view space (zNear < zFar).
  static Camera orthographic(const glm::dmat4& view, double left, double right, double bottom,
                             double top, double zNear, double zFar, uint32_t width,
                             uint32_t height);
};

/// \brief Perspective projection in Vulkan conventions (y flipped, depth 0..1).
glm::dmat4 perspectiveVk(double fovyRadians, double aspect, double zNear, double zFar);

/// \brief Orthographic projection in Vulkan conventions (y flipped, depth 0..1).
glm::dmat4 orthographicVk(double left, double right, double bottom, double top, double zNear,
                          double zFar);

/// \brief Axis-aligned bounds of points.
struct Bounds {
  glm::dvec3 lo{0.0};
  glm::dvec3 hi{0.0};
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  double radius() const;  ///< half the diagonal
  /// \brief The 8 corners (bit 0: x, bit 1: y, bit 2: z; set: hi).
  std::array<glm::dvec3, 8> corners() const;
};
Bounds boundsOf(std::span<const glm::dvec3> points);
/// \brief The bounds of both (componentwise min of lo, max of hi).
Bounds unite(const Bounds& a, const Bounds& b);

/// \brief A perspective camera looking at the bounds' center from direction `fromDirection`
/// (pointing from the center towards the eye), far enough that the bounding sphere fits
/// the smaller field of view; near and far planes enclose the sphere.
Camera frameBounds(const Bounds& bounds, const glm::dvec3& fromDirection, const glm::dvec3& up,
                   double fovyDegrees, uint32_t width, uint32_t height);

/// \brief The perspective `camera` moved along its own view axis and aimed at the centre of
/// the points' bounds so that every point just fits within `fill` of the image's half-extent
/// on its tighter side (direction, up, field of view and image size kept; near and far
/// enclose the points). Given an object's control points, the object fills the image where
/// frameBounds' bounding sphere leaves a flat or elongated one a third of it. An
/// orthographic camera, or no points, returns `camera` unchanged.
Camera frameTightly(const Camera& camera, std::span<const glm::dvec3> points, double fill = 0.92);

/// \brief The camera of an object placed by `model` (object → world): view · model, composed
/// in double. Culling and drawing with it work in the object's own coordinates, so the GPU
/// never rounds world coordinates to float: a mesh 1e5 from the origin, seen from nearby,
/// culls and draws as the same mesh at the origin (docs/algorithms/instances.md). A mirroring
/// model (negative determinant) makes isMirrored() true; the draws flip their front face.
Camera instanceCamera(const Camera& camera, const glm::dmat4& model);

/// \brief Whether the camera's view (possibly composed with a model) mirrors space
/// (negative determinant of its 3x3 part): projected triangles change winding.
bool isMirrored(const Camera& camera);

/// \brief Rotates the camera about the world axis `axis` through `pivot` by `degrees`.
Camera orbit(const Camera& camera, const glm::dvec3& pivot, const glm::dvec3& axis, double degrees);

}  // namespace osd_cull::frame
