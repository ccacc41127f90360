#pragma once
/// \file tangent_plane_factored.h
/// \brief The 64 coefficients of the parametric tangent-plane test (Loop, Nießner,
/// Eisenacher §4.2) in world space, computed by a factored form instead of the 516-term
/// table of §5: the double-precision mirror of the GPU kernel (shaders/cull/tangent_plane
/// _common.glsl), derived in docs/algorithms/cull-kernel.md ("The factored form").
///
/// With Q = E - B(u,v) for the eye E, the de Casteljau split B = (1-u) A + u C in u (A: the
/// first three columns of control points, C: the last three) and Bu = 3 (C - A) give
///
///   e·T(u,v) ∝ det(Q, Bu, Bv) = 9 det(E - A, Γ, Δ) = 9 (E - A) · (Γ × Δ)
///
/// with Γ = C - A (the u-differences, bidegree (2,3)) and Δ = Bv / 3 (the v-differences,
/// bidegree (3,2)). N = Γ × Δ is a (5,5) polynomial (144 cross products of differences),
/// (E - A) · N a (7,8) polynomial (432 dot products); its v-degree is exactly 7 (§3), and
/// the reduction to the 8 x 8 coefficients is a chain of subtractions in the scaled
/// Bernstein basis. Every weight is an integer, so the form is exact in exact arithmetic:
///
///   F_i = Σ w (E - b_j) · ((b_k - b_j) × (b_l - b_j))   (the table's world-space form)
///       = 9 d_pq / (C(7,p) C(7,q)),   i = 8 q + p,
///
/// where d_pq are the scaled coefficients this file computes. Signs are all the test needs.

#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull::bound {

/// \brief Scaled world-space coefficients d_pq = C(7,p) C(7,q) F_i / 9 (i = 8 q + p, u
/// fastest, as tangentPlaneControlPlanes()) and for each a bound of the magnitudes of the
/// products it is summed from: Σ w |E - a|_∞ |Γ|_1 |Δ|_1 through the same integer weights
/// and the |·| of the reduction. A bound is 0 exactly when every product in the
/// coefficient has a zero difference, and then so is the coefficient.
///
/// `collapsed` marks the coefficients along a boundary whose four control points are equal
/// (the teapot's poles): the §5 table skips every term of those (each has two equal points),
/// so they are exactly 0 with margin 0 in the reference too and the Pcnt rule (§7) does not
/// count them. A zero bound elsewhere can come from terms that cancel exactly while the
/// reference still gives them a margin; the kernel counts such a coefficient as possibly
/// positive and negative, as the reference does.
struct TangentPlaneFactored {
  std::array<double, 64> d{};
  std::array<double, 64> bound{};
  std::array<bool, 64> collapsed{};
};

/// \brief The factored coefficients of the 16-point Bézier patch `bezier` seen from `eye`.
/// \throws osd_cull::Error if `bezier` does not hold 16 points.
TangentPlaneFactored tangentPlaneFactored(std::span<const glm::dvec3> bezier,
                                          const glm::dvec3& eye);

/// \brief C(7,p) C(7,q) / 9: d_pq of tangentPlaneFactored() is F_i times this scale.
double tangentPlaneFactoredScale(int p, int q);

}  // namespace osd_cull::bound
