#pragma once
/// \file clip_space.h
/// \brief Homogeneous clip-space helpers shared by every CPU reference test in bound/:
/// point transforms with rounding bounds, the 4D cross product and the clip-space eye.
///
/// Conventions (relied on by the GLSL mirrors of these functions):
/// - A view-projection matrix `viewProj` maps world points to Vulkan clip space as column
///   vectors, c = viewProj * (p, 1); the clip volume is -w <= x <= w, -w <= y <= w,
///   0 <= z <= w (GLM_FORCE_DEPTH_ZERO_TO_ONE).
/// - Every test rounds toward "visible": a quantity is only treated as having a sign when
///   its magnitude exceeds kRelativeMargin times an upper bound of the magnitudes it was
///   computed from (see absClipPoint()). The rounding error of the double computations is
///   below 100 ulps of that bound; the margin is 1e-12 (about 4500 ulps), so a decision never
///   rests on rounding, and scaling the scene by any factor gives the same decisions.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <optional>
#include <span>

namespace osd_cull::bound {

/// \brief Relative margin by which every double-precision decision rounds toward "visible".
inline constexpr double kRelativeMargin = 1e-12;

/// \brief c = viewProj * (p, 1).
glm::dvec4 clipPoint(const glm::dvec3& p, const glm::dmat4& viewProj);

/// \brief |viewProj| * (|p|, 1), component-wise absolute values: an upper bound of the
/// magnitude of every product summed in clipPoint(), used to bound its rounding error.
glm::dvec4 absClipPoint(const glm::dvec3& p, const glm::dmat4& viewProj);

/// \brief True when every coordinate of every point is finite (no NaN, no Inf).
bool allFinite(std::span<const glm::dvec3> points);

/// \brief True when every entry of the matrix is finite.
bool allFinite(const glm::dmat4& m);

/// \brief The generalized cross product of three homogeneous points (Loop et al.,
/// Appendix A): the oriented plane through a, b, c, with x·cross4(a, b, c) = det[x; a; b; c].
glm::dvec4 cross4(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c);

/// \brief The z component of cross4(): det of the x, y and w rows of [a b c].
double cross4Z(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c);

/// \brief The permanent of the absolute x, y, w rows of [a b c]: an upper bound of every
/// product summed in cross4Z(). Called with absClipPoint() values it bounds cross4Z() of
/// the exact clip points and the rounding error of computing it.
double cross4ZBound(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c);

/// \brief The homogeneous eye of a view-projection matrix: adj(viewProj) * (0, 0, 1, 0),
/// the point that maps to clip x = y = w = 0 (Loop et al. §4.1: f = [0 0 α 0]). Its w is
/// nonzero for a perspective projection, zero for an orthographic one.
glm::dvec4 homogeneousEye(const glm::dmat4& viewProj);

/// \brief The world-space eye (camera centre) of a perspective view-projection matrix;
/// nothing for an orthographic or singular matrix, or non-finite input.
std::optional<glm::dvec3> eyePosition(const glm::dmat4& viewProj);

/// \brief The sign σ (+1 or -1) with σ · cross4Z(clip B, clip Bu, clip Bv) of the same sign
/// as dot(Bu x Bv, eye - B) at every surface point (Loop et al. §4.1: "α is of known sign").
/// σ = sign(w of homogeneousEye()); 0 when the matrix has no finite eye (orthographic,
/// singular, non-finite, or the sign is within rounding of zero): then the tangent-plane
/// test keeps every patch. Computed once per view on the host.
double clipSpaceEyeSign(const glm::dmat4& viewProj);

}  // namespace osd_cull::bound
