#pragma once
/// \file tangent_plane_table.h
/// \brief The index and weight table of the parametric tangent plane (Loop, Nießner,
/// Eisenacher, "Effective Back-Patch Culling for Hardware Tessellation", §3 and §5),
/// derived in code from its definition, never typed in.
///
/// For a bicubic Bézier patch B with homogeneous control points b_0..b_15 (point (i, j) at
/// 4*j + i, u fastest), the tangent plane T(u,v) = cross4(B, Bu, Bv) (eq. 1) is a
/// polynomial of bidegree 7 with Bézier control planes t_0..t_63 (t at 8*row_v + col_u):
///
///   t_target = Σ weight · cross4(b_j, b_k, b_l)   over the terms with that target.
///
/// Derivation (tangent_plane_table.cpp): expand B, Bu, Bv in Bernstein form; cross4 is
/// trilinear and alternating, so each sorted triple j < k < l gets the coefficient
/// polynomial det[φ; φu; φv] of the three basis functions; products of Bernstein bases are
/// multiplied exactly in rational arithmetic (bidegree (8,8)), then reduced to bidegree
/// (7,7), checking that the reduction is exact (the §3 claim "less by one in both
/// parametric directions"). Zero weights are dropped; the paper counts 516 terms.

#include <cstdint>
#include <span>
#include <string>

namespace osd_cull::bound {

inline constexpr uint32_t kTangentPlaneDegree = 7;          ///< bidegree of T(u,v) (§3)
inline constexpr uint32_t kTangentPlaneControlPlanes = 64;  ///< 8x8 control planes
inline constexpr uint32_t kTangentPlaneThreads = 16;        ///< threads per patch (§6)

/// \brief One weighted cross4() product of §5: t[target] += weight * cross4(b_j, b_k, b_l).
struct TangentPlaneTerm {
  uint32_t target = 0;  ///< control plane index, 8 * row_v + col_u
  uint32_t j = 0;       ///< control point indices, j < k < l (4 * row_v + col_u)
  uint32_t k = 0;
  uint32_t l = 0;
  double weight = 0.0;      ///< numerator / denominator, rounded to double
  int64_t numerator = 0;    ///< the exact rational weight
  int64_t denominator = 1;  ///< > 0
};

/// \brief The serial table of §5, sorted by target, then (j, k, l). Derived on first use
/// (thread-safe); throws osd_cull::Error if the derivation finds T is not of bidegree 7.
std::span<const TangentPlaneTerm> tangentPlaneTerms();

/// \brief The same terms reordered for the 16-threads-per-patch scheme of §6: thread
/// (r, c) = (thread / 4, thread % 4) owns the four targets (r, c), (r, c+4), (r+4, c),
/// (r+4, c+4) of the 8x8 array, so no two threads write the same target. Entry
/// slot * 16 + thread belongs to thread `thread`; threads with fewer terms than the busiest
/// one are padded with weight-0 terms on their own first target (indices 0, 1, 2), so the
/// loop `for (k = thread; k < size; k += 16)` needs no bounds check. Size is 16 * slots.
std::span<const TangentPlaneTerm> tangentPlaneParallelTerms();

/// \brief GLSL source declaring the table for a shader, generated from the derived terms:
/// `const uint kTangentPlaneTermCount`, `const uvec4 kTangentPlaneTerms[]` (target, j, k, l)
/// and `const float kTangentPlaneWeights[]` (each an exact quotient of integers, rounded
/// once by the compiler). `parallelOrder` selects tangentPlaneParallelTerms().
std::string tangentPlaneTableGlsl(bool parallelOrder);

}  // namespace osd_cull::bound
