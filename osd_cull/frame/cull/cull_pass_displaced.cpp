#include "osd_cull/frame/cull/cull_pass_displaced.h"

#include "osd_cull/bound/frustum.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"

#include <cmath>
#include <limits>
#include <string>

namespace osd_cull::frame {
namespace {

float roundOutward(double v, bool up) {
  float f = static_cast<float>(v);
  const float toward = up ? std::numeric_limits<float>::max() : -std::numeric_limits<float>::max();
  if (up ? static_cast<double>(f) < v : static_cast<double>(f) > v) f = std::nextafter(f, toward);
  return f;
}

}  // namespace

std::vector<float> packDisplacedPatches(std::span<const bound::DisplacedPatch> patches) {
  constexpr size_t kFloats = 4 * shader::kConeVec4s;
  std::vector<float> out(std::max<size_t>(1, patches.size()) * kFloats, 0.0f);
  for (size_t p = 0; p < patches.size(); ++p) {
    const bound::DisplacedPatch& d = patches[p];
    float* o = &out[kFloats * p];
    o[0] = roundOutward(d.range.dmin, false);
    o[1] = roundOutward(d.range.dmax, true);
    o[2] = static_cast<float>(std::cos(d.cone.angle));  // rounding: kDeltaSlack of the kernel
    o[3] = static_cast<float>(std::sin(d.cone.angle));
    o[4] = static_cast<float>(d.cone.axis.x);
    o[5] = static_cast<float>(d.cone.axis.y);
    o[6] = static_cast<float>(d.cone.axis.z);
    o[7] = d.cone.valid ? 1.0f : 0.0f;
  }
  return out;
}

std::vector<bound::DisplacedPatch> unpackDisplacedPatches(std::span<const float> data,
                                                          uint32_t patchCount) {
  constexpr size_t kFloats = 4 * shader::kConeVec4s;
  if (data.size() < size_t{patchCount} * kFloats)
    throw Error("unpackDisplacedPatches: " + std::to_string(data.size()) + " floats for " +
                std::to_string(patchCount) + " patches");
  std::vector<bound::DisplacedPatch> out(patchCount);
  for (uint32_t p = 0; p < patchCount; ++p) {
    const float* f = &data[kFloats * p];
    bound::DisplacedPatch& d = out[p];
    d.range = {double(f[0]), double(f[1])};
    d.cone.sinAngle = double(f[3]);
    d.cone.angle = std::atan2(double(f[3]), double(f[2]));
    d.cone.axis = {double(f[4]), double(f[5]), double(f[6])};
    d.cone.valid = f[7] != 0.0f;
    d.cone.reason = bound::BackPatchVerdict::BackFacing;
    if (!d.cone.valid) d.cone = {};
  }
  return out;
}

std::vector<float> packDisplacementRanges(std::span<const bound::DisplacementRange> ranges) {
  std::vector<float> out(std::max<size_t>(1, ranges.size()) * 2, 0.0f);
  for (size_t p = 0; p < ranges.size(); ++p) {
    out[2 * p] = roundOutward(ranges[p].dmin, false);
    out[2 * p + 1] = roundOutward(ranges[p].dmax, true);
  }
  return out;
}

shader::DisplacedView displacedView(const Camera& camera) {
  shader::DisplacedView v{};
  v.view = glm::mat4(camera.view);
  v.projection = glm::mat4(camera.projection);
  v.perspective = bound::isCameraAlignedPerspective(camera.projection) ? 1u : 0u;
  return v;
}

std::vector<uint32_t> displacedReferenceCull(const PatchSet& host, const CullPass& pass,
                                             const Camera& camera, const bound::HiZPyramid* hiz,
                                             bound::HiZLookup lookup) {
  return displacedReferenceCull(host, pass, pass.displacedPatches(), camera, hiz, lookup);
}

std::vector<uint32_t> displacedReferenceCull(const PatchSet& host, const CullPass& pass,
                                             std::span<const bound::DisplacedPatch> data,
                                             const Camera& camera, const bound::HiZPyramid* hiz,
                                             bound::HiZLookup lookup) {
  if (data.size() != host.patchCount())
    throw Error("displacedReferenceCull: displaced data for " + std::to_string(data.size()) +
                " patches, the mesh has " + std::to_string(host.patchCount()));
  const CullMethod::Displaced kernel = pass.displacedKernel();
  std::vector<uint32_t> codes(host.patchCount(), shader::kResultInitial);
  for (uint32_t p = 0; p < host.patchCount(); ++p) {
    const bound::DisplacedBound b =
        bound::displacedBound(host.controlPoints(p), data[p], kernel.extension, kernel.box,
                              camera.view, camera.projection);
    if (!b.finite) continue;
    uint32_t& code = codes[p];
    if (pass.settings().frustum) {
      const bound::FrustumResult f = bound::frustumTest(b.corners, b.toClip);
      code = (code & ~0xF0u) | (f.plane << shader::kResultShiftFrustum);
      if (f.culled) {
        code = (code & ~0xFu) | shader::kStageFrustum;
        continue;
      }
    }
    // The displaced draw clamps its fragments' depth to the nearest depth of the boxes
    // around the control points (patch.tesc): their nearest depth bounds the fragments.
    if (!hiz) continue;
    const std::vector<glm::dvec3> reach =
        bound::displacedReachCorners(host.controlPoints(p), data[p].range.maxAbs());
    const bound::HiZDepthPoints depth{reach, camera.viewProjection()};
    if (bound::hizOcclusionTest(b.corners, b.toClip, *hiz, lookup, &depth).culled)
      code = (code & ~0xFu) | shader::kStageOcclusion;
  }
  return codes;
}

}  // namespace osd_cull::frame
