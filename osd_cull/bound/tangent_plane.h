#pragma once
/// \file tangent_plane.h
/// \brief Back-patch culling with the parametric tangent plane in clip space (Loop,
/// Nießner, Eisenacher, "Effective Back-Patch Culling for Hardware Tessellation", §3-§5
/// and the Pcnt rule of §7), double-precision CPU reference of the GPU kernel.
///
/// The clip-space control points b'_i = viewProj * (b_i, 1) give the 64 control planes
/// t'_i of T'(u,v) = cross4(B', B'u, B'v); only their z components are needed (§4.1): with
/// σ = clipSpaceEyeSign(viewProj), σ·T'_z(u,v) has the sign of dot(N, eye - B) (§4.2's
/// e·T(u,v)). By the convex-hull property of the Bézier form, if no σ·t'_z,i is positive
/// then no point of the patch is front-facing: the patch is culled (the Pcnt = 0 rule; the
/// paper's Ncnt = 64 rule would keep patches whose collapsed edges make some t_i zero).
///
/// Points behind the eye need no special case: the test is an identity between
/// homogeneous multilinear forms (e·T = f·T' / det M), valid for any w, and never divides
/// by w. Rounding: each t'_z,i comes with an upper bound m_i of the magnitudes it is summed
/// from; a coefficient counts as possibly positive unless σ t'_z,i + kRelativeMargin·m_i
/// <= 0. Terms whose three control points are equal (collapsed edges, zero-area patches)
/// are exactly zero and are skipped, so Pcnt classifies collapsed patches exactly.

#include "osd_cull/bound/back_patch.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull::bound {

/// \brief The z components of the 64 clip-space control planes, u fastest (8*row_v + col_u),
/// each with an upper bound of the magnitudes summed into it (its rounding error, and the
/// error from rounding the clip-space points, is below kRelativeMargin * bound).
struct TangentPlaneControlPlanes {
  std::array<double, 64> z{};
  std::array<double, 64> bound{};
};

/// \brief Computes the control planes with the serial table of §5 (tangentPlaneTerms()).
/// `bezier` holds 16 points; terms with two equal control points are exactly 0 and skipped.
/// \throws osd_cull::Error if `bezier` does not hold 16 points.
TangentPlaneControlPlanes tangentPlaneControlPlanes(std::span<const glm::dvec3> bezier,
                                                    const glm::dmat4& viewProj);

/// \brief The same with the 16-thread ordering of §6 (tangentPlaneParallelTerms()),
/// simulating the threads one after another; the sums are equal up to summation order.
TangentPlaneControlPlanes tangentPlaneControlPlanesParallel(std::span<const glm::dvec3> bezier,
                                                            const glm::dmat4& viewProj);

/// \brief Result of the tangent-plane test with the paper's counts.
struct TangentPlaneResult {
  bool culled = false;
  BackPatchVerdict verdict = BackPatchVerdict::NonFinite;
  uint32_t pcnt = 0;  ///< control planes that may be positive (σ z + margin·bound > 0)
  uint32_t ncnt = 0;  ///< control planes that may be negative (σ z - margin·bound < 0)
};

/// \brief DVis classification of §4.2 with the Pcnt rule of §7, from computed planes:
/// NonFinite if any value is not finite; NoFiniteEye if eyeSign is 0; BackFacing (culled)
/// if pcnt == 0; FrontFacing if ncnt == 0; Silhouette otherwise. With `drawnMargin` > 0
/// (clip-space units: |e.w| times tangentPlaneDrawnMargin() of drawn_triangles.h) a plane
/// also counts as possibly positive when σ z + margin·bound + drawnMargin > 0, and a patch
/// that only this keeps gets DrawnTriangles.
TangentPlaneResult classifyTangentPlane(const TangentPlaneControlPlanes& planes, double eyeSign,
                                        double drawnMargin = 0.0);

/// \brief The tangent-plane back-patch test of a 16-point bicubic Bézier patch.
/// `eyeSign` is clipSpaceEyeSign(viewProj), computed once per view. NaN or Inf control
/// points or matrix entries: kept (NonFinite).
TangentPlaneResult tangentPlaneTest(std::span<const glm::dvec3> bezier, const glm::dmat4& viewProj,
                                    double eyeSign, double drawnMargin = 0.0);

}  // namespace osd_cull::bound
