#pragma once
/// \file patch_set.h
/// \brief The patches osd_cull culls and draws: bicubic Bézier and Gregory-basis patches.
///
/// Layout (relied on by bound/, vk/, frame/ and the shaders):
/// - patches are numbered 0..patchCount()-1: first all Bézier patches, then all Gregory;
/// - `points` holds 16 points per Bézier patch, then 20 per Gregory patch, in patch order;
/// - Bézier point (i, j), i along u and j along v, is points[firstPoint + 4*j + i]
///   (u fastest, OpenSubdiv's order);
/// - Gregory point order is OpenSubdiv's Gregory basis: 5 points per corner, corners
///   (0,0), (1,0), (1,1), (0,1), each as P, Ep, Em, Fp, Fm (point 5*corner + k).

#include <glm/vec3.hpp>
#include <opensubdiv/far/patchParam.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace osd_cull {

/// \brief How a patch is drawn and bounded: 16-point bicubic Bézier or 20-point Gregory.
enum class PatchType : uint32_t { Bezier = 0, Gregory = 1 };

inline constexpr uint32_t kBezierPoints = 16;
inline constexpr uint32_t kGregoryPoints = 20;

/// \brief Where a patch came from (for reports; culling does not depend on it).
enum class PatchOrigin : uint8_t {
  Regular,   ///< interior regular B-spline patch, converted to Bézier
  Boundary,  ///< regular patch with one boundary edge (points extrapolated), converted
  Corner,    ///< regular patch with two or more boundary edges (a corner, or a strip one
             ///< patch wide), converted
  Gregory,   ///< irregular patch, Gregory-basis end cap
  BSplineEndCap,  ///< irregular patch approximated by a B-spline end cap, converted
  Input,     ///< Bézier patch read directly from a file (e.g. BPT)
};

/// \brief A set of Bézier and Gregory patches with their OpenSubdiv PatchParams.
struct PatchSet {
  std::string source;
  uint32_t bezierCount = 0;
  uint32_t gregoryCount = 0;
  std::vector<glm::dvec3> points;                       ///< see the file comment for layout
  std::vector<OpenSubdiv::Far::PatchParam> params;      ///< one per patch
  std::vector<PatchOrigin> origins;                     ///< one per patch

  uint32_t patchCount() const { return bezierCount + gregoryCount; }
  PatchType type(uint32_t patch) const {
    return patch < bezierCount ? PatchType::Bezier : PatchType::Gregory;
  }
  uint32_t firstPoint(uint32_t patch) const {
    return patch < bezierCount ? patch * kBezierPoints
                               : bezierCount * kBezierPoints + (patch - bezierCount) * kGregoryPoints;
  }
  uint32_t pointCount(uint32_t patch) const {
    return patch < bezierCount ? kBezierPoints : kGregoryPoints;
  }
  std::span<const glm::dvec3> controlPoints(uint32_t patch) const {
    return {points.data() + firstPoint(patch), pointCount(patch)};
  }
};

}  // namespace osd_cull
