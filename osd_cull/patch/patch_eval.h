#pragma once
/// \file patch_eval.h
/// \brief Double-precision evaluation of the patches of a PatchSet (position and first
/// derivatives), the CPU reference for the tessellation shaders.
///
/// (u, v) are the patch's own parameters in [0, 1]^2 (PatchParam::Normalize() maps face
/// coordinates to them); derivatives are with respect to these local parameters. OpenSubdiv's
/// Far::PatchTable::EvaluateBasis takes face coordinates and returns derivatives scaled by
/// 2^depth (PatchParam::GetDepth()), so its derivatives are ours times 2^depth.

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

/// \brief Evaluates a bicubic Bézier patch (16 points, u fastest) with the Bernstein basis.
SurfacePoint evaluateBezier(std::span<const glm::dvec3, kBezierPoints> points, double u, double v);

/// \brief Evaluates a Gregory-basis patch (20 points in OpenSubdiv's order, see patch_set.h).
///
/// The position is exact. The derivatives follow OpenSubdiv's convention
/// (osd/patchBasisCommon.h, Osd_EvalBasisGregory, and Far::PatchTable::EvaluateBasis): they
/// are the derivatives of the Bézier patch whose four interior points are the rational
/// blends of the face points at (u, v) — the approximation of Loop et al. that OpenSubdiv's
/// shaders use, not the derivative of the rational blend itself.
SurfacePoint evaluateGregory(std::span<const glm::dvec3, kGregoryPoints> points, double u,
                             double v);

/// \brief The 16 Bézier points of the Gregory patch frozen at (u, v): the boundary points
/// and, for the interior, the rational blend of each corner's face points Fp and Fm.
std::array<glm::dvec3, kBezierPoints> gregoryToBezierAt(
    std::span<const glm::dvec3, kGregoryPoints> points, double u, double v);

/// \brief Evaluates patch `patch` of a set (Bézier or Gregory by its position in the set).
SurfacePoint evaluatePatch(const PatchSet& set, uint32_t patch, double u, double v);

}  // namespace osd_cull
