#pragma once
/// \file cull_pass_displaced.h
/// \brief What a CullPass uploads for the displaced bounds (shaders/cull/displaced_bound.glsl):
/// the per-patch data in the cones buffer and the per-view matrices.

#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/bound/occlusion.h"
#include "osd_cull/frame/camera.h"

#include <osd_cull/shared/cull_layout.h>

#include <span>
#include <vector>

namespace osd_cull::frame {

/// \brief Why back-patch culling is off for displaced meshes (CullPass::backPatchNote()).
inline constexpr const char* kDisplacedBackPatchNote =
    "the mesh is displaced: its normals are not the patch's normals, and no back-patch test "
    "that is conservative for displaced surfaces is derived here";

/// \brief shared/cull_layout.h kConeVec4s vec4 per patch: (Dmin rounded down, Dmax rounded
/// up, cos α, sin α), (cone axis, 1 with a valid cone, else 0), zeros.
std::vector<float> packDisplacedPatches(std::span<const bound::DisplacedPatch> patches);

/// \brief The inverse of packDisplacedPatches widened to double (the bounds pass's
/// displaced output): range, cone axis, sin α, α = atan2(sin α, cos α), valid.
/// \throws osd_cull::Error when `data` holds fewer than kConeVec4s vec4 per patch.
std::vector<bound::DisplacedPatch> unpackDisplacedPatches(std::span<const float> data,
                                                          uint32_t patchCount);

/// \brief (Dmin rounded down, Dmax rounded up) as floats, two per patch (the bounds pass's
/// input; the same rounding as packDisplacedPatches).
std::vector<float> packDisplacementRanges(std::span<const bound::DisplacementRange> ranges);

/// \brief The view's matrices for the camera-aligned frustum.
shader::DisplacedView displacedView(const Camera& camera);

class CullPass;

/// \brief The double-precision reference of a displaced pass (CullPass::displaced()): per
/// patch the displaced bound (bound::displacedBound), then the frustum test of its corners
/// (when the pass runs it) and, with `hiz`, the Hi-Z test of its corners
/// (bound::hizOcclusionTest). Result codes as bound::referenceCull (stage and frustum plane).
std::vector<uint32_t> displacedReferenceCull(const PatchSet& host, const CullPass& pass,
                                             const Camera& camera, const bound::HiZPyramid* hiz,
                                             bound::HiZLookup lookup);

/// \brief The same with the per-patch data given (one per patch, e.g. built from this
/// frame's points by bound::buildDisplacedPatches for a pass that reads the bounds pass's
/// displaced output, whose displacedPatches() is empty).
std::vector<uint32_t> displacedReferenceCull(const PatchSet& host, const CullPass& pass,
                                             std::span<const bound::DisplacedPatch> data,
                                             const Camera& camera, const bound::HiZPyramid* hiz,
                                             bound::HiZLookup lookup);

}  // namespace osd_cull::frame
