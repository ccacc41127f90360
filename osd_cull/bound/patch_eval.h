#pragma once
/// \file patch_eval.h
/// \brief Double-precision evaluation of bicubic Bézier and Gregory-basis patches with
/// first derivatives: the ground truth the cull tests are checked against (dense sampling).
///
/// The names of bound/ over osd_cull/patch/patch_eval.h, which implements them: points come
/// as dynamic spans (checked), and Gregory derivatives are the exact derivatives of the
/// rational surface (evaluateGregoryExact), as front-facing checks need.

#include "osd_cull/patch/patch_eval.h"

#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull::bound {

/// \brief A surface point with its partial derivatives.
using PatchSample = SurfacePoint;

using osd_cull::bernstein;
using osd_cull::GregoryInterior;
using osd_cull::kGregoryBoundary;
using osd_cull::kGregoryInterior;

/// \brief Evaluates a 16-point bicubic Bézier patch (point (i, j) at 4*j + i) at (u, v)
/// (osd_cull::evaluateBezier).
/// \throws osd_cull::Error if `bezier` does not hold 16 points.
PatchSample evaluateBezier(std::span<const glm::dvec3> bezier, double u, double v);

/// \brief The Bézier net of a 20-point Gregory patch at (u, v): boundary points copied,
/// interior points blended with the rational multipliers (osd_cull::gregoryToBezierAt).
/// \throws osd_cull::Error if `gregory` does not hold 20 points.
std::array<glm::dvec3, 16> gregoryBezierNet(std::span<const glm::dvec3> gregory, double u,
                                            double v);

/// \brief Evaluates a 20-point Gregory-basis patch at (u, v): the position OpenSubdiv
/// evaluates, and the true partial derivatives (osd_cull::evaluateGregoryExact).
/// \throws osd_cull::Error if `gregory` does not hold 20 points.
PatchSample evaluateGregory(std::span<const glm::dvec3> gregory, double u, double v);

}  // namespace osd_cull::bound
