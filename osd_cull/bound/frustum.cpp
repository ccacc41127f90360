#include "osd_cull/bound/frustum.h"

#include "osd_cull/bound/clip_space.h"

#include <glm/common.hpp>

#include <bit>
#include <cmath>
#include <limits>

namespace osd_cull::bound {
namespace {

bool finite4(const glm::dvec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

}  // namespace

ClipBounds clipBounds(std::span<const glm::dvec3> points, const glm::dmat4& viewProj) {
  ClipBounds b;
  if (points.empty() || !allFinite(points) || !allFinite(viewProj)) return b;
  constexpr double inf = std::numeric_limits<double>::infinity();
  b.finite = true;
  b.behindEye = false;
  b.outsideAll = (1u << kFrustumPlaneCount) - 1;
  b.ndcMin = glm::dvec3(inf);
  b.ndcMax = glm::dvec3(-inf);
  for (const glm::dvec3& p : points) {
    const glm::dvec4 c = clipPoint(p, viewProj);
    const glm::dvec4 m = absClipPoint(p, viewProj);  // bounds |c| and its rounding
    if (!finite4(c) || !finite4(m)) {
      b = ClipBounds{};
      return b;
    }
    // Signed distances of the six planes (inside >= 0) and the magnitudes behind them.
    const double dist[kFrustumPlaneCount] = {c.x + c.w, c.w - c.x, c.y + c.w,
                                             c.w - c.y, c.z,       c.w - c.z};
    const double mag[kFrustumPlaneCount] = {m.x + m.w, m.w + m.x, m.y + m.w,
                                            m.w + m.y, m.z,       m.w + m.z};
    uint32_t outside = 0, maybeOutside = 0;
    for (uint32_t plane = 0; plane < kFrustumPlaneCount; ++plane) {
      const double margin = kRelativeMargin * mag[plane];
      if (dist[plane] < -margin) outside |= 1u << plane;
      if (dist[plane] < margin) maybeOutside |= 1u << plane;
    }
    b.outsideAll &= outside;
    b.outsideAny |= maybeOutside;
    if (!(c.w > kRelativeMargin * m.w)) {
      b.behindEye = true;
      continue;
    }
    // x/w with x and w each off by at most margin * magnitude: widen by the worst case.
    const glm::dvec3 ndc = glm::dvec3(c) / c.w;
    const glm::dvec3 err =
        kRelativeMargin * (glm::dvec3(m) + glm::abs(ndc) * m.w) / (c.w - kRelativeMargin * m.w);
    b.ndcMin = glm::min(b.ndcMin, ndc - err);
    b.ndcMax = glm::max(b.ndcMax, ndc + err);
  }
  b.hasNdcBox = !b.behindEye;
  if (!b.hasNdcBox) b.ndcMin = b.ndcMax = glm::dvec3(0.0);
  return b;
}

FrustumResult frustumTest(std::span<const glm::dvec3> points, const glm::dmat4& viewProj) {
  const ClipBounds b = clipBounds(points, viewProj);
  FrustumResult r;
  r.finite = b.finite;
  if (b.finite && b.outsideAll != 0) {
    r.culled = true;
    r.plane = static_cast<uint32_t>(std::countr_zero(b.outsideAll));
  }
  return r;
}

}  // namespace osd_cull::bound
