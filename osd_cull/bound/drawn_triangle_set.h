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

/// \brief How far (per coordinate) a vertex the tessellator makes for `levels` can lie from
/// its exact position k / n: the tessellator works in fixed point (lavapipe: 16 fractional
/// bits) and steps k times by the spacing rounded to 2^-16, so vertex k is off by up to
/// k 2^-17; we allow (L + 1) 2^-17, L the largest outer or inner level (measured on lavapipe:
/// at most 0.46 of it). Transition and outer-edge
/// vertices are re-evaluated from round(t n) / n and exact, inner ones are not.
/// tests/test_drawn_triangles.cpp checks every captured vertex against it.
double tessCoordError(const QuadTessLevels& levels);

/// \brief Whether the triangle p0 p1 p2 (counter-clockwise in the domain) faces away from
/// `eye` even when each corner moves by up to `vertexError`:
///   (E - p0) . ((p1 - p0) x (p2 - p0)) + (|E - p0| + ε) D + ε |a| |b| < 0,
///   D = 2 ε (|a| + |b|) + 4 ε²,  a = p1 - p0, b = p2 - p0.
bool triangleFacesAway(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                       const glm::dvec3& eye, double vertexError);

/// \brief Whether every triangle forEachDrawnTriangle() lists for the 16-point Bézier patch
/// `bezier` faces away from `eye` (triangleFacesAway() with ε = drawnVertexError() plus
/// 2 G tessCoordError(): the drawn vertex is B at the tessellator's rounded coordinates).
/// `snapPerDistance` as for tangentPlaneDrawnMargin().
bool drawnTrianglesFaceAway(std::span<const glm::dvec3> bezier, const QuadTessLevels& levels,
                            const glm::dvec3& eye, double snapPerDistance);

}  // namespace osd_cull::bound
