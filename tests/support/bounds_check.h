#pragma once
/// \file bounds_check.h
/// \brief Checks that the bounds pass's output bounds the double reference of every patch
/// (frame/cull/bounds_pass.h): the test oracle of the GPU bounds.

#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/patch/patch_set.h"

#include <span>
#include <string>
#include <vector>

namespace osd_cull::test {

/// \brief What checkBounds() found.
struct BoundsCheck {
  uint32_t patches = 0;
  uint32_t violations = 0;                   ///< a bound that does not hold (must be 0)
  std::vector<std::string> firstViolations;  ///< at most 8, for messages
  uint32_t bothValid = 0;          ///< patches whose GPU and reference cones are both valid
  uint32_t lost = 0;               ///< reference valid, GPU invalid (looser, allowed)
  uint32_t containsReference = 0;  ///< of bothValid: γ_gpu >= γ_ref + angle(axes)
  double maxAngleExcess = 0.0;     ///< largest γ_gpu - γ_ref (radians)
  double minAngleExcess = 0.0;     ///< smallest (negative: GPU half-angle below the reference's)
};

/// \brief For every patch of `set` (exact points in double) and its bounds `gpu` of `method`:
/// - a valid cone holds every normal Bu x Bv sampled on a 17 x 17 grid, (NCONE) every
///   normal-patch coefficient, and every control point in its apex cone (within 90° - γ of
///   the axis seen from the apex); its angle and sine agree (γ >= asin(sin γ));
/// - min |N| <= |N| at every sample (and <= n_k . a for NCONE); max radius >= the points'
///   largest distance from the axis line through their centre;
/// - Bézier G, H and max |coordinate| >= bound::bezierDerivativeBounds;
/// - a valid GPU cone where the reference's points are not finite is a violation.
BoundsCheck checkBounds(const PatchSet& set, bound::BackPatchMethod method,
                        std::span<const frame::PatchBounds> gpu);

/// \brief The same for the bounds pass's displaced output (BoundsPass::readDisplaced) of
/// `extension` against `ranges` (bound::displacementRanges) and the double reference
/// (bound::displacementCone of the exact points): Dmin/Dmax rounded outward by at most one
/// float step; Full without a cone; a valid cone holds every sampled normal and (CoN,
/// Bézier) every normal-patch coefficient, and its cos α and sin α agree.
BoundsCheck checkDisplacedBounds(const PatchSet& set, bound::DisplacedExtension extension,
                                 std::span<const bound::DisplacementRange> ranges,
                                 std::span<const bound::DisplacedPatch> gpu);

}  // namespace osd_cull::test
