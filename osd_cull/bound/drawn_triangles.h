#pragma once
/// \file drawn_triangles.h
/// \brief Back-patch culling that is conservative for the triangles the renderer draws,
/// not only for the surface (docs/algorithms/drawn-triangles.md).
///
/// The back-patch tests of Loop, Nießner and Eisenacher (§3-§5, and the cones of §2) are
/// exact for the surface B(u,v). The tessellator draws chord triangles whose corners lie on
/// the surface. Near a silhouette a back-facing patch can own a chord triangle that faces
/// the eye, and that triangle can win pixels. The bound used here:
///
/// For a triangle with parameter-space corners q0, q1 = q0 + d1, q2 = q0 + d2 (counter-
/// clockwise, area A), drawn corners p_i = B(q_i) + e_i with |e_i| <= dv, Taylor's theorem
/// gives p_i - p0 = J d_i + R_i with |J d| <= G |d|_1 and |R_i| <= H |d_i|_1^2 / 2 + 2 dv,
/// where G bounds the first-derivative control vectors (3 Δ b) and H the second-derivative
/// ones (6 Δ² b, 9 Δu Δv b). So the triangle normal is
///   n_t = (p1 - p0) x (p2 - p0) = 2A (N(q0) + Δ),  N = Bu x Bv,
///   |Δ| <= ΔN = G H' Φ / 2 + H'^2 Ψ / 4,   H' = H + 4 dv / m^2,
/// with Φ = κ (|d1|_1 + |d2|_1), Ψ = κ |d1|_1 |d2|_1, κ = |d1|_1 |d2|_1 / 2A (the shape of
/// the triangle, maximized over the tessellation: triangleShape()) and m the shortest
/// parameter-space edge. The triangle faces away from eye E iff (E - p0) . n_t < 0, and
///   (E - p0) . n_t / 2A <= (E - B(q0)) . N(q0) + (R + dv) ΔN + dv |N(q0)|,
/// R = max |E - b_i| over the control points. Hence:
/// - tangent plane: cull only if every coefficient of (E - B) . N is <= -μ,
///   μ = (R + dv) ΔN + dv G^2 (tangentPlaneDrawnMargin());
/// - cones: n_t lies within asin(ΔN / Nmin) of a surface normal (Nmin <= |N| on the
///   patch), so the cone's half-angle grows by that angle and its apex moves back
///   (widenCone()).
/// Gregory patches are not covered by this bound (their rational blends have no such G and
/// H): they are back-patch culled, when the drawn triangles must be respected, only by the
/// listed test (drawn_triangle_set.h), which evaluates their triangles' corners.

#include "osd_cull/bound/cone_of_normals.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>

namespace osd_cull::bound {

/// \brief Tessellation levels of one quad patch as the draw shaders set them (equal
/// spacing): outer edges in gl_TessLevelOuter order, each split into a Lo and a Hi half
/// (Hi = 0 except on transition edges, whose Lo segments cover [0, 1/2] and Hi segments
/// [1/2, 1]); inner levels average opposite outer levels (OsdComputeTessLevels).
struct QuadTessLevels {
  std::array<double, 4> lo{};
  std::array<double, 4> hi{};
};

/// \brief The shape of the worst triangle of one patch's tessellation (see the file
/// comment): phi = max κ (|d1|_1 + |d2|_1), psi = max κ |d1|_1 |d2|_1, minEdge = the
/// shortest parameter-space edge.
struct TriangleShape {
  double phi = 0.0;
  double psi = 0.0;
  double minEdge = 1.0;
  /// The integer levels the tessellator uses, when they are known exactly (uniform
  /// tessellation, slack 0): then drawn_triangle_set.h can list the triangles themselves.
  QuadTessLevels levels{};
  bool exactLevels = false;
};

/// \brief Bounds of every triangle the tessellator draws for `levels`. `slack` > 0 allows
/// each level to be off by that much (levels recomputed in another precision). The ring
/// between an outer edge and the inner grid is assumed stitched so that each triangle's
/// apex lies within one segment (the larger spacing of its two rows) of its base, plus the
/// transition remap of the edge; tests/test_drawn_triangles.cpp checks this against the
/// device's tessellator.
TriangleShape triangleShape(const QuadTessLevels& levels, double slack = 0.0);

/// \brief G, H (file comment) and the largest coordinate magnitude of a 16-point bicubic
/// Bézier patch.
struct DerivativeBounds {
  double g = 0.0;
  double h = 0.0;
  double maxAbs = 0.0;
};
DerivativeBounds bezierDerivativeBounds(std::span<const glm::dvec3> bezier);

/// \brief dv: bound of the displacement of a drawn vertex from the surface: fp32 evaluation
/// in the evaluation shader (below 20 ulps of the largest coordinate) and the clip
/// transform (below 8 ulps of coordinate plus eye magnitudes), 32 ulps of both together,
/// plus the rasterizer's snapping to its sub-pixel grid, which moves a vertex at distance d
/// from the eye by at most d * snapPerDistance (snapPerDistance(): half a sub-pixel step,
/// in world units per unit of distance). `maxDistance` bounds the distance of the patch's
/// points from the eye.
double drawnVertexError(double maxAbs, const glm::dvec3& eye, double maxDistance,
                        double snapPerDistance);

/// \brief World-space displacement per unit of eye distance of half a sub-pixel step
/// (2^-subPixelBits pixels) for a perspective `viewProj` drawn at width x height pixels.
double snapPerDistance(const glm::dmat4& viewProj, double width, double height,
                       uint32_t subPixelBits);

/// \brief ΔN of the file comment.
double normalDeviation(const DerivativeBounds& d, const TriangleShape& shape, double vertexError);

/// \brief μ of the file comment: cull with the tangent plane only if every coefficient of
/// (E - B) . (Bu x Bv) is <= -μ.
double tangentPlaneDrawnMargin(std::span<const glm::dvec3> bezier, const glm::dvec3& eye,
                               const TriangleShape& shape, double snapPerDistance);

/// \brief The cone of a Bézier patch widened so that it holds the normals of the drawn
/// triangles too; invalid (never culls) when the deviation reaches the smallest normal.
ConeOfNormals widenCone(const ConeOfNormals& cone, std::span<const glm::dvec3> bezier,
                        const glm::dvec3& eye, const TriangleShape& shape, double snapPerDistance);

}  // namespace osd_cull::bound
