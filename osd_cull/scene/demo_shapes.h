#pragma once
/// \file demo_shapes.h
/// \brief Patch sets generated in code: closed Bézier surfaces with and without Gregory
/// patches and transition edges, for tests, the default scene and benchmarks.

#include "osd_cull/patch/patch_set.h"

#include <glm/vec3.hpp>

#include <array>
#include <functional>
#include <span>

namespace osd_cull::scene {

/// \brief A flat Bézier patch: point (i, j) = origin + du * i/3 + dv * j/3, so the surface
/// is exactly the parallelogram origin + [0,1] du + [0,1] dv.
std::array<glm::dvec3, 16> flatBezierPatch(const glm::dvec3& origin, const glm::dvec3& du,
                                           const glm::dvec3& dv);

/// \brief The 20 Gregory-basis points (OpenSubdiv order: per corner P, Ep, Em, Fp, Fm) of
/// the same surface as a Bézier patch: boundary points copied, Fp = Fm = the Bézier
/// interior point, so the Gregory patch evaluates to the Bézier patch.
std::array<glm::dvec3, 20> gregoryFromBezier(std::span<const glm::dvec3, 16> bezier);

/// \brief Builds a PatchSet from Bézier patches (face id = index, depth 0, regular).
PatchSet bezierPatchSet(std::span<const std::array<glm::dvec3, 16>> patches, std::string source);

/// \brief Turns the Bézier patches for which `toGregory(index)` is true into the
/// equivalent Gregory patches (moved after the Bézier ones; params and origins follow).
PatchSet convertToGregory(const PatchSet& set, const std::function<bool(uint32_t)>& toGregory);

/// \brief Appends b's patches to a's (Bézier with Bézier, Gregory with Gregory).
PatchSet concatenate(const PatchSet& a, const PatchSet& b);

/// \brief Moves every point by `offset`.
PatchSet translated(PatchSet set, const glm::dvec3& offset);

/// \brief A closed sphere-like surface: each face of a cube split into k x k Bézier
/// patches whose points are projected onto the sphere. Points of shared edges are
/// computed from the same cube-surface points, so neighbours share them bit for bit.
PatchSet bezierSphere(const glm::dvec3& center, double radius, uint32_t k);

/// \brief Options of bsplineTorus().
struct TorusOptions {
  uint32_t nu = 8;  ///< patches around the main ring
  uint32_t nv = 6;  ///< patches around the tube
  double majorRadius = 1.0;
  double minorRadius = 0.4;
  glm::dvec3 center{0.0};
  /// When >= 0, this patch is replaced by its four half-size children (PatchParam depth 1)
  /// and its four neighbours get the transition bit on the shared edge, as in
  /// OpenSubdiv's adaptive patches.
  int refinePatch = -1;
};

/// \brief A closed torus of uniform bicubic B-spline patches on a periodic control grid,
/// converted to Bézier form (neighbours' shared edge points agree up to rounding, as in
/// patches converted from Far::PatchTable).
PatchSet bsplineTorus(const TorusOptions& options);

}  // namespace osd_cull::scene
