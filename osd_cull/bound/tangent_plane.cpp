#include "osd_cull/bound/tangent_plane.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/tangent_plane_table.h"
#include "osd_cull/error.h"

#include <cmath>
#include <string>
#include <vector>

namespace osd_cull::bound {
namespace {

void requireBezier(std::span<const glm::dvec3> bezier) {
  if (bezier.size() != 16)
    throw Error(std::string(__FILE__) + ":" + std::to_string(__LINE__) +
                ": a bicubic Bézier patch has 16 control points, got " +
                std::to_string(bezier.size()));
}

TangentPlaneControlPlanes accumulate(std::span<const glm::dvec3> bezier, const glm::dmat4& viewProj,
                                     std::span<const TangentPlaneTerm> terms) {
  requireBezier(bezier);
  std::array<glm::dvec4, 16> clip, absClip;
  for (size_t i = 0; i < 16; ++i) {
    clip[i] = clipPoint(bezier[i], viewProj);
    absClip[i] = absClipPoint(bezier[i], viewProj);
  }
  TangentPlaneControlPlanes planes;
  for (const TangentPlaneTerm& t : terms) {
    // cross4 of two equal points is exactly zero; skipping keeps collapsed edges exact.
    if (bezier[t.j] == bezier[t.k] || bezier[t.k] == bezier[t.l] || bezier[t.j] == bezier[t.l])
      continue;
    planes.z[t.target] += t.weight * cross4Z(clip[t.j], clip[t.k], clip[t.l]);
    planes.bound[t.target] +=
        std::abs(t.weight) * cross4ZBound(absClip[t.j], absClip[t.k], absClip[t.l]);
  }
  return planes;
}

}  // namespace

TangentPlaneControlPlanes tangentPlaneControlPlanes(std::span<const glm::dvec3> bezier,
                                                    const glm::dmat4& viewProj) {
  return accumulate(bezier, viewProj, tangentPlaneTerms());
}

TangentPlaneControlPlanes tangentPlaneControlPlanesParallel(std::span<const glm::dvec3> bezier,
                                                            const glm::dmat4& viewProj) {
  // Thread by thread, each walking k = thread, thread + 16, ... as in §6.
  const auto terms = tangentPlaneParallelTerms();
  std::vector<TangentPlaneTerm> ordered;
  ordered.reserve(terms.size());
  for (size_t thread = 0; thread < kTangentPlaneThreads; ++thread)
    for (size_t k = thread; k < terms.size(); k += kTangentPlaneThreads)
      ordered.push_back(terms[k]);
  return accumulate(bezier, viewProj, ordered);
}

TangentPlaneResult classifyTangentPlane(const TangentPlaneControlPlanes& planes, double eyeSign,
                                        double drawnMargin) {
  TangentPlaneResult r;
  uint32_t pcntDrawn = 0;
  for (size_t i = 0; i < 64; ++i) {
    if (!std::isfinite(planes.z[i]) || !std::isfinite(planes.bound[i])) {
      r.verdict = BackPatchVerdict::NonFinite;
      return r;
    }
  }
  if (eyeSign == 0.0) {
    r.verdict = BackPatchVerdict::NoFiniteEye;
    return r;
  }
  for (size_t i = 0; i < 64; ++i) {
    const double s = eyeSign * planes.z[i];
    const double margin = kRelativeMargin * planes.bound[i];
    if (s + margin > 0.0) ++r.pcnt;
    if (s + margin + drawnMargin > 0.0) ++pcntDrawn;
    if (s - margin < 0.0) ++r.ncnt;
  }
  if (r.pcnt == 0 && pcntDrawn > 0) {
    r.verdict = BackPatchVerdict::DrawnTriangles;
    return r;
  }
  // §4.2 DVis with §7's Pcnt rule. A patch with every plane exactly zero (all terms
  // skipped: the patch is a point) has no front-facing point and is culled.
  if (r.pcnt == 0) {
    r.culled = true;
    r.verdict = BackPatchVerdict::BackFacing;
  } else if (r.ncnt == 0) {
    r.verdict = BackPatchVerdict::FrontFacing;
  } else {
    r.verdict = BackPatchVerdict::Silhouette;
  }
  return r;
}

TangentPlaneResult tangentPlaneTest(std::span<const glm::dvec3> bezier, const glm::dmat4& viewProj,
                                    double eyeSign, double drawnMargin) {
  requireBezier(bezier);
  if (!allFinite(bezier) || !allFinite(viewProj) || !std::isfinite(eyeSign) ||
      !std::isfinite(drawnMargin))
    return {};
  return classifyTangentPlane(tangentPlaneControlPlanes(bezier, viewProj), eyeSign, drawnMargin);
}

}  // namespace osd_cull::bound
