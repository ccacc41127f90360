#pragma once
/// \file drawn_triangle_set.h
/// \brief The tightened drawn-triangle test: every triangle the tessellator can draw for a
/// patch, tested one by one (docs/algorithms/drawn-triangles.md, "Enumerated triangles").
///
/// drawn_triangles.h bounds the worst chord triangle of a patch from the patch-wide
/// derivative bounds G and H, which near a silhouette keeps about half of what the papers'
/// surface tests cull (Loop, Niessner, Eisenacher §2-§5 are exact for the surface B(u,v),
/// not for its chords). With uniform tessellation the levels are integers known per patch,
/// so the triangles themselves can be listed: the inner grid of the quad domain (spacing
/// 1/i0 x 1/i1; both diagonals of every cell, because Vulkan leaves the diagonal to the
/// implementation) and, per outer edge, the ring between the edge's n vertices and the inner
/// row, where a triangle has its base on one row and its apex on the other within
/// ringApexOffset() of the base (the same stitching fact triangleShape() relies on; tests/
/// test_drawn_triangle_set.cpp checks that every triangle the device draws is listed). A
/// patch is culled only if every listed triangle, with its corners moved by up to the
/// drawn-vertex error dv (drawnVertexError(): fp32 evaluation and sub-pixel snapping), faces
/// away from the eye. Adaptive levels (not integers known to the kernel) are not listed:
/// the worst-case bound stays in force for them.

#include "osd_cull/bound/drawn_triangles.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <functional>
#include <span>

namespace osd_cull::bound {

/// \brief A triangle's corners in the (u, v) domain, counter-clockwise (so its drawn normal
/// (p1 - p0) x (p2 - p0) points the way of N = Bu x Bv).
using DomainTriangle = std::array<glm::dvec2, 3>;

/// \brief How far beyond the nearer end of its base a ring triangle's apex can lie along
/// the edge, in the tessellator's (unremapped) parameter: for an outer edge of `outerLevel`
/// segments and an inner row of spacing 1/`innerLevel`,
///   min(1.1 (|n - i| m + |σ - s|), 0.8 (max(σ, s) + |n - i| m / 2)),  m = min(σ, s),
/// σ = 1/n, s = 1/i (triangleShape() explains the measurement behind it).
double ringApexOffset(double outerLevel, double innerLevel);

/// \brief Calls `fn(triangle, ring)` for every triangle the tessellator may draw for the
/// integer `levels` (QuadTessLevels: lo + hi segments per edge, transition edges remapped
/// as the draw shaders do), and more: both diagonals of each inner cell and every apex
/// the ring offset allows. `ring` is false for inner-grid cells.
/// \throws osd_cull::Error if a level is not an integer in [0, 64] or an edge has none.
void forEachDrawnTriangle(const QuadTessLevels& levels,
                          const std::function<void(const DomainTriangle&, bool ring)>& fn);

/// \brief How far from k / n the tessellator places point k of `level` = n segments, per
/// coordinate. Lavapipe tessellates with Mesa's port of the Direct3D 11 reference tessellator
/// (gallium/auxiliary/tessellator, CHWTessellator::PlacePointIn1D): with integer levels it
/// places point k at k r_n in 16.16 fixed point, r_n = round(2^16 / n) 2^-16 (its table
/// s_fixedReciprocal), counting k from the nearer end of the edge (points past the middle are
/// mirrored, 1 - (n - k) r_n, and the middle of an even level is exactly 1/2). So the error
/// is at most floor(n / 2) |r_n - 1/n| <= floor(n / 2) 2^-17, and 0 when n is a power of
/// two (tess 4, 8, 16 and their transition halves). tests/test_drawn_triangles.cpp checks
/// every vertex the device makes against it.
double tessellatorPointError(double level);

/// \brief How far (per coordinate) a vertex the draw shaders evaluate for `levels` can lie
/// from its exact position: tessellatorPointError() of the inner levels (inner vertices are
/// evaluated at the tessellator's coordinates), plus 2^-21 for the draw shader's fp32
/// parameter arithmetic (outer-edge and transition vertices are re-evaluated from
/// round(t n) / n: one division, 2.5 ulps of a value <= 1 by the Vulkan spec).
double tessCoordError(const QuadTessLevels& levels);

/// \brief Whether the triangle p0 p1 p2 (counter-clockwise in the domain) faces away from
/// `eye` even when each corner moves by up to `vertexError`:
///   (E - p0) . ((p1 - p0) x (p2 - p0)) + (|E - p0| + ε) D + ε |a| |b| < 0,
///   D = 2 ε (|a| + |b|) + 4 ε²,  a = p1 - p0, b = p2 - p0.
bool triangleFacesAway(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                       const glm::dvec3& eye, double vertexError);

/// \brief G of a 20-point Gregory patch: a bound of |∂S/∂u| and |∂S/∂v| over the domain for
/// the rational surface S(u, v) = Σ B_ij(u, v) q_ij(u, v) itself (not OpenSubdiv's pseudo-
/// derivatives), as the tessellator's coordinate error needs. Each interior q_ij is a convex
/// blend of its corner's Fp and Fm, so the hodograph term Σ ∂B_ij q_ij is bounded by 3 times
/// the largest difference of neighbouring net points over both choices at each interior
/// position; the rational term B_ij ∂q_ij/∂u is, for corner 0 (q = (s Fp + t Fm)/(s + t)),
/// 9 s (1-s)² t (1-t)² t / (s + t)² |Fp - Fm| <= 9 s (1-s)² |Fp - Fm| <= 4/3 |Fp - Fm|, and
/// alike for the other corners and for v; the bound adds all four.
/// \throws osd_cull::Error if `gregory` does not hold 20 points.
double gregoryDerivativeBound(std::span<const glm::dvec3> gregory);

/// \brief Extra fp32 error of the draw shader's Gregory evaluation over its Bézier one, in
/// units of 2^-24 of the largest coordinate: Osd_EvalBasisGregory's interior multiplier
/// g = s / (s + t) (and its three mirrors) is a quotient of non-negative values, so however
/// close its corner (where s + t -> 0; at the corner itself the guard makes the weight
/// B_11 g = 0, exact) it carries at most 8 units of relative error (the sum, 1 - s, 2.5 ulps
/// of the division the Vulkan spec allows, the product) and 1 - g one more: each interior
/// Bézier point is off by 17 units of the coordinates, weighted by B_ij (the four interior
/// weights sum to at most 9/16), plus four more terms in the 20-term sum: below 14, and 16
/// are allowed.
inline constexpr double kGregoryEvalUlps = 16.0;

/// \brief Whether every triangle forEachDrawnTriangle() lists for the patch `points` (a
/// 16-point Bézier or a 20-point Gregory patch, evaluated as the draw shaders do) faces away
/// from `eye` (triangleFacesAway() with ε = drawnVertexError() (plus kGregoryEvalUlps for
/// Gregory) plus 2 G tessCoordError(): the drawn vertex is S at the tessellator's rounded
/// coordinates; G from bezierDerivativeBounds() or gregoryDerivativeBound()).
/// `snapPerDistance` as for tangentPlaneDrawnMargin().
/// \throws osd_cull::Error if `points` holds neither 16 nor 20 points.
/// \brief The largest outer level at which the back-patch test lists the drawn triangles
/// even without CullSettings::drawnEnumerate (CullTests::drawnListLevel): at most 8 ring and
/// 16 grid triangles, where the worst-case bound of drawn_triangles.h is loosest (one
/// triangle spans a quarter of the patch) and the listing costs little
/// (docs/algorithms/drawn-triangles.md, "Listing at low levels").
inline constexpr uint32_t kDrawnListLowLevel = 2;

bool drawnTrianglesFaceAway(std::span<const glm::dvec3> points, const QuadTessLevels& levels,
                            const glm::dvec3& eye, double snapPerDistance);

}  // namespace osd_cull::bound
