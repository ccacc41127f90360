#pragma once
/// \file tangent_plane_factored_glsl.h
/// \brief GLSL of the factored tangent-plane coefficients (bound::tangentPlaneFactored,
/// docs/algorithms/cull-kernel.md "The factored form"), generated as straight-line code.
///
/// Written with loops over local arrays, lavapipe takes 40-190 s to compile the kernel
/// (NIR's passes over thousands of array accesses); with loops left rolled, the dynamic
/// indexing costs as much as the 516-term table. Generated with one named value per
/// quantity, every index is a constant and there are no local arrays to lower.

#include <string>

namespace osd_cull::frame {

/// \brief Declares `uvec4 tangentPlaneFactoredSigns(vec3 b[16], float inputError, float
/// reference, float drawn, bvec4 collapsed)`: the (may be positive, may be negative, not
/// finite, may be above -drawn) counts over the 64 coefficients, each through
/// `tangentPlaneFactoredCount()` (shaders/cull/tangent_plane_factored.glsl). `collapsed`:
/// the boundaries v = 0, v = 1, u = 0, u = 1 have four equal points.
std::string tangentPlaneFactoredGlsl();

}  // namespace osd_cull::frame
