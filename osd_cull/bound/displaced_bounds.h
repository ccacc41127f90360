#pragma once
/// \file displaced_bounds.h
/// \brief Bounds of displaced patches, double-precision CPU references of the GPU kernels
/// (shaders/cull/displaced_bound.glsl): Nießner & Loop §4.2 (Fig. 5) and Sathe's run-time
/// step.
///
/// A displaced patch is S(u,v) = P(u,v) + N(u,v) D(u,v) with N the unit normal and
/// Dmin <= D <= Dmax, Dmin <= 0 <= Dmax (DisplacementMap::displacementOver() of the
/// patch's texture region). P lies in the convex hull of the control points; N lies in a
/// cone of normals (axis a, half-angle α). For a direction r, N·r̂ lies in [-δ-, δ+] with
///   δ+ = 1 if a·r̂ >= cos α, else cos(arccos(a·r̂) - α)     (and δ- the same for -r̂),
/// so (N D)·r lies in [-max(Dmax δ-, -Dmin δ+), max(Dmax δ+, -Dmin δ-)] |r| (§4.2).
///
/// Extensions (how the cone is known):
/// - Full: no cone, δ± = 1: the uniform extension by max |D| (Sathe);
/// - ACoN: the approximate cone from tangent and bitangent cones (Sederberg and Meyers,
///   bound::buildConeFromTangentCones; Gregory patches: buildGregoryConeFromTangentCones);
/// - CoN: the true cone of the normal patch (Shirman and Abi-Ezzi, buildConeOfNormals);
///   Gregory patches, whose normal patch is rational, use their tangent-cone cone.
/// An invalid cone (wide, degenerate or non-finite) falls back to Full.
///
/// Boxes (where the extension is applied):
/// - OOBB: the object-space (world-axis) box of the control points, each side moved out by
///   the extension along that axis (Munkberg et al., as in §6.2);
/// - CAF: the camera-aligned frustum (§4.2): control points to camera space, a box per
///   point extended along the camera axes, the nearest depth of all boxes as the front
///   plane, the boxes' extreme x/depth and y/depth slopes as side planes, the farthest
///   depth as the back plane. Its screen rectangle is what its front face projects to.
///   With a box at or behind the eye plane, or a projection that is not a perspective
///   projection along the camera's -z, the CAF falls back to the camera-space box of all
///   per-point boxes (still valid for the homogeneous frustum test).
/// Both bounds are convex hulls of 8 corners given with the matrix that takes them to clip
/// space, so the frustum test (frustum.h) and Hi-Z occlusion (occlusion.h) run on them
/// unchanged.

#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::bound {

/// \brief How the range of normals is bounded (Table 1 columns).
enum class DisplacedExtension : uint32_t { Full = 0, ACoN = 1, CoN = 2 };
/// \brief Which volume is extended (Table 1 column groups).
enum class DisplacedBox : uint32_t { OOBB = 0, CAF = 1 };

/// \brief "full", "acon", "con".
const char* toString(DisplacedExtension extension);
/// \brief "oobb", "caf".
const char* toString(DisplacedBox box);
/// \brief The kernel's name, e.g. "acon-caf".
std::string displacedKernelName(DisplacedExtension extension, DisplacedBox box);

/// \brief The box of a patch's texture coordinates `corners` (4, bilinear over the patch:
/// the box of the corners is exact).
UvRegion patchUvRegion(std::span<const glm::dvec2> corners);

/// \brief What a displaced bound needs of a patch, built once per static mesh and map.
struct DisplacedPatch {
  DisplacementRange range;
  ConeOfNormals cone;  ///< invalid for Full (never read)
};

/// \brief Dmin/Dmax of every patch over its texture region (uvCorners: 4 per patch, the
/// PatchSet order): static under motion of the cage (the bounds pass of an animated mesh
/// reads them).
/// \throws osd_cull::Error when uvCorners is empty (no UVs) or does not hold 4 per patch.
std::vector<DisplacementRange> displacementRanges(const PatchSet& patches,
                                                  std::span<const glm::dvec2> uvCorners,
                                                  const DisplacementMap& map);

/// \brief Dmin/Dmax of every patch over its texture region (uvCorners: 4 per patch, the
/// PatchSet order) and the cone of `extension`.
/// \throws osd_cull::Error when uvCorners does not hold 4 per patch.
std::vector<DisplacedPatch> buildDisplacedPatches(const PatchSet& patches,
                                                  std::span<const glm::dvec2> uvCorners,
                                                  const DisplacementMap& map,
                                                  DisplacedExtension extension);

/// \brief The cone `extension` uses for one patch (invalid for Full).
ConeOfNormals displacementCone(const PatchSet& patches, uint32_t patch,
                               DisplacedExtension extension);

/// \brief The range of (N D)·r over the patch: D along direction r (any length): the
/// point moves by at most `plus` along r and at most `minus` against it (both >= 0,
/// rounded up).
struct AxisExtension {
  double plus = 0.0;
  double minus = 0.0;
};
AxisExtension axisExtension(const DisplacedPatch& patch, DisplacedExtension extension,
                            const glm::dvec3& direction);

/// \brief A displaced bound: the convex hull of `corners`, mapped to clip space by `toClip`
/// (OOBB: corners in world space, toClip = viewProj; CAF: corners in camera space,
/// toClip = projection).
struct DisplacedBound {
  std::array<glm::dvec3, 8> corners{};
  glm::dmat4 toClip{1.0};
  DisplacedBox box = DisplacedBox::OOBB;
  bool finite = false;   ///< false: NaN/Inf input; the bound is meaningless (keep the patch)
  bool frustum = false;  ///< CAF: the camera-aligned frustum was built (not the fallback)
  /// OOBB: the world box; CAF fallback: the camera-space box.
  glm::dvec3 lo{0.0}, hi{0.0};
  /// CAF: x/depth and y/depth slopes of the side planes, the depth range (depth = -z).
  glm::dvec2 slopeLo{0.0}, slopeHi{0.0};
  double nearDepth = 0.0, farDepth = 0.0;
};

/// \brief The bound of one patch's control points `points` (16 or 20) displaced as
/// `patch` says, with `extension` applied to `box`. `view` maps world to camera space
/// (camera looking down -z), `projection` camera to clip space.
DisplacedBound displacedBound(std::span<const glm::dvec3> points, const DisplacedPatch& patch,
                              DisplacedExtension extension, DisplacedBox box,
                              const glm::dmat4& view, const glm::dmat4& projection);

/// \brief Whether a world-space point lies in the bound, with a relative tolerance (for
/// tests that sample the displaced surface).
bool boundContains(const DisplacedBound& bound, const glm::dvec3& point, const glm::dmat4& view,
                   double tolerance = 1e-9);

/// \brief True when `projection` is a perspective projection along the camera's -z
/// (clip w = -z, x and y depending on x, y and z only): what the CAF needs.
bool isCameraAlignedPerspective(const glm::dmat4& projection);

}  // namespace osd_cull::bound
