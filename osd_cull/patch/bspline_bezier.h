#pragma once
/// \file bspline_bezier.h
/// \brief Regular bicubic B-spline patch (OpenSubdiv REGULAR) → bicubic Bézier patch.
///
/// OpenSubdiv stores a regular patch as 16 B-spline control points, row by row (u fastest).
/// On a boundary it stores duplicates in place of the points beyond the boundary edges and
/// marks those edges in PatchParam::GetBoundary(): bit 0 the edge v = 0 (row 0), bit 1 the
/// edge u = 1 (column 3), bit 2 the edge v = 1 (row 3), bit 3 the edge u = 0 (column 0).
/// The missing points are extrapolated exactly as OpenSubdiv's GPU code does
/// (OsdComputeBSplineBoundaryPoints in osd/glslPatchCommon.glsl: edge points first, then
/// the corner points), which is equivalent to the boundary-adjusted basis of
/// Far::PatchTable::EvaluateBasis. The extrapolated B-spline patch is then converted to
/// Bézier form with the usual per-direction matrix Q (OsdComputePerPatchVertexBSpline).

#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull {

/// \brief Linear map from 16 B-spline points to 16 Bézier points: Bézier point r (u fastest)
/// = sum over k of weights[r][k] * B-spline point k.
using PatchConversion = std::array<std::array<double, 16>, 16>;

/// \brief Replaces the points beyond the boundary edges named by `boundaryMask` (low four
/// bits of PatchParam::GetBoundary()) with OpenSubdiv's linear extrapolation. Bits above
/// the fourth (used by triangle patches) are ignored.
void extrapolateBoundaryPoints(std::span<glm::dvec3, 16> points, unsigned boundaryMask);

/// \brief The combined extrapolation + B-spline → Bézier map for a boundary mask. Each row
/// sums to one (the map is affine invariant). Returned by reference to a table built once.
const PatchConversion& bsplineToBezierWeights(unsigned boundaryMask);

/// \brief Converts one regular B-spline patch (16 points as OpenSubdiv stores them, with
/// duplicates at boundaries) to its 16 Bézier points.
std::array<glm::dvec3, 16> bsplineToBezier(std::span<const glm::dvec3, 16> points,
                                           unsigned boundaryMask);

}  // namespace osd_cull
