#pragma once
/// \file cull_reference.h
/// \brief Double-precision CPU reference of one cull pass (the GPU kernel of
/// shaders/cull/cull_main.glsl): the enabled tests cheapest first, frustum then back-patch,
/// each patch getting the same result code the kernel writes (shaders/shared/cull_layout.h).
///
/// Per patch type:
/// - Bézier: frustumTest on the 16 points; back-patch by the chosen method (TCONE or NCONE
///   cones built once per static mesh, or the tangent-plane test);
/// - Gregory: frustumTest on the 20 points; back-patch by the Gregory TCONE for every
///   method (buildGregoryConeFromTangentCones), since the tangent plane and the normal patch
///   of a Gregory patch are rational (docs/algorithms/back-patch.md).
/// Back-patch culling is only meaningful on meshes where backPatchValidity() allows it; the
/// caller decides (this function tests what it is told to).

#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/drawn_triangle_set.h"
#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace osd_cull::bound {

/// \brief Which back-patch test a pass runs on Bézier patches.
enum class BackPatchMethod : uint32_t {
  None,
  TCone,         ///< buildConeFromTangentCones, precomputed per static mesh
  NCone,         ///< buildConeOfNormals, precomputed per static mesh
  TangentPlane,  ///< tangentPlaneTest, per view
};

/// \brief "none", "tcone", "ncone", "tangent-plane".
const char* toString(BackPatchMethod method);

/// \brief The cones a back-patch method tests, one per patch: Bézier patches get the TCONE
/// or NCONE of `method` (an invalid placeholder for None and TangentPlane, which use none),
/// Gregory patches the Gregory TCONE (for every method but None). Sets of at least
/// kParallelConePatches patches are split over up to `threads` threads (0: the hardware's
/// concurrency); the result does not depend on the split.
std::vector<ConeOfNormals> buildPatchCones(const PatchSet& patches, BackPatchMethod method,
                                           ConeSearch search = ConeSearch::Filtered,
                                           unsigned threads = 0);

/// \brief Smallest patch count buildPatchCones splits over threads.
inline constexpr uint32_t kParallelConePatches = 16384;

/// \brief What the tests need of a view, computed once per view.
struct CullView {
  glm::dmat4 viewProj{1.0};
  std::optional<glm::dvec3> eye;  ///< eyePosition(viewProj)
  double eyeSign = 0.0;           ///< clipSpaceEyeSign(viewProj)
};
CullView makeCullView(const glm::dmat4& viewProj);

/// \brief The tests a pass runs.
struct CullTests {
  bool frustum = true;
  BackPatchMethod backPatch = BackPatchMethod::None;
  /// Back-patch tests conservative for the drawn triangles (drawn_triangles.h): one
  /// TriangleShape per patch for this view's tessellation. Empty: the tests are exact for
  /// the surface only (what the papers measure).
  std::span<const TriangleShape> drawnShapes;
  /// With drawnShapes: bound::snapPerDistance() of the view's draw.
  double snapPerDistance = 0.0;
  /// With drawnShapes: a patch the worst-case bound keeps (BackPatchVerdict::
  /// DrawnTriangles) is still culled when its levels are exact and every triangle
  /// drawn_triangle_set.h lists faces away (the tightened test, CullSettings::
  /// drawnEnumerate).
  bool drawnEnumerate = false;
  /// With drawnShapes: without drawnEnumerate, the listed test still runs on patches with
  /// exact levels whose outer levels are all at most this (kDrawnListLowLevel as the kernel
  /// lists them; 0: never).
  uint32_t drawnListLevel = 0;
};

/// \brief The result code (shaders/shared/cull_layout.h) of one patch. `cones` is
/// buildPatchCones(patches, tests.backPatch) (may be empty when backPatch is None).
/// Without an eye (orthographic or singular projection) back-patch tests keep the patch
/// with BackPatchVerdict::NoFiniteEye.
uint32_t referenceCullCode(const PatchSet& patches, uint32_t patch, const CullView& view,
                           const CullTests& tests, std::span<const ConeOfNormals> cones);

/// \brief referenceCullCode() of every patch.
std::vector<uint32_t> referenceCull(const PatchSet& patches, const CullView& view,
                                    const CullTests& tests, std::span<const ConeOfNormals> cones);

/// \brief Reading a result code.
struct CullCode {
  uint32_t value = 0;
  /// kStage* of shaders/shared/cull_layout.h: 0 kept, 1 frustum, 2 back-patch, 3 occlusion.
  uint32_t stage() const { return value & 0xFu; }
  bool culled() const { return stage() != 0; }
  /// Frustum plane 0..5 (culled), 6 inside, 7 non-finite, 15 not run.
  uint32_t frustum() const { return (value >> 4) & 0xFu; }
  /// BackPatchVerdict value, 0xFF not run.
  uint32_t backPatch() const { return (value >> 8) & 0xFFu; }
  /// Occlusion verdict (0 culled), 0xFF not run.
  uint32_t occlusion() const { return (value >> 16) & 0xFFu; }
};

/// \brief A short description of a code, e.g. "culled: frustum plane 4" or "kept:
/// back-patch silhouette".
std::string describe(CullCode code);

}  // namespace osd_cull::bound
