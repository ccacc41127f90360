#pragma once
/// \file patch_eval.h
/// \brief Double-precision evaluation of the patches of a PatchSet (position and first
/// derivatives): the CPU reference for the tessellation shaders and, through bound/patch_eval.h,
/// the ground truth of the cull tests.
///
/// (u, v) are the patch's own parameters in [0, 1]^2 (PatchParam::Normalize() maps face
/// coordinates to them); derivatives are with respect to these local parameters. OpenSubdiv's
/// Far::PatchTable::EvaluateBasis takes face coordinates and returns derivatives scaled by
/// 2^depth (PatchParam::GetDepth()), so its derivatives are ours times 2^depth.
///
/// Gregory patches have two derivative conventions here:
/// - evaluateGregory(): OpenSubdiv's (what Far::PatchTable::EvaluateBasis and its shaders
///   return), the derivatives of the Bézier net frozen at (u, v);
/// - evaluateGregoryExact(): the true derivatives of the rational Gregory surface, which
///   front-facing (back-patch) decisions need.
/// Both give the same position.

#include "osd_cull/patch/patch_set.h"

#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull {

/// \brief A point on a patch with its first partial derivatives.
struct SurfacePoint {
  glm::dvec3 position{0.0};
  glm::dvec3 du{0.0};  ///< dP/du
  glm::dvec3 dv{0.0};  ///< dP/dv
};

/// \brief The Bernstein polynomial B^degree_i(t) = C(degree, i) (1-t)^(degree-i) t^i.
double bernstein(int degree, int i, double t);

/// \brief One interior point of a Gregory patch: the 4x4 Bézier position (i, j) it lands
/// on and its two Gregory-basis points A (Fp) and B (Fm), blended as (a A + b B) / (a + b)
/// with a(s,t) = a0 + as s + at t and b(s,t) = b0 + bs s + bt t (OpenSubdiv's rational
/// multipliers, Far::internal::EvalBasisGregory).
struct GregoryInterior {
  int i, j;
  int a, b;
  double a0, as, at;
  double b0, bs, bt;
};

/// \brief The four interior blends of OpenSubdiv's 20-point Gregory basis (points
/// 5*corner + {P, Ep, Em, Fp, Fm}, corners (0,0), (1,0), (1,1), (0,1)).
inline constexpr std::array<GregoryInterior, 4> kGregoryInterior{{
    {1, 1, 3, 4, 0, 1, 0, 0, 0, 1},      // Fp0 s/(s+t),        Fm0 t/(s+t)
    {2, 1, 8, 9, 0, 0, 1, 1, -1, 0},     // Fp1 t/(1-s+t),      Fm1 (1-s)/(1-s+t)
    {2, 2, 13, 14, 1, -1, 0, 1, 0, -1},  // Fp2 (1-s)/(2-s-t),  Fm2 (1-t)/(2-s-t)
    {1, 2, 18, 19, 1, 0, -1, 0, 1, 0},   // Fp3 (1-t)/(s+1-t),  Fm3 s/(s+1-t)
}};

/// \brief The Gregory point on each of the 12 boundary positions of the 4x4 Bézier net,
/// indexed 4*j + i; -1 on the four interior positions (Osd_EvalBasisGregory: boundaryGregory).
inline constexpr std::array<int, 16> kGregoryBoundary{0,  1,  7,  5,  2,  -1, -1, 6,
                                                      16, -1, -1, 12, 15, 17, 11, 10};

/// \brief Evaluates a bicubic Bézier patch (16 points, u fastest) with the Bernstein basis.
/// Derivatives come from differences of control points (the hodographs): translation
/// invariant, and exactly zero along a collapsed edge, where the points are equal.
SurfacePoint evaluateBezier(std::span<const glm::dvec3, kBezierPoints> points, double u, double v);

/// \brief The 16 Bézier points of the Gregory patch frozen at (u, v): the boundary points
/// and, for the interior, the rational blend of each corner's face points Fp and Fm. Where
/// the blend is undefined (at its own corner, where its basis function is zero) Fm is used,
/// as OpenSubdiv's guard does.
std::array<glm::dvec3, kBezierPoints> gregoryToBezierAt(
    std::span<const glm::dvec3, kGregoryPoints> points, double u, double v);

/// \brief Evaluates a Gregory-basis patch (20 points in OpenSubdiv's order, see patch_set.h)
/// with OpenSubdiv's derivative convention.
///
/// The position is exact. The derivatives follow OpenSubdiv (osd/patchBasisCommon.h,
/// Osd_EvalBasisGregory, and Far::PatchTable::EvaluateBasis): they are the derivatives of
/// the Bézier patch gregoryToBezierAt(points, u, v) — the approximation of Loop et al. that
/// OpenSubdiv's shaders use, not the derivative of the rational blend itself.
SurfacePoint evaluateGregory(std::span<const glm::dvec3, kGregoryPoints> points, double u,
                             double v);

/// \brief Evaluates a Gregory-basis patch with the exact partial derivatives of the rational
/// surface: evaluateGregory() plus the derivatives of the rational multipliers, which
/// OpenSubdiv's pseudo-derivatives omit. Same position as evaluateGregory().
SurfacePoint evaluateGregoryExact(std::span<const glm::dvec3, kGregoryPoints> points, double u,
                                  double v);

/// \brief Evaluates patch `patch` of a set (Bézier or Gregory by its position in the set),
/// Gregory derivatives in OpenSubdiv's convention.
SurfacePoint evaluatePatch(const PatchSet& set, uint32_t patch, double u, double v);

}  // namespace osd_cull
