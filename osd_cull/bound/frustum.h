#pragma once
/// \file frustum.h
/// \brief Clip-space bounds of a patch's control points and the view-frustum test,
/// double-precision CPU references of the GPU kernels (Sathe, "View Frustum Culling of
/// Catmull-Clark Patches in DirectX 11", Run-Time Step: the patch lies in the convex hull
/// of its control points, so the hull is tested against the frustum planes).
///
/// The test is done in homogeneous clip space, never after a division by w. A point of the
/// patch is a convex combination of the control points with the same weights in world and
/// clip space (the map is linear on homogeneous coordinates), and each frustum plane is a
/// half-space of R^4, so if every control point is outside one plane, so is the patch. This
/// holds for points behind the eye (w <= 0) too: Sathe's NDC box would not, so it is only
/// built when every w is positive. Gregory patches use their 20 points: the Gregory basis
/// functions are non-negative and sum to one, so the 20 points bound the patch as well.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

namespace osd_cull::bound {

/// \brief The six clip-volume planes in Vulkan convention; bit p of an outcode is plane p.
enum class FrustumPlane : uint32_t {
  Left = 0,    ///< inside: x >= -w
  Right = 1,   ///< inside: x <= w
  Bottom = 2,  ///< inside: y >= -w
  Top = 3,     ///< inside: y <= w
  Near = 4,    ///< inside: z >= 0
  Far = 5,     ///< inside: z <= w
};
inline constexpr uint32_t kFrustumPlaneCount = 6;
inline constexpr uint32_t kNoPlane = 6;  ///< FrustumResult::plane when not culled

/// \brief Clip-space bounds of a set of control points.
struct ClipBounds {
  uint32_t outsideAll = 0;  ///< bit p: every point is certainly outside plane p
  uint32_t outsideAny = 0;  ///< bit p: some point may be outside plane p
  bool finite = false;      ///< every input and clip coordinate is finite
  bool behindEye = true;    ///< some point may have w <= 0 (behind or on the eye plane)
  bool hasNdcBox = false;   ///< finite and no point behind the eye: the NDC box is valid
  glm::dvec3 ndcMin{0.0};   ///< NDC (x/w, y/w, z/w) box, widened by the rounding bound
  glm::dvec3 ndcMax{0.0};
};

/// \brief Transforms the points to clip space and bounds them: per-plane outcodes in
/// homogeneous form (a point is outside plane x >= -w when x + w < -margin, with margin =
/// kRelativeMargin times the magnitudes |x| and |w| are summed from, so rounding never
/// moves a point outside), the behind-the-eye flag (w <= margin), and, only when every
/// w is certainly positive, the NDC box. Non-finite input: finite = false, outsideAll = 0.
ClipBounds clipBounds(std::span<const glm::dvec3> points, const glm::dmat4& viewProj);

/// \brief Result of the frustum test.
struct FrustumResult {
  bool culled = false;
  uint32_t plane = kNoPlane;  ///< lowest plane every point is outside of, if culled
  bool finite = false;        ///< false: NaN/Inf input, kept
};

/// \brief Sathe's test on the convex hull: culled iff all points are outside the same one
/// of the six planes (ClipBounds::outsideAll != 0). Valid with points behind the eye.
/// Works for any number of points (16 Bézier, 20 Gregory).
FrustumResult frustumTest(std::span<const glm::dvec3> points, const glm::dmat4& viewProj);

}  // namespace osd_cull::bound
