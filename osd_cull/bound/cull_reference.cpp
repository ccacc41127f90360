#include "osd_cull/bound/cull_reference.h"

#include "osd_cull/bound/back_patch.h"
#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/frustum.h"
#include "osd_cull/bound/tangent_plane.h"
#include "osd_cull/error.h"
#include "osd_cull/parallel.h"

#include <osd_cull/shared/cull_layout.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace osd_cull::bound {

namespace sh = osd_cull::shader;

// The kernel writes BackPatchVerdict values and frustum planes into the result code.
static_assert(sh::kVerdictBackFacing == uint32_t(BackPatchVerdict::BackFacing));
static_assert(sh::kVerdictFrontFacing == uint32_t(BackPatchVerdict::FrontFacing));
static_assert(sh::kVerdictSilhouette == uint32_t(BackPatchVerdict::Silhouette));
static_assert(sh::kVerdictEyeOutsideBackRegion == uint32_t(BackPatchVerdict::EyeOutsideBackRegion));
static_assert(sh::kVerdictNonFinite == uint32_t(BackPatchVerdict::NonFinite));
static_assert(sh::kVerdictNoNormal == uint32_t(BackPatchVerdict::NoNormal));
static_assert(sh::kVerdictWideCone == uint32_t(BackPatchVerdict::WideCone));
static_assert(sh::kVerdictNoFiniteEye == uint32_t(BackPatchVerdict::NoFiniteEye));
static_assert(sh::kVerdictDrawnTriangles == uint32_t(BackPatchVerdict::DrawnTriangles));
static_assert(sh::kFrustumInside == kNoPlane);
static_assert(uint32_t(FrustumPlane::Far) + 1 == kFrustumPlaneCount);

const char* toString(BackPatchMethod method) {
  switch (method) {
    case BackPatchMethod::None:
      return "none";
    case BackPatchMethod::TCone:
      return "tcone";
    case BackPatchMethod::NCone:
      return "ncone";
    case BackPatchMethod::TangentPlane:
      return "tangent-plane";
  }
  return "?";
}

std::vector<ConeOfNormals> buildPatchCones(const PatchSet& patches, BackPatchMethod method,
                                           ConeSearch search, unsigned threads) {
  std::vector<ConeOfNormals> cones = hugePageVector<ConeOfNormals>(patches.patchCount());
  if (method == BackPatchMethod::None) return cones;
  auto build = [&](uint32_t begin, uint32_t end) {
    for (uint32_t p = begin; p < end; ++p) {
      const auto points = patches.controlPoints(p);
      if (patches.type(p) == PatchType::Gregory)
        cones[p] = buildGregoryConeFromTangentCones(points, search);
      else if (method == BackPatchMethod::TCone)
        cones[p] = buildConeFromTangentCones(points, search);
      else if (method == BackPatchMethod::NCone)
        cones[p] = buildConeOfNormals(points, search);
    }
  };
  // Each patch's cone depends on its own points only.
  parallelChunks(patches.patchCount(), kParallelConePatches, threads, build);
  return cones;
}

CullView makeCullView(const glm::dmat4& viewProj) {
  return {viewProj, eyePosition(viewProj), clipSpaceEyeSign(viewProj)};
}

namespace {

uint32_t boundVerdict(const PatchSet& patches, uint32_t patch, const CullView& view,
                      BackPatchMethod method, std::span<const ConeOfNormals> cones,
                      std::span<const TriangleShape> drawnShapes, double snap) {
  const bool bezier = patches.type(patch) == PatchType::Bezier;
  const bool drawn = !drawnShapes.empty();
  if (drawn && patch >= drawnShapes.size())
    throw Error(std::string(__FILE__) +
                ": referenceCullCode needs one drawn-triangle shape per "
                "patch, got " +
                std::to_string(drawnShapes.size()) + " for " +
                std::to_string(patches.patchCount()) + " patches");
  if (bezier && method == BackPatchMethod::TangentPlane) {
    double clipMargin = 0.0;
    if (drawn && view.eye)
      clipMargin = std::abs(homogeneousEye(view.viewProj).w) *
                   tangentPlaneDrawnMargin(patches.controlPoints(patch), *view.eye,
                                           drawnShapes[patch], snap);
    if (drawn && !view.eye) clipMargin = std::numeric_limits<double>::infinity();
    return uint32_t(
        tangentPlaneTest(patches.controlPoints(patch), view.viewProj, view.eyeSign, clipMargin)
            .verdict);
  }
  if (patch >= cones.size())
    throw Error(std::string(__FILE__) + ": referenceCullCode needs buildPatchCones(patches, " +
                toString(method) + ") with one cone per patch, got " +
                std::to_string(cones.size()) + " for " + std::to_string(patches.patchCount()) +
                " patches");
  const ConeOfNormals& cone = cones[patch];
  if (!cone.valid) return uint32_t(cone.reason);
  if (!view.eye) return uint32_t(BackPatchVerdict::NoFiniteEye);
  const BackPatchResult surface = testConeOfNormals(cone, *view.eye);
  if (!drawn || !surface.culled) return uint32_t(surface.verdict);
  if (!bezier) return uint32_t(BackPatchVerdict::DrawnTriangles);
  const ConeOfNormals wide =
      widenCone(cone, patches.controlPoints(patch), *view.eye, drawnShapes[patch], snap);
  if (!wide.valid) return uint32_t(BackPatchVerdict::DrawnTriangles);
  return testConeOfNormals(wide, *view.eye).culled ? uint32_t(BackPatchVerdict::BackFacing)
                                                   : uint32_t(BackPatchVerdict::DrawnTriangles);
}

// boundVerdict, then drawn_triangle_set.h's listed triangles for a patch (Bézier or Gregory)
// the worst-case bound keeps.
uint32_t backPatchVerdict(const PatchSet& patches, uint32_t patch, const CullView& view,
                          BackPatchMethod method, std::span<const ConeOfNormals> cones,
                          const CullTests& tests) {
  const uint32_t v =
      boundVerdict(patches, patch, view, method, cones, tests.drawnShapes, tests.snapPerDistance);
  if (v != uint32_t(BackPatchVerdict::DrawnTriangles) || !view.eye ||
      !tests.drawnShapes[patch].exactLevels)
    return v;
  const QuadTessLevels& levels = tests.drawnShapes[patch].levels;
  double maxOuter = 0.0;
  for (int e = 0; e < 4; ++e)
    maxOuter =
        std::max(maxOuter, std::max(1.0, std::ceil(levels.lo[e])) +
                               (levels.hi[e] > 0.0 ? std::max(1.0, std::ceil(levels.hi[e])) : 0.0));
  if (!tests.drawnEnumerate && !(maxOuter <= double(tests.drawnListLevel))) return v;
  return drawnTrianglesFaceAway(patches.controlPoints(patch), tests.drawnShapes[patch].levels,
                                *view.eye, tests.snapPerDistance)
             ? uint32_t(BackPatchVerdict::BackFacing)
             : v;
}

uint32_t withField(uint32_t code, uint32_t shift, uint32_t width, uint32_t value) {
  const uint32_t mask = ((1u << width) - 1u) << shift;
  return (code & ~mask) | ((value << shift) & mask);
}

}  // namespace

uint32_t referenceCullCode(const PatchSet& patches, uint32_t patch, const CullView& view,
                           const CullTests& tests, std::span<const ConeOfNormals> cones) {
  uint32_t code = sh::kResultInitial;
  if (tests.frustum) {
    const FrustumResult f = frustumTest(patches.controlPoints(patch), view.viewProj);
    const uint32_t field = !f.finite  ? sh::kFrustumNonFinite
                           : f.culled ? f.plane
                                      : sh::kFrustumInside;
    code = withField(code, sh::kResultShiftFrustum, 4, field);
    if (f.culled) return withField(code, 0, 4, sh::kStageFrustum);
  }
  if (tests.backPatch != BackPatchMethod::None) {
    const uint32_t v = backPatchVerdict(patches, patch, view, tests.backPatch, cones, tests);
    code = withField(code, sh::kResultShiftBackPatch, 8, v);
    if (v == sh::kVerdictBackFacing) return withField(code, 0, 4, sh::kStageBackPatch);
  }
  return code;
}

std::vector<uint32_t> referenceCull(const PatchSet& patches, const CullView& view,
                                    const CullTests& tests, std::span<const ConeOfNormals> cones) {
  std::vector<uint32_t> codes(patches.patchCount());
  for (uint32_t p = 0; p < patches.patchCount(); ++p)
    codes[p] = referenceCullCode(patches, p, view, tests, cones);
  return codes;
}

std::string describe(CullCode code) {
  static const char* const kPlanes[] = {"left", "right", "bottom", "top", "near", "far"};
  std::string s = code.culled() ? "culled" : "kept";
  if (code.stage() == sh::kStageFrustum) return s + ": frustum " + kPlanes[code.frustum()];
  if (code.stage() == sh::kStageBackPatch) return s + ": back-patch back-facing";
  if (code.stage() == sh::kStageOcclusion) return s + ": occluded";
  if (code.frustum() == sh::kFrustumNonFinite) s += ": frustum non-finite";
  if (code.backPatch() != 0xFFu)
    s += std::string(": back-patch ") + toString(static_cast<BackPatchVerdict>(code.backPatch()));
  if (code.occlusion() != 0xFFu) s += ": occlusion " + std::to_string(code.occlusion());
  return s;
}

}  // namespace osd_cull::bound
