#include "osd_cull/bound/patch_eval.h"

#include "osd_cull/error.h"

#include <string>

namespace osd_cull::bound {
namespace {

void requireSize(std::span<const glm::dvec3> points, size_t expected, const char* what) {
  if (points.size() != expected)
    throw Error(std::string(__FILE__) + ": a " + what + " patch has " + std::to_string(expected) +
                " control points, got " + std::to_string(points.size()));
}

}  // namespace

PatchSample evaluateBezier(std::span<const glm::dvec3> bezier, double u, double v) {
  requireSize(bezier, kBezierPoints, "bicubic Bézier");
  return osd_cull::evaluateBezier(bezier.first<kBezierPoints>(), u, v);
}

std::array<glm::dvec3, 16> gregoryBezierNet(std::span<const glm::dvec3> gregory, double u,
                                            double v) {
  requireSize(gregory, kGregoryPoints, "Gregory");
  return osd_cull::gregoryToBezierAt(gregory.first<kGregoryPoints>(), u, v);
}

PatchSample evaluateGregory(std::span<const glm::dvec3> gregory, double u, double v) {
  requireSize(gregory, kGregoryPoints, "Gregory");
  return osd_cull::evaluateGregoryExact(gregory.first<kGregoryPoints>(), u, v);
}

}  // namespace osd_cull::bound
