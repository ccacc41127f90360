#pragma once
/// \file patch_eval.h
/// \brief Double-precision evaluation of bicubic Bézier and Gregory-basis patches with
/// first derivatives: the ground truth the cull tests are checked against (dense sampling).

#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull::bound {

/// \brief A surface point with its partial derivatives.
struct PatchSample {
  glm::dvec3 position{0.0};
  glm::dvec3 du{0.0};
  glm::dvec3 dv{0.0};
};

/// \brief The Bernstein polynomial B^degree_i(t) = C(degree, i) (1-t)^(degree-i) t^i.
double bernstein(int degree, int i, double t);

/// \brief Evaluates a 16-point bicubic Bézier patch (point (i, j) at 4*j + i) at (u, v).
/// \throws osd_cull::Error if `bezier` does not hold 16 points.
PatchSample evaluateBezier(std::span<const glm::dvec3> bezier, double u, double v);

/// \brief One interior point of a Gregory patch: the 4x4 Bézier position (i, j) it lands
/// on and its two Gregory-basis points A and B, blended as (a A + b B) / (a + b) with
/// a(s,t) = a0 + as s + at t and b(s,t) = b0 + bs s + bt t (OpenSubdiv's rational
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
/// indexed 4*j + i; -1 on the four interior positions.
inline constexpr std::array<int, 16> kGregoryBoundary{0,  1,  7,  5,  2,  -1, -1, 6,
                                                      16, -1, -1, 12, 15, 17, 11, 10};

/// \brief The Bézier net of a 20-point Gregory patch at (u, v): boundary points copied,
/// interior points blended with the rational multipliers (corners use 1/2 each, where the
/// multiplier is undefined and its basis function is zero).
std::array<glm::dvec3, 16> gregoryBezierNet(std::span<const glm::dvec3> gregory, double u,
                                            double v);

/// \brief Evaluates a 20-point Gregory-basis patch at (u, v): the position OpenSubdiv
/// evaluates, and the true partial derivatives (including the derivatives of the rational
/// multipliers, which OpenSubdiv's pseudo-derivatives omit).
/// \throws osd_cull::Error if `gregory` does not hold 20 points.
PatchSample evaluateGregory(std::span<const glm::dvec3> gregory, double u, double v);

}  // namespace osd_cull::bound
