#pragma once
/// \file cone_of_normals.h
/// \brief Cone-of-normals back-patch tests, double-precision CPU references of the GPU
/// kernels (Loop, Nießner, Eisenacher, §2 "Previous Work"):
/// - NCONE (Shirman and Abi-Ezzi): a cone bounding the Bézier coefficients of the normal
///   patch N = Bu x Bv, built once per static patch (buildConeOfNormals) and tested per
///   view (testConeOfNormals);
/// - TCONE (Sederberg and Meyers; Munkberg et al.): a normal cone combined from the cones
///   of the tangent (Bu) and bitangent (Bv) control vectors, cheap enough to build per frame
///   (buildConeFromTangentCones);
/// - the same TCONE construction for Gregory patches, whose tangent vectors include the
///   derivatives of the rational interior blends (buildGregoryConeFromTangentCones).
///
/// A cone is (apex l, unit axis a, half-angle γ < 90°) such that every normal of the patch
/// lies within γ of a, and every point of the patch lies in the cone with apex l, axis a and
/// half-angle 90° - γ. Then the patch is back-facing from every eye E with
///   dot(a, E - l) <= -sin(γ) |E - l|                      (the cull region)
/// because E - B = (E - l) + (l - B) is a sum of two vectors at most 90° - γ from -a, and
/// every normal is at least 90° from such a vector (docs/algorithms/back-patch.md).

#include "osd_cull/bound/back_patch.h"

#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace osd_cull::bound {

/// \brief Angle (radians) added to every cone half-angle: covers the rounding of the
/// direction and angle computations (below 1e-13 rad) with a wide margin.
inline constexpr double kConeAngleMargin = 1e-9;

/// \brief How a cone's axis search finds the widest direction from a candidate axis
/// (cone_of_normals.cpp, widestFiltered): both give bit-identical cones.
enum class ConeSearch {
  /// atan2 (and asin of a direction's uncertainty) only for the directions whose
  /// pseudo-angle is within 1e-9 of the largest: TCONE, Gregory TCONE and NCONE.
  Filtered,
  Exhaustive,  ///< atan2 of every direction (the definition; kept for tests and benchmarks)
};

/// \brief A bounding cone of a patch's normals with its apex (see the file comment).
struct ConeOfNormals {
  glm::dvec3 apex{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};  ///< unit
  double sinAngle = 1.0;           ///< sine of the half-angle γ, rounded up, < 1 if valid
  double angle = 0.0;              ///< γ (radians)
  /// Largest distance of a control point from the axis line through the points' centre
  /// (moves the apex when γ grows: drawn_triangles.h widenCone()).
  double maxRadius = 0.0;
  /// A lower bound of |Bu x Bv| over the patch (0 when none is known, e.g. Gregory
  /// patches or collapsed edges).
  double minNormal = 0.0;
  bool valid = false;                                     ///< false: never cull (reason says why)
  BackPatchVerdict reason = BackPatchVerdict::NonFinite;  ///< NonFinite, NoNormal or WideCone
};

/// \brief The 36 Bézier coefficients of the normal patch N = Bu x Bv of a bicubic patch,
/// bidegree (5,5), coefficient (p, q) at 6*q + p, computed exactly from products of the
/// degree (2,3) and (3,2) derivative patches: B^2_i B^3_k = C(2,i) C(3,k) / C(5,i+k) B^5_{i+k}.
/// \throws osd_cull::Error if `bezier` does not hold 16 points.
std::array<glm::dvec3, 36> normalPatch(std::span<const glm::dvec3> bezier);

/// \brief NCONE: the cone of normals of a bicubic Bézier patch (Shirman and Abi-Ezzi),
/// bounding the normal-patch coefficients; precompute it for static meshes.
ConeOfNormals buildConeOfNormals(std::span<const glm::dvec3> bezier,
                                 ConeSearch search = ConeSearch::Filtered);

/// \brief TCONE: a cone of normals from the tangent cone (12 control vectors of Bu) and
/// bitangent cone (12 of Bv) of a bicubic Bézier patch, combined as Sederberg and Meyers:
/// axis a_u x a_v, sin γ = sqrt(sin²α + 2 sinα sinβ |cos θ| + sin²β) / sin θ.
ConeOfNormals buildConeFromTangentCones(std::span<const glm::dvec3> bezier,
                                        ConeSearch search = ConeSearch::Filtered);

/// \brief TCONE for a 20-point Gregory-basis patch. Its tangent Gu at every (u,v) is a
/// non-negative combination of the differences of the Bézier-net candidates (boundary
/// points, and both Fp and Fm on interior positions) and of the signed Fp - Fm
/// differences from the derivatives of the rational blends, so the tangent cones bound it.
ConeOfNormals buildGregoryConeFromTangentCones(std::span<const glm::dvec3> gregory,
                                               ConeSearch search = ConeSearch::Filtered);

/// \brief Tests a cone against the eye: culled (BackFacing) iff the eye is in the cull
/// region, with a margin of kRelativeMargin (|E| + |l|) toward "visible". Invalid cone:
/// kept with its reason. Non-finite eye: kept (NonFinite).
BackPatchResult testConeOfNormals(const ConeOfNormals& cone, const glm::dvec3& eye);

}  // namespace osd_cull::bound
