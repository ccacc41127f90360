#pragma once
/// \file back_patch.h
/// \brief Results shared by the back-patch tests (TCONE, NCONE, tangent plane).
///
/// Orientation convention (all of bound/): the normal of a patch is N = Bu x Bv (Bézier
/// point (i, j) at 4*j + i, u along i). A surface point B(u,v) is front-facing from eye E
/// when dot(N(u,v), E - B(u,v)) > 0. A patch is back-facing when it has no front-facing
/// point; only such patches are culled. For OpenSubdiv patches of a cage whose faces are
/// ordered counter-clockwise seen from outside (positive signed volume), N points outward
/// (tests/test_bound_validity.cpp checks this against Far::PatchTable).

#include <cstdint>

namespace osd_cull::bound {

/// \brief Why a back-patch test culled or kept a patch. The numeric values are part of the
/// GPU interface (the cull kernel writes them per patch).
enum class BackPatchVerdict : uint32_t {
  BackFacing = 0,            ///< culled: no point of the patch faces the eye
  FrontFacing = 1,           ///< kept (tangent plane): every control plane faces the eye
  Silhouette = 2,            ///< kept (tangent plane): control planes of both signs
  EyeOutsideBackRegion = 3,  ///< kept (cones): the eye is not in the cone's cull region
  NonFinite = 4,             ///< kept: NaN or Inf in the control points, matrix, eye or results
  NoNormal = 5,              ///< kept (cones): no tangent/normal direction survives rounding
  WideCone = 6,              ///< kept (cones): the normals do not fit in a cone narrower than 90°
  NoFiniteEye = 7,           ///< kept (tangent plane): the projection has no finite eye
  DrawnTriangles = 8,        ///< kept: the surface faces away, but a drawn triangle may not
                             ///< (drawn_triangles.h)
};

/// \brief Result of a back-patch test.
struct BackPatchResult {
  bool culled = false;
  BackPatchVerdict verdict = BackPatchVerdict::NonFinite;
};

/// \brief A short name for reports ("back-facing", "silhouette", ...).
const char* toString(BackPatchVerdict verdict);

}  // namespace osd_cull::bound
